#include "job/job.h"

#include <algorithm>
#include <chrono>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "job/job_parts.h"
#include "radiosity/presets.h"
#include "render/camera.h"
#include "solvers/registry.h"
#include "util/errors.h"
#include "util/format.h"
#include "util/params.h"
#include "util/setting_names.h"

namespace radkit {

const char* jobKindName(JobKind kind) {
  return kind == JobKind::Run ? "run" : kind == JobKind::Solvers ? "solvers" : "formfactors";
}

JobSettings resolveJobSettings(const JobSettings& given) {
  JobSettings s = given;
  if (s.scene.empty())
    throw std::invalid_argument("no scene: give the scene file to run (a .json or .obj)");
  const bool hierarchicalPreset = !s.preset.empty() && presetIsHierarchical(s.preset);
  if (hierarchicalPreset) {
    if (s.kind != JobKind::Run)
      throw std::invalid_argument("preset \"" + s.preset +
                                  "\" runs hierarchical radiosity, which only a run does; use "
                                  "a dense preset (" +
                                  densePresetNames() + ")");
    if (s.method && *s.method != JobMethod::Hierarchical)
      throw std::invalid_argument("preset \"" + s.preset +
                                  "\" runs the hierarchical method, not the dense one; drop "
                                  "one of the two, or use a dense preset");
  }
  if (!s.method) s.method = hierarchicalPreset ? JobMethod::Hierarchical : JobMethod::Dense;

  if (*s.method == JobMethod::Hierarchical) {
    if (s.kind != JobKind::Run)
      throw std::invalid_argument(
          std::string("the hierarchical method writes a run's outputs; a ") + jobKindName(s.kind) +
          " job needs the dense method's F");
    if (!s.preset.empty() && !hierarchicalPreset)
      throw std::invalid_argument("preset \"" + s.preset +
                                  "\" belongs to the dense method; the hierarchy sets its own "
                                  "elements and links");
    if (s.adaptive)
      throw std::invalid_argument(
          "adaptive refinement belongs to the dense method; the hierarchy refines its own "
          "elements (lower its epsilon or its smallest area instead)");
    HierarchicalSettings& h = s.hierarchical;
    h.seed = s.seed;
    if (s.memoryBudget) h.memoryBudget = *s.memoryBudget;
    const SolverSettings defaults;
    h.stopping = s.stopping;
    h.stopping.tolerance = s.tolerance.value_or(defaults.tolerance);
    // The dense default (10⁸ steps) is no bound on a gather's sweeps: the hierarchy has its own.
    h.stopping.maxIterations = s.maxIterations.value_or(kDefaultHierarchicalSweeps);
    h.keepGatherArrays = s.checkLinks > 0;
    validateHierarchicalSettings(h);
    s.memoryBudget = h.memoryBudget;
    s.maxIterations = h.stopping.maxIterations;
    s.tolerance = h.stopping.tolerance;
    return s;
  }

  if (s.checkLinks > 0)
    throw std::invalid_argument(
        "checking links is for the hierarchical method; a dense run has none");
  if (s.adaptive && s.kind != JobKind::Run)
    throw std::invalid_argument("adaptive refinement is a run's; a " +
                                std::string(jobKindName(s.kind)) + " job keeps its mesh");
  // The preset first, then what was given, then each setting's own default.
  PipelineSettings preset;
  if (!s.preset.empty()) applyPreset(s.preset, preset);
  if (!s.mesh) {
    if (!s.preset.empty())
      s.mesh = preset.mesh;
    else if (s.kind == JobKind::Run)
      // Adaptive refinement starts coarse, at a quarter of its budget, so it has room to refine.
      s.mesh = SubdivisionSettings{
          0, s.adaptive ? std::max(1, s.adaptive->maxPatches / 4) : kDefaultRunPatches};
    else
      s.mesh = SubdivisionSettings{};
  }
  const bool methodGiven = s.formFactorMethod.has_value();
  if (methodGiven && s.formFactorMethod->find(':') != std::string::npos) {
    // "name:key=value;..." carries the method's own parameters
    const PluginChoice choice = splitPluginChoice(*s.formFactorMethod);
    s.formFactorMethod = choice.name;
    s.formFactors.parameters = choice.parameters;
  }
  if (!s.formFactorMethod)
    s.formFactorMethod = s.preset.empty() ? FormFactorSettings{}.method : preset.formFactors.method;
  formFactorTraits(*s.formFactorMethod);  // an unknown name is refused before any work
  // Each method has its own K; a preset's K is for its own method.
  if (!s.formFactorSamples)
    s.formFactorSamples = !s.preset.empty() && !methodGiven
                              ? preset.formFactors.samples
                              : defaultFormFactorSamples(*s.formFactorMethod);
  if (!s.tolerance)
    s.tolerance = !s.preset.empty() ? preset.stopping.tolerance
                  : s.kind == JobKind::Solvers
                      // past 1e-9, so report.json's table of iterations to 1e-3, 1e-6 and
                      // 1e-9 is whole
                      ? 1e-10
                      : SolverSettings{}.tolerance;
  if (!s.maxIterations) s.maxIterations = SolverSettings{}.maxIterations;
  if (!s.memoryBudget) s.memoryBudget = FormFactorSettings{}.memoryBudget;
  s.formFactors.method = *s.formFactorMethod;
  s.formFactors.samples = *s.formFactorSamples;
  s.formFactors.memoryBudget = *s.memoryBudget;
  s.formFactors.seed = s.seed;
  s.stopping.tolerance = *s.tolerance;
  s.stopping.maxIterations = *s.maxIterations;
  validateFormFactorSettings(s.formFactors);
  if (s.kind == JobKind::FormFactors) {
    s.solvers.clear();
  } else if (s.solvers.empty()) {
    if (s.kind == JobKind::Solvers) {
      for (const std::string& name : solverNames()) s.solvers.push_back({name, ""});
    } else {
      s.solvers.push_back(SolverChoice{});
    }
  }
  return s;
}

std::string defaultOutFolder(const std::string& sceneName) {
  std::string name;
  for (char c : sceneName)
    name += (c == '/' || c == '\\' || static_cast<unsigned char>(c) < 0x20 || c == 0x7f) ? '_' : c;
  if (!name.empty() && name[0] == '.') name[0] = '_';  // no "..", no hidden folder
  if (name.size() > 200) {  // one path component's limit is 255 bytes; keep UTF-8 whole
    name.resize(200);
    while (!name.empty() && (static_cast<unsigned char>(name.back()) & 0xC0) == 0x80)
      name.pop_back();
    if (!name.empty() && static_cast<unsigned char>(name.back()) >= 0xC0) name.pop_back();
  }
  return "out/" + (name.empty() ? std::string("scene") : name);
}

Scene loadJobScene(const std::string& path, const LoadOptions& load, const std::string& camera,
                   const PipelineLog& log, LoadReport* out) {
  // Parsed before the scene loads: a typo is refused before minutes of work.
  std::optional<Camera> given;
  if (!camera.empty()) given = parseCamera(setting("camera"), camera);
  LoadReport local;
  LoadReport& report = out ? *out : local;
  // Stages of loading that run over a second (a large mesh read and checked) show progress.
  LoadOptions options = load;
  std::string stage;
  std::chrono::steady_clock::time_point started;
  bool shown = false;
  if (!options.progress && log.progress)
    options.progress = [&](const std::string& name, double fraction) {
      const auto now = std::chrono::steady_clock::now();
      if (name != stage) {
        stage = name;
        started = now;
        shown = false;
      }
      if (!shown && now - started < std::chrono::seconds(1)) return;
      shown = true;
      log.progress(name, fraction);
    };
  Scene scene = loadScene(path, &report, options);
  if (log.message)
    for (const std::string& w : report.warnings) log.message("warning: " + w);
  if (given) scene.camera = given;
  return scene;
}

JobResult runJob(const JobSettings& given, const PipelineLog& log) {
  const auto start = std::chrono::steady_clock::now();
  const JobSettings s = resolveJobSettings(given);
  LoadReport loaded;
  Scene scene = loadJobScene(s.scene, s.load, s.camera, log, &loaded);
  if (*s.method == JobMethod::Hierarchical)
    return runHierarchicalJob(std::move(scene), loaded, s, log, start, secondsSince(start));
  return runDenseJob(std::move(scene), loaded, s, log, start);
}

JobResult runJob(Scene scene, const JobSettings& given, const PipelineLog& log,
                 const LoadReport& loaded) {
  const auto start = std::chrono::steady_clock::now();
  JobSettings named = given;
  if (named.scene.empty()) named.scene = scene.file;
  const JobSettings s = resolveJobSettings(named);
  if (!s.camera.empty()) scene.camera = parseCamera(setting("camera"), s.camera);
  if (*s.method == JobMethod::Hierarchical)
    return runHierarchicalJob(std::move(scene), loaded, s, log, start, 0);
  return runDenseJob(std::move(scene), loaded, s, log, start);
}

}  // namespace radkit
