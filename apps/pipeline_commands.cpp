// radkit formfactors, radkit solvers and radkit run: one pipeline, three selections of output.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "apps/common.h"
#include "apps/hierarchical_command.h"
#include "apps/options.h"
#include "apps/report.h"
#include "output/run_files.h"
#include "radiosity/adaptive.h"
#include "radiosity/form_factor_heat_map.h"
#include "radiosity/presets.h"
#include "radiosity/surface_form_factors.h"
#include "render/radiosity_image.h"
#include "solvers/registry.h"
#include "util/errors.h"
#include "util/output_folder.h"

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

/// The run's settings: the preset's (if any), then every option the user gave explicitly.
PipelineSettings pipelineSettings(const PipelineCommand& cmd) {
  PipelineSettings explicitSettings;
  explicitSettings.mesh = {cmd.mesh.maxArea, cmd.mesh.patches};
  explicitSettings.formFactors = cmd.ff.settings;
  explicitSettings.solvers =
      cmd.job == Job::FormFactors ? std::vector<SolverChoice>{} : cmd.solver.choices;
  explicitSettings.stopping = cmd.solver.stopping;
  // Each method has its own K; a preset's K is for its own method.
  if (!given(cmd.samplesFlag) && (cmd.preset.empty() || given(cmd.methodFlag)))
    explicitSettings.formFactors.samples =
        defaultFormFactorSamples(explicitSettings.formFactors.method);
  if (cmd.preset.empty()) return explicitSettings;
  PipelineSettings s = explicitSettings;
  applyPreset(cmd.preset, s);
  if (given(cmd.meshFlags)) s.mesh = explicitSettings.mesh;
  if (given(cmd.methodFlag)) s.formFactors.method = explicitSettings.formFactors.method;
  if (given(cmd.samplesFlag)) s.formFactors.samples = explicitSettings.formFactors.samples;
  if (given(cmd.tolFlag)) s.stopping.tolerance = explicitSettings.stopping.tolerance;
  return s;
}

/// `run`'s mesh when none is given: on the Cornell box, surface radiosities lie within 0.6 %
/// of a 32 000-patch run (docs/run.md), in about 13 s on two cores.
constexpr int kDefaultRunPatches = 4000;

