// runJob for the dense method: F for every patch pair, the solvers, and the outputs of the
// job's kind.
#include <algorithm>
#include <chrono>
#include <string>

#include "job/job_parts.h"
#include "job/report.h"
#include "output/run_files.h"
#include "radiosity/form_factor_heat_map.h"
#include "radiosity/presets.h"
#include "radiosity/surface_form_factors.h"
#include "render/radiosity_image.h"
#include "util/errors.h"
#include "util/format.h"
#include "util/output_folder.h"
#include "util/setting_names.h"

namespace radkit {

namespace {

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
  return secondsSince(start);
}

void renderImage(OutputFolder& folder, const Scene& scene, const PipelineResult& r,
                 const JobSettings& s, const PipelineLog& log) {
  ImageSettings image;
  image.width = s.imageWidth, image.height = s.imageHeight;
  image.smooth = s.smooth;
  if (r.sky) image.background = [&](const Vec3& d) { return r.sky->radiance(d); };
  if (!writeRadiosityPng(folder.path("render.png"), scene, r.mesh, *r.rays, r.radiosity, image) &&
      log.message)
    log.message("warning: " + blackPictureWarning("render.png"));
}

/// MemoryBudgetError's message with what it leaves out: a mesh of one patch per input face
/// cannot have fewer patches (that fix is dropped), and the hierarchical method keeps no n×n
/// matrix.
std::string memoryBudgetMessage(const MemoryBudgetError& e, const Scene& scene, JobKind kind) {
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
    const std::string fewer = fewerPatchesFix();
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
  if (kind == JobKind::Run) {
    // Peak memory of `run --method hierarchical --no-render` on the shipped scenes, less
    // radkit's own 40 MiB: terrain-room.json 2.7 kB per input face (51 201 faces, 170 MiB),
    // models/spot-room.json 11.7 kB (5 870 faces, 105 MiB). A million-face terrain takes
    // 1.3 kB, so for large meshes the range errs high.
    const double base = 40.0 * 1024 * 1024;
    const double low = base + 2.7e3 * double(faces), high = base + 11.7e3 * double(faces);
    message += " " + setting("method") +
               " hierarchical keeps no n×n matrix: on the shipped scenes it took 40 MiB "
               "and 2.7-11.7 kB per input face, about " +
               formatBytes(low) + " to " + formatBytes(high) +
               " here (docs/bring-your-own-model.md)";
  }
  return message;
}

}  // namespace

JobResult runDenseJob(Scene loadedScene, const LoadReport& loaded, const JobSettings& s,
                      const PipelineLog& log, std::chrono::steady_clock::time_point start) {
  JobResult result;
  result.method = JobMethod::Dense;
  result.scene = std::move(loadedScene);
  Scene& scene = result.scene;
  addBackSides(scene);  // two-sided surfaces exchange light on both sides
  // Only a run names its own folder; an empty one for the others is OutputFolder's error.
  result.out = s.out.empty() && s.kind == JobKind::Run ? defaultOutFolder(scene.name) : s.out;
  OutputFolder folder(result.out);  // refuses a folder it cannot replace before the work

  PipelineSettings settings;
  settings.mesh = *s.mesh;
  settings.formFactors = s.formFactors;
  settings.solvers = s.solvers;
  settings.stopping = s.stopping;
  nlohmann::json adaptiveJson;
  result.dense = std::make_unique<PipelineResult>();
  PipelineResult& r = *result.dense;
  try {  // subdivide's TooManyPatches: more patches than radkit meshes
    if (s.adaptive) {
      AdaptiveResult a = solveAdaptive(scene, settings, *s.adaptive, log);
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
    throwTooManyPatches(scene, settings.mesh);
  } catch (const MemoryBudgetError& e) {
    throw InputError(memoryBudgetMessage(e, scene, s.kind));
  }
  // A run's answer must be a number: a diverged first solver leaves nothing to write.
  if (s.kind == JobKind::Run && !r.solves.empty() &&
      r.solves.front().reason.rfind("diverged", 0) == 0)
    throw std::runtime_error(r.solves.front().solver + " " + r.solves.front().reason +
                             "; nothing written");

  nlohmann::json& report = result.report;
  report = {{"radkit", RADKIT_VERSION},
            {"command", jobKindName(s.kind)},
            {"scene", sceneJson(scene)},
            {"mesh", meshJson(scene, r.mesh)},
            {"form_factors", toJson(r.formFactors->diagnostics)},
            {"warnings", r.warnings},
            {"load", loadJson(loaded)}};
  if (!s.preset.empty())
    report["preset"] = {{"name", s.preset}, {"description", describePreset(s.preset)}};
  if (s.adaptive) report["adaptive"] = adaptiveJson;
  if (r.formFactorNoise > 0) report["form_factors"]["gathered_light_noise"] = r.formFactorNoise;
  writePatchesCsv(folder.path("patches.csv"), scene, r.mesh,
                  r.solves.empty() ? nullptr : &r.radiosity);
  if (s.kind != JobKind::Solvers)
    result.matrixSeconds = writeFormFactorFiles(folder, scene, r, s.writeMatrix);
  if (!r.solves.empty()) {
    writeConvergence(folder.path("convergence.csv"), folder.path("convergence.png"), r.solves,
                     scene.metresPerUnit());
    nlohmann::json solves = nlohmann::json::array();
    for (const SolveResult& solve : r.solves) solves.push_back(solveJson(solve));
    report["solvers"] = solves;
    report["energy_balance"] = energyJson(r.energy);
    report["surfaces"] = surfacesJson(r.surfaces);
  }
  if (r.daylight) report["daylight"] = daylightJson(*r.sky, *r.daylight);
  if (s.kind == JobKind::Solvers)
    for (const SolveResult& solve : r.solves)
      writeSolutionCsv(folder.path("solution-" + solve.solver + ".csv"), scene, r.mesh, solve);
  if (s.kind == JobKind::Run) {
    writeSurfacesCsv(folder.path("surfaces.csv"), scene, r.surfaces, s.photometric);
    writePatchesVtp(folder.path("radiosity.vtp"), scene, r.mesh, &r.radiosity);
    if (r.sky) report["sky_panorama"] = writeSkyPanorama(folder, *r.sky);
    if (s.render) renderImage(folder, scene, r, s, log);
  }
  result.seconds = secondsSince(start);
  report["seconds"] = {{"mesh", r.seconds.mesh},
                       {"ray_scene", r.seconds.rayScene},
                       {"form_factors", r.seconds.formFactors},
                       {"daylight", r.seconds.daylight},
                       {"solve", r.seconds.solve},
                       {"results", r.seconds.results},
                       {"matrix_files", result.matrixSeconds},
                       {"total", result.seconds}};
  report["peak_memory_bytes"] = peakMemoryBytes();
  writeJson(folder.path("report.json"), report);
  folder.commit();
  return result;
}

}  // namespace radkit
