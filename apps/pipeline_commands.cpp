// radkit formfactors, radkit solvers and radkit run: one pipeline, three selections of output.
#include <cstdio>
#include <memory>

#include "apps/common.h"
#include "apps/console.h"
#include "apps/hierarchical_command.h"
#include "apps/job_summary.h"
#include "apps/options.h"
#include "job/job.h"
#include "job/report.h"
#include "radiosity/presets.h"
#include "solvers/registry.h"

namespace radkit::app {

namespace {

enum class Job { FormFactors, Solvers, Run };

struct PipelineCommand {
  Job job = Job::Run;
  MeshOptions mesh;
  FormFactorOptions ff;
  SolverOptions solver;
  std::string out;
  bool noRender = false, photometric = false, smooth = false, writeMatrix = false;
  int imageWidth = 512, imageHeight = 512;
  std::string preset, camera;
  bool adaptive = false;
  AdaptiveSettings adaptiveSettings;
  HierarchicalOptions hierarchical;
  /// Options a preset must not override when the user gave them.
  std::vector<CLI::Option*> meshFlags, methodFlag, samplesFlag, tolFlag, maxIterationsFlag,
      memoryBudgetFlag;
};

bool given(const std::vector<CLI::Option*>& flags) {
  for (const CLI::Option* o : flags)
    if (o && o->count() > 0) return true;
  return false;
}

/// The library job the options describe: a setting a preset or the method would choose is
/// passed on only when its option was given.
JobSettings jobSettings(const PipelineCommand& cmd) {
  JobSettings s;
  s.kind = cmd.job == Job::Run       ? JobKind::Run
           : cmd.job == Job::Solvers ? JobKind::Solvers
                                     : JobKind::FormFactors;
  s.scene = cmd.mesh.scene;
  s.load = cmd.mesh.load;
  s.camera = cmd.camera;
  s.out = cmd.out;
  s.preset = cmd.preset;
  if (cmd.hierarchical.methodOption && cmd.hierarchical.methodOption->count() > 0)
    s.method =
        cmd.hierarchical.method == "hierarchical" ? JobMethod::Hierarchical : JobMethod::Dense;
  if (given(cmd.meshFlags)) s.mesh = SubdivisionSettings{cmd.mesh.maxArea, cmd.mesh.patches};
  if (given(cmd.methodFlag)) s.formFactorMethod = cmd.ff.settings.method;
  if (given(cmd.samplesFlag)) s.formFactorSamples = cmd.ff.settings.samples;
  if (given(cmd.tolFlag)) s.tolerance = cmd.solver.stopping.tolerance;
  if (given(cmd.maxIterationsFlag)) s.maxIterations = cmd.solver.stopping.maxIterations;
  if (given(cmd.memoryBudgetFlag)) s.memoryBudget = cmd.ff.settings.memoryBudget;
  s.seed = cmd.ff.settings.seed;
  s.formFactors = cmd.ff.settings;
  s.solvers = cmd.solver.choices;
  s.stopping = cmd.solver.stopping;
  if (cmd.adaptive) s.adaptive = cmd.adaptiveSettings;
  s.hierarchical = cmd.hierarchical.settings;
  s.checkLinks = cmd.hierarchical.checkLinks;
  s.linkColour =
      cmd.hierarchical.linkColour == "power" ? LinkColour::Power : LinkColour::FormFactor;
  s.writeMatrix = cmd.writeMatrix;
  s.render = !cmd.noRender;
  s.photometric = cmd.photometric;
  s.smooth = cmd.smooth;
  s.imageWidth = cmd.imageWidth, s.imageHeight = cmd.imageHeight;
  return s;
}

/// The option combinations the library would refuse, refused in the options' own words.
void checkCombinations(PipelineCommand& cmd) {
  if (!cmd.preset.empty() && presetIsHierarchical(cmd.preset)) {
    // A preset that picks the hierarchical method: only `run` has it, and a --method given
    // explicitly must agree (explicit options win, so a disagreement has no right answer).
    const std::string flag = "--preset " + cmd.preset;
    if (cmd.job != Job::Run)
      throw CLI::ValidationError(flag,
                                 "runs hierarchical radiosity, which only `radkit run` "
                                 "does; use a dense preset (draft, balanced, reference)");
    if (cmd.hierarchical.methodOption && cmd.hierarchical.methodOption->count() > 0 &&
        cmd.hierarchical.method != "hierarchical")
      throw CLI::ValidationError(flag, "runs --method hierarchical, not --method " +
                                           cmd.hierarchical.method +
                                           "; drop one of the two, or use a dense preset "
                                           "(draft, balanced, reference)");
    cmd.hierarchical.method = "hierarchical";
  }
  if (cmd.job == Job::Run && cmd.hierarchical.method == "hierarchical") {
    finishHierarchicalOptions(cmd.hierarchical);
    std::vector<std::string> refused;
    for (const CLI::Option* o : cmd.hierarchical.denseOnly)
      if (o && o->count() > 0) refused.push_back(o->get_name());
    if (!cmd.preset.empty() && !presetIsHierarchical(cmd.preset)) refused.push_back("--preset");
    if (cmd.adaptive) refused.push_back("--adaptive");
    if (!refused.empty()) {
      std::string list;
      for (const std::string& name : refused) list += (list.empty() ? "" : ", ") + name;
      throw CLI::ValidationError(
          "--method hierarchical",
          list +
              " belong to the dense method; the hierarchy sets its own elements and links. "
              "Use --epsilon, --min-area and --hr-rays instead");
    }
    return;
  }
  if (cmd.hierarchical.checkLinks > 0)
    throw CLI::ValidationError("--check-links",
                               "checks the links of --method hierarchical; a dense run has none");
}

JobResult runCommand(PipelineCommand& cmd) {
  cmd.ff.finish();
  if (cmd.job != Job::FormFactors) cmd.solver.finish();
  if (cmd.mesh.scene.empty()) cmd.mesh.scene = defaultScenePath();
  checkCombinations(cmd);
  Progress progress;
  const PipelineLog log = consoleLog(progress);
  try {
    JobResult result = radkit::runJob(jobSettings(cmd), log);
    progress.finish();
    if (result.hierarchical)
      printHierarchicalSummary(result, cmd.hierarchical.settings.epsilon, cmd.photometric);
    else
      printDenseSummary(result, cmd.writeMatrix, cmd.photometric);
    return result;
  } catch (...) {
    progress.finish();
    throw;
  }
}

CLI::App* addPipelineCommand(CLI::App& app, Job job, const char* name, const std::string& help) {
  auto cmd = std::make_shared<PipelineCommand>();
  cmd->job = job;
  CLI::App* sub = app.add_subcommand(name, help);
  addMeshOptions(*sub, cmd->mesh, job != Job::Run);
  addFormFactorOptions(*sub, cmd->ff);
  std::string presets;
  for (const std::string& preset : presetNames()) presets += "\n  " + describePreset(preset);
  sub->add_option("--preset", cmd->preset,
                  "Speed-accuracy preset; options given explicitly win:" + presets)
      ->check(CLI::IsMember(presetNames()));
  cmd->meshFlags = {sub->get_option("--patches"), sub->get_option("--max-area")};
  cmd->methodFlag = {sub->get_option("--ff")};
  cmd->samplesFlag = {sub->get_option("--ff-samples")};
  cmd->memoryBudgetFlag = {sub->get_option("--memory-budget")};
  // `solvers` runs past 1e-9 (its default in the library), shown in --help.
  if (job == Job::Solvers) cmd->solver.stopping.tolerance = 1e-10;
  if (job != Job::FormFactors) {
    std::string every;  // `solvers` compares every registered solver by default
    for (const std::string& solver : solverNames()) every += (every.empty() ? "" : ",") + solver;
    addSolverOptions(*sub, cmd->solver, job == Job::Solvers ? every : "gauss-seidel");
    cmd->tolFlag = {sub->get_option("--tol")};
    cmd->maxIterationsFlag = {sub->get_option("--max-iterations")};
  }
  if (job != Job::Solvers)
    sub->add_flag("--write-matrix", cmd->writeMatrix,
                  "Also write F as Matrix Market text, formfactors.mtx (about 25 bytes per "
                  "non-zero; the viewer "
                  "needs only formfactors.bin, written always)");
  auto* out = sub->add_option(
      "--out", cmd->out,
      job == Job::Run ? "Output folder (default out/<scene name>)" : "Output folder");
  if (job != Job::Run) out->required();
  if (job == Job::Run) {
    sub->add_flag("--no-render", cmd->noRender, "Skip render.png");
    sub->add_flag("--photometric", cmd->photometric,
                  "Add luminance (cd/m²) and illuminance (lux) to surfaces.csv");
    sub->add_flag("--smooth", cmd->smooth, "Interpolate radiosity between patches in render.png");
    sub->add_flag(
        "--adaptive", cmd->adaptive,
        "Refine patches where radiosity changes most between neighbours and across shadow "
        "boundaries, "
        "re-solve, repeat (starts from --patches/--max-area, else a quarter of the budget; "
        "docs/speed-vs-accuracy.md)");
    sub->add_option("--adaptive-max-patches", cmd->adaptiveSettings.maxPatches,
                    "Adaptive: patch budget")
        ->check(CLI::Range(1, int(kMaxPatches)))
        ->capture_default_str();
    sub->add_option("--adaptive-tol", cmd->adaptiveSettings.tolerance,
                    "Adaptive: stop when no patch's indicator exceeds this")
        ->check(FinitePositive)
        ->capture_default_str();
    sub->add_option("--adaptive-rounds", cmd->adaptiveSettings.maxRounds,
                    "Adaptive: refine-and-solve rounds at most")
        ->check(CLI::NonNegativeNumber)
        ->capture_default_str();
    addCameraOption(*sub, cmd->camera);
    addImageSizeOptions(*sub, cmd->imageWidth, cmd->imageHeight, "render.png");
    addHierarchicalOptions(*sub, cmd->hierarchical);
    cmd->hierarchical.denseOnly = {
        sub->get_option("--patches"),    sub->get_option("--max-area"),
        sub->get_option("--ff"),         sub->get_option("--ff-samples"),
        sub->get_option("--ff-enforce"), sub->get_option("--ff-storage"),
        sub->get_option("--solvers"),    sub->get_option("--write-matrix")};
  }
  sub->callback([cmd] { runCommand(*cmd); });
  return sub;
}

}  // namespace

std::string runDefaultJob(const std::string& scenePath, const std::string& outDir) {
  PipelineCommand cmd;
  cmd.job = Job::Run;
  cmd.mesh.scene = scenePath;
  cmd.out = outDir;
  return runCommand(cmd).out;
}

void addPipelineCommands(CLI::App& app) {
  addPipelineCommand(
      app, Job::FormFactors, "formfactors",
      "Compute the form-factor matrix: formfactors.bin (and with --write-matrix formfactors.mtx), "
      "surface_formfactors.csv, formfactors.png, report.json");
  addPipelineCommand(app, Job::Solvers, "solvers",
                     "Build F once and run several solvers from the same start: "
                     "convergence.csv/.png, solution-<solver>.csv");
  addPipelineCommand(
      app, Job::Run, "run",
      "The main job: mesh, form factors, solve, and every output (default scene: the Cornell box, "
      "default mesh: about " +
          std::to_string(kDefaultRunPatches) + " patches)");
}

}  // namespace radkit::app