/// Writes the form-factor files; returns the seconds spent on formfactors.bin and .mtx.
double writeFormFactorFiles(OutputFolder& folder, const Scene& scene, const PipelineResult& r,
                            bool matrixFile) {
  std::vector<std::string> names = surfaceNames(scene);
  const FormFactorMatrix& f = r.formFactors->matrix;
  writeSurfaceFormFactors(folder.path("surface_formfactors.csv"), r.mesh, names, f);
  HeatMapSettings heat;
  heat.title = scene.name + ": F_ij, " + std::to_string(r.mesh.size()) + " patches, " +
               r.formFactors->diagnostics.method;
  writeFormFactorHeatMap(folder.path("formfactors.png"), r.mesh, names, f, heat);
  // The viewer's matrix and row views read the compact binary, written on every run (4 bytes
  // per entry at most); the Matrix Market text (about 25 bytes per entry) only when asked.
  const auto start = std::chrono::steady_clock::now();
  writeFormFactorBinary(folder.path("formfactors.bin"), f);
  if (matrixFile)
    writeMatrixMarket(
        folder.path("formfactors.mtx"), f,
        {"radkit form factors of " + scene.file, r.formFactors->diagnostics.description,
         "row i, column j: F_ij (patch ids from 0 in patches.csv are i-1, j-1)"});
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void renderImage(OutputFolder& folder, const Scene& scene, const PipelineResult& r,
                 const PipelineCommand& cmd) {
  ImageSettings s;
  s.width = cmd.imageWidth, s.height = cmd.imageHeight;
  s.smooth = cmd.smooth;
  if (r.sky) s.background = [&](const Vec3& d) { return r.sky->radiance(d); };
  if (!writeRadiosityPng(folder.path("render.png"), scene, r.mesh, *r.rays, r.radiosity, s))
    std::fprintf(stderr, "radkit: warning: %s\n", blackPictureWarning("render.png").c_str());
}

void printSummary(const Scene& scene, const PipelineResult& r, const PipelineCommand& cmd,
                  double total, double matrixSeconds) {
  const FormFactorDiagnostics& d = r.formFactors->diagnostics;
  std::printf("\n");
  printField("scene", scene.name + " (" + scene.file + ")");
  printField("patches", std::to_string(r.mesh.size()));
  printField("form factors", d.method + ", " + d.storage + ", " + std::to_string(d.raysCast) +
                                 " rays (" + std::to_string(d.raysSaved) + " saved), " +
                                 fmt("%.3g rays/s", d.raysPerSecond));
  printField("row sums", fmt("%.6f", d.rowSumMin) + " .. " + fmt("%.6f", d.rowSumMax) +
                             ", reciprocity error " + fmt("%.2e", d.maxRelativeReciprocityError) +
                             (r.formFactorNoise > 0 ? ", gathered-light noise " +
                                                          fmt("%.2g %%", 100 * r.formFactorNoise)
                                                    : ""));
  printField("seconds",
             "mesh " + fmt("%.2f", r.seconds.mesh) + ", rays " + fmt("%.2f", r.seconds.rayScene) +
                 ", form factors " + fmt("%.2f", r.seconds.formFactors) +
                 (r.daylight ? ", daylight " + fmt("%.2f", r.seconds.daylight) : "") + ", solve " +
                 fmt("%.2f", r.seconds.solve) + ", F files " + fmt("%.2f", matrixSeconds) +
                 (cmd.writeMatrix ? " (with .mtx)" : "") + ", total " + fmt("%.2f", total));
  if (r.daylight)
    printField("daylight", r.sky->typeName() + " sky" + (r.sky->hasSun() ? " and sun" : "") +
                               ", open horizontal " +
                               fmt("%.4g lux", kLumensPerWatt * luminance(r.sky->horizontalSky() +
                                                                          r.sky->horizontalSun())) +
                               ", " + std::to_string(r.daylight->rays) + " rays, sky noise " +
                               fmt("%.2g %%", 100 * r.daylight->skyNoise));
  for (const SolveResult& s : r.solves)
    printField(s.solver, std::to_string(s.iterations) + " iterations, residual " +
                             fmt("%.2e", s.checkedResidual) + ", " + fmt("%.3f s", s.seconds) +
                             (s.converged ? "" : "  NOT CONVERGED: " + s.reason));
  if (!r.solves.empty()) printEnergyAndSurfaces(r.energy, r.surfaces, cmd.photometric);
  printField("peak memory", fmt("%.0f MiB", peakMemoryBytes() / 1048576.0));
  printField("wrote", cmd.out);
}

/// `run --method hierarchical`: the options it shares with a dense run, and a refusal of the
/// ones that only a dense run understands.
void runHierarchical(PipelineCommand& cmd) {
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
  HierarchicalJob job;
  job.scene = cmd.mesh.scene;
  job.load = cmd.mesh.load;
  job.out = cmd.out;
  job.settings = cmd.hierarchical.settings;
  job.settings.seed = cmd.ff.settings.seed;
  // Dense F's default budget is a fixed 8 GiB; the hierarchy's follows the machine.
  if (given(cmd.memoryBudgetFlag)) job.settings.memoryBudget = cmd.ff.settings.memoryBudget;
  job.settings.stopping = cmd.solver.stopping;
  // The dense default (10⁸ steps) is no bound on a gather's sweeps: the hierarchy has its own.
  if (!given(cmd.maxIterationsFlag))
    job.settings.stopping.maxIterations = kDefaultHierarchicalSweeps;
  job.linkColour =
      cmd.hierarchical.linkColour == "power" ? LinkColour::Power : LinkColour::FormFactor;
  job.noRender = cmd.noRender, job.photometric = cmd.photometric, job.smooth = cmd.smooth;
  job.imageWidth = cmd.imageWidth, job.imageHeight = cmd.imageHeight;
  job.camera = cmd.camera;
  job.checkLinks = cmd.hierarchical.checkLinks;
  job.settings.keepGatherArrays = job.checkLinks > 0;
  job.preset = cmd.preset;
  runHierarchicalJob(job);
}

/// MemoryBudgetError's message with what it leaves out: a mesh of one patch per input face
/// cannot have fewer patches (that fix is dropped), and the hierarchical method keeps no n×n
/// matrix.
std::string memoryBudgetMessage(const MemoryBudgetError& e, const Scene& scene,
                                const PipelineCommand& cmd) {
  std::size_t faces = 0;
  for (const Surface& s : scene.surfaces) faces += s.faces.size();
  const bool atFloor = std::size_t(e.patches) <= faces + faces / 20;
  // F grows with the square of the patch count: at one patch per input face it would need
  // about this much in the smallest storage.
  const double ratio = double(faces) / double(std::max(1, e.patches));
  const double atFloorBytes = double(e.smallestBytes) * ratio * ratio;
  const bool floorTooBig = !atFloor && e.budget > 0 && atFloorBytes > double(e.budget);
  std::string message = e.what();
  if (atFloor || floorTooBig) {
    const std::string fewer = kFewerPatchesFix;
    if (const std::size_t at = message.find(fewer); at != std::string::npos) {
      message.erase(at, fewer.size());
    } else if (const std::size_t last = message.find(", " + fewer.substr(0, fewer.size() - 2));
               last != std::string::npos) {
      message.erase(last, fewer.size());  // the last fix: ", use fewer ... smaller)"
    }
  }
  message += atFloor
                 ? ". The mesh is at its floor: " + std::to_string(faces) +
                       " input faces, and a patch never spans two, so fewer patches cannot help."
             : floorTooBig
                 ? ". Fewer patches cannot help enough: at the floor of " + std::to_string(faces) +
                       " patches (one per input face; a patch never spans two) F would "
                       "still need about " +
                       formatBytes(atFloorBytes) + "."
                 : ". Fewer patches help down to about " + std::to_string(faces) +
                       ", the scene's input faces (a patch never spans two).";
  if (cmd.job == Job::Run) {
    // Peak memory of `run --method hierarchical --no-render` on the shipped scenes, less
    // radkit's own 40 MiB: terrain-room.json 2.7 kB per input face (51 201 faces, 170 MiB),
    // models/spot-room.json 11.7 kB (5 870 faces, 105 MiB). A million-face terrain takes
    // 1.3 kB, so for large meshes the range errs high.
    const double base = 40.0 * 1024 * 1024;
    const double low = base + 2.7e3 * double(faces), high = base + 11.7e3 * double(faces);
    message +=
        " --method hierarchical keeps no n×n matrix: on the shipped scenes it took 40 MiB "
        "and 2.7-11.7 kB per input face, about " +
        formatBytes(low) + " to " + formatBytes(high) + " here (docs/bring-your-own-model.md)";
  }
  return message;
}

void runJob(PipelineCommand& cmd) {
  auto start = std::chrono::steady_clock::now();
  cmd.ff.finish();
  if (cmd.job != Job::FormFactors) cmd.solver.finish();
  if (cmd.mesh.scene.empty()) cmd.mesh.scene = defaultScenePath();
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
  if (cmd.job == Job::Run && cmd.hierarchical.method == "hierarchical") return runHierarchical(cmd);
  if (cmd.hierarchical.checkLinks > 0)
    throw CLI::ValidationError("--check-links",
                               "checks the links of --method hierarchical; a dense run has none");
  // Adaptive refinement starts coarse, at a quarter of its budget, so it has room to refine.
  if (cmd.job == Job::Run && cmd.preset.empty() && cmd.mesh.maxArea <= 0 && cmd.mesh.patches <= 0)
    cmd.mesh.patches =
        cmd.adaptive ? std::max(1, cmd.adaptiveSettings.maxPatches / 4) : kDefaultRunPatches;
  LoadReport loaded;
  Scene scene = loadSceneReporting(cmd.mesh.scene, cmd.mesh.load, &loaded, cmd.camera);
  addBackSides(scene);  // two-sided surfaces exchange light on both sides
  if (cmd.out.empty() && cmd.job == Job::Run)
    cmd.out = defaultOutFolder(scene.name);  // required for the others
  OutputFolder folder(cmd.out);  // refuses an --out it cannot replace before the work, not after

  PipelineSettings settings = pipelineSettings(cmd);
  Progress progress;
  PipelineLog log;
  log.progress = [&](const std::string& stage, double f) { progress(stage, f); };
  log.message = [&](const std::string& line) {
    progress.finish();
    printLogLine(line);
  };
  nlohmann::json adaptiveJson;
  PipelineResult r;
  try {  // subdivide's TooManyPatches: more patches than radkit meshes
    if (cmd.adaptive) {
      AdaptiveResult a = solveAdaptive(scene, settings, cmd.adaptiveSettings, log);
      r = std::move(a.final);
      nlohmann::json rounds = nlohmann::json::array();
      for (const AdaptiveRound& round : a.rounds)
        rounds.push_back({{"patches", round.patches},
                          {"max_indicator", round.maxIndicator},
                          {"shadow_patches", round.shadowPatches},
                          {"split", round.split}});
      adaptiveJson = {{"rounds", rounds}, {"stop_reason", a.stopReason}, {"seconds", a.seconds}};
    } else {
      r = runPipeline(scene, settings, log);
    }
  } catch (const TooManyPatches&) {
    tooManyPatches(scene, cmd.mesh);
  } catch (const MemoryBudgetError& e) {
    progress.finish();
    throw InputError(memoryBudgetMessage(e, scene, cmd));
  }
  progress.finish();
  // A run's answer must be a number: a diverged first solver leaves nothing to write.
  if (cmd.job == Job::Run && !r.solves.empty() && r.solves.front().reason.rfind("diverged", 0) == 0)
    throw std::runtime_error(r.solves.front().solver + " " + r.solves.front().reason +
                             "; nothing written");

  nlohmann::json report{{"radkit", RADKIT_VERSION},
                        {"command", cmd.job == Job::Run       ? "run"
                                    : cmd.job == Job::Solvers ? "solvers"
                                                              : "formfactors"},
                        {"scene", sceneJson(scene)},
                        {"mesh", meshJson(scene, r.mesh)},
                        {"form_factors", toJson(r.formFactors->diagnostics)},
                        {"warnings", r.warnings},
                        {"load", loadJson(loaded)}};
  if (!cmd.preset.empty())
    report["preset"] = {{"name", cmd.preset}, {"description", describePreset(cmd.preset)}};
  if (cmd.adaptive) report["adaptive"] = adaptiveJson;
  if (r.formFactorNoise > 0) report["form_factors"]["gathered_light_noise"] = r.formFactorNoise;
  writePatchesCsv(folder.path("patches.csv"), scene, r.mesh,
                  r.solves.empty() ? nullptr : &r.radiosity);
  double matrixSeconds = 0;
  if (cmd.job != Job::Solvers)
    matrixSeconds = writeFormFactorFiles(folder, scene, r, cmd.writeMatrix);
  if (!r.solves.empty()) {
    writeConvergence(folder.path("convergence.csv"), folder.path("convergence.png"), r.solves,
                     scene.metresPerUnit());
    nlohmann::json solves = nlohmann::json::array();
    for (const SolveResult& s : r.solves) solves.push_back(solveJson(s));
    report["solvers"] = solves;
    report["energy_balance"] = energyJson(r.energy);
    report["surfaces"] = surfacesJson(r.surfaces);
  }
  if (r.daylight) report["daylight"] = daylightJson(*r.sky, *r.daylight);
  if (cmd.job == Job::Solvers)
    for (const SolveResult& s : r.solves)
      writeSolutionCsv(folder.path("solution-" + s.solver + ".csv"), scene, r.mesh, s);
  if (cmd.job == Job::Run) {
    writeSurfacesCsv(folder.path("surfaces.csv"), scene, r.surfaces, cmd.photometric);
    writePatchesVtp(folder.path("radiosity.vtp"), scene, r.mesh, &r.radiosity);
    if (r.sky) report["sky_panorama"] = writeSkyPanorama(folder, *r.sky);
    if (!cmd.noRender) renderImage(folder, scene, r, cmd);
  }
  double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  report["seconds"] = {{"mesh", r.seconds.mesh},
                       {"ray_scene", r.seconds.rayScene},
                       {"form_factors", r.seconds.formFactors},
                       {"daylight", r.seconds.daylight},
                       {"solve", r.seconds.solve},
                       {"results", r.seconds.results},
                       {"matrix_files", matrixSeconds},
                       {"total", total}};
  report["peak_memory_bytes"] = peakMemoryBytes();
  writeJson(folder.path("report.json"), report);
  folder.commit();
  printSummary(scene, r, cmd, total, matrixSeconds);
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
  // `solvers` runs past 1e-9 so report.json's table of iterations to 1e-3, 1e-6 and 1e-9 is whole.
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
  sub->callback([cmd] { runJob(*cmd); });
  return sub;
}

}  // namespace

std::string runDefaultJob(const std::string& scenePath, const std::string& outDir) {
  PipelineCommand cmd;
  cmd.job = Job::Run;
  cmd.mesh.scene = scenePath;
  cmd.out = outDir;
  runJob(cmd);
  return cmd.out;
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
