// radkit render: one camera image of a scene by one shading mode (radiosity, two-pass Phong
// or Cook-Torrance, path tracing, photon mapping), as PNG (tone mapped) or PFM (linear radiance).
#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>

#include <nlohmann/json.hpp>

#include "apps/common.h"
#include "apps/console.h"
#include "apps/options.h"
#include "geometry/scene_loader.h"
#include "integrators/integrator.h"
#include "job/report.h"
#include "render/camera.h"
#include "render/exr_io.h"
#include "render/hdr_io.h"
#include "render/image_comparison.h"
#include "util/output_folder.h"
#include "viewer/viewer.h"  // parseSize (viewer.h has no VTK)

namespace radkit::app {

namespace {

struct RenderCommand {
  MeshOptions mesh;
  FormFactorOptions ff;
  SolverOptions solver;
  std::string shading = "path-trace", size = "512x512", tonemap = "srgb",
              masking = "height-correlated", out;
  std::string sampler = "sobol", report, camera;
  std::string lightSampling = "area";  ///< RenderSettings::light says why
  std::vector<std::string> references;
  int spp = 16;
  int rouletteDepth = PathTraceSettings{}.rouletteDepth, maxDepth = PathTraceSettings{}.maxDepth;
  std::size_t photons = 200000;
  int gatherRays = PhotonSettings{}.gatherRays;
  double exposure = 0;
  bool smooth = false, compensated = false, unguided = false;
  CLI::Option* sppOption = nullptr;  ///< photon-map takes --spp only when given
  SmoothSettings smoothing;
};

/// The image of the chosen integrator (integrators/integrator.h), from the command's flags.
RenderResult renderMode(const RenderCommand& cmd, const Scene& scene, int width, int height) {
  RenderSettings s;
  s.film.width = width, s.film.height = height, s.film.samplesPerPixel = cmd.spp;
  s.film.seed = cmd.ff.settings.seed;
  s.film.sampler = parseSamplerType(cmd.sampler);
  s.camera = scene.camera ? *scene.camera : automaticCamera(scene);
  s.bsdf.masking = parseMaskingShadowing(cmd.masking);
  s.bsdf.compensated = cmd.compensated;
  s.light = parseLightSampling(cmd.lightSampling);
  s.mesh = {cmd.mesh.maxArea, cmd.mesh.patches};
  s.formFactors = cmd.ff.settings;
  s.solvers = cmd.solver.choices;
  s.stopping = cmd.solver.stopping;
  s.rouletteDepth = cmd.rouletteDepth, s.maxDepth = cmd.maxDepth;
  s.photons = cmd.photons;
  s.gatherRays = cmd.gatherRays;
  // photon-map: one pass unless --spp is given, which asks for that many passes.
  s.photonPasses = cmd.sppOption && cmd.sppOption->count() > 0 ? cmd.spp : 1;
  s.smooth = cmd.smooth;
  s.smoothing = cmd.smoothing;
  s.guided = !cmd.unguided;
  Progress progress;
  s.log.progress = [&](const std::string& stage, double f) { progress(stage, f); };
  s.warning = [&](const std::string& w) {
    progress.finish();
    std::fprintf(stderr, "radkit: warning: %s\n", w.c_str());
  };
  try {
    RenderResult r = renderImage(cmd.shading, scene, s);
    progress.finish();
    return r;
  } catch (const TooManyPatches&) {
    MeshOptions options = cmd.mesh;
    if (options.maxArea <= 0 && options.patches <= 0) options.patches = kDefaultRenderPatches;
    tooManyPatches(scene, options);
  }
}

/// Region errors against the reference renders: printed, and written as JSON with --report.
void compareWithReference(const RenderCommand& cmd, const Scene& scene, const LoadReport& loaded,
                          const RenderResult& mode, double seconds,
                          const std::vector<RadianceImage>& refs) {
  const RadianceImage& img = mode.image;
  const std::vector<int>& surfaces = mode.surfaces;
  const std::vector<std::string>& warnings = mode.warnings;
  std::vector<std::string> names;
  for (const Surface& s : scene.surfaces) names.push_back(s.name);
  names.push_back("edges");
  const std::vector<int> region =
      surfaceRegions(surfaces, img.width, img.height, int(names.size()) - 1);
  // Also the lit surfaces alone, away from edges: emitters and aliased edges swamp "all".
  std::vector<int> lit(region.size(), -1);
  for (std::size_t k = 0; k < region.size(); ++k)
    if (region[k] >= 0 && region[k] < int(scene.surfaces.size()) &&
        !scene.materials[scene.surfaces[region[k]].material].emits())
      lit[k] = 0;
  std::vector<RegionError> errors;
  try {
    errors = compareToReference(img, refs, region, names);
    errors.insert(errors.begin() + 1, compareToReference(img, refs, lit, {"surfaces"})[1]);
  } catch (const std::invalid_argument& e) {
    throw InputError(std::string(e.what()) + ". Fix: render the image at the reference's --size");
  }
  nlohmann::json rows = nlohmann::json::array();
  for (const RegionError& e : errors) {
    if (e.pixels == 0) continue;
    char line[160];
    std::snprintf(line, sizeof line,
                  "%6.2f %% (raw %.4g, reference noise %.4g, mean %.4g W/m²/sr, %d px)",
                  100 * e.relative(), e.rawRmse, e.referenceNoise, e.referenceMean, e.pixels);
    printField("rmse " + e.name, line);
    rows.push_back({{"region", e.name},
                    {"pixels", e.pixels},
                    {"reference_mean", e.referenceMean},
                    {"raw_rmse", e.rawRmse},
                    {"reference_noise", e.referenceNoise},
                    {"rmse", e.rmse},
                    {"relative_rmse", e.relative()}});
  }
  if (refs.size() < 2)
    printField("note", "one reference: its own noise is not subtracted (give --reference twice)");
  if (cmd.report.empty()) return;
  const nlohmann::json j{{"shading", cmd.shading},
                         {"load", loadJson(loaded)},
                         {"warnings", warnings},
                         {"smooth", cmd.smooth},
                         {"sampler", cmd.sampler},
                         {"light_sampling", cmd.lightSampling},
                         {"spp", cmd.spp},
                         {"width", img.width},
                         {"height", img.height},
                         {"seconds", seconds},
                         {"references", cmd.references},
                         {"regions", rows}};
  writeJson(cmd.report, j);
  printField("report", cmd.report);
}

void runRender(RenderCommand& cmd) {
  cmd.ff.finish();
  cmd.solver.finish();
  int width = 0, height = 0;
  viewer::parseSize(cmd.size, width, height, 1, 16384);  // tests render 8x8 images
  // Refused before the render, which may take minutes, rather than when it is written.
  checkOutputFile("--out", cmd.out);
  if (!cmd.report.empty()) {
    if (cmd.references.empty())
      throw InputError("--report " + cmd.report +
                       " needs --reference: the report holds the errors against it");
    checkOutputFile("--report", cmd.report);
  }
  std::string ext = std::filesystem::path(cmd.out).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  if (ext != ".png" && ext != ".pfm" && ext != ".exr")
    throw InputError("--out " + cmd.out + ": '" + ext +
                     "' is not an image format render writes (PNG bytes under "
                     "another name would mislead). Fix: end the name in .png (tone mapped), .exr "
                     "or .pfm (linear "
                     "radiance, W/m²/sr)");
  // References are read and their size checked first: a mismatch found after the render left
  // the image behind.
  std::vector<RadianceImage> refs;
  for (const std::string& f : cmd.references) {
    refs.push_back(readPfm(f));
    if (refs.back().width != width || refs.back().height != height)
      throw InputError("--reference " + f + " is " + std::to_string(refs.back().width) + "x" +
                       std::to_string(refs.back().height) + ", the image --size " +
                       std::to_string(width) + "x" + std::to_string(height) +
                       ". Fix: render at the reference's --size");
  }
  if (cmd.mesh.scene.empty()) cmd.mesh.scene = defaultScenePath();
  LoadReport loaded;
  const Scene scene = loadSceneReporting(cmd.mesh.scene, cmd.mesh.load, &loaded, cmd.camera);
  const auto start = std::chrono::steady_clock::now();
  RenderResult mode = renderMode(cmd, scene, width, height);
  const RadianceImage& img = mode.image;
  const std::string& what = mode.what;
  const std::vector<bool>& emits = mode.emits;
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double exposure = cmd.exposure > 0 ? cmd.exposure : autoExposure(img, emits);
  if (ext == ".pfm")
    writePfm(cmd.out, img);
  else if (ext == ".exr")
    writeExr(cmd.out, img);
  else
    writePng(cmd.out, toneMapCurve(img, exposure,
                                   cmd.tonemap == "filmic" ? ToneCurve::Filmic : ToneCurve::Srgb));
  printField("scene", scene.name + " (" + scene.file + ")");
  printField("shading", cmd.shading + ": " + what);
  if (ext == ".png") printField("exposure", std::to_string(exposure));
  printField("wrote", cmd.out);
  printField("seconds", std::to_string(seconds));
  if (!cmd.references.empty()) compareWithReference(cmd, scene, loaded, mode, seconds, refs);
}

}  // namespace

void addRenderCommand(CLI::App& app) {
  auto cmd = std::make_shared<RenderCommand>();
  CLI::App* sub = app.add_subcommand(
      "render",
      "One camera image: radiosity, two-pass Phong / Cook-Torrance, or a path-traced reference");
  addMeshOptions(*sub, cmd->mesh, false);
  addCameraOption(*sub, cmd->camera);
  addFormFactorOptions(*sub, cmd->ff);
  addSolverOptions(*sub, cmd->solver, "gauss-seidel");
  std::vector<std::string> modes;
  std::string modeHelp = "Image mode:";
  for (const auto& mode : integratorRegistry().entries()) {
    modes.emplace_back(mode.name);
    modeHelp += std::string("\n  ") + mode.name + ": " + mode.help;
  }
  sub->add_option("--shading", cmd->shading, modeHelp)
      ->check(CLI::IsMember(modes))
      ->capture_default_str();
  sub->add_option("--sampler", cmd->sampler, "Monte Carlo modes: the camera samples' numbers")
      ->check(CLI::IsMember({"independent", "stratified", "sobol"}))
      ->capture_default_str();
  sub->add_option("--light-sampling", cmd->lightSampling,
                  "Monte Carlo modes: a point on the chosen emitter uniformly by area, or "
                  "(rectangles) uniformly "
                  "by solid angle (Urena et al. 2013)")
      ->check(CLI::IsMember({"area", "solid-angle"}))
      ->capture_default_str();
  sub->add_option("--roulette-depth", cmd->rouletteDepth,
                  "path-trace: vertices before Russian roulette may end a path")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  sub->add_option(
         "--max-depth", cmd->maxDepth,
         "path-trace: the most vertices a path has (fewer drop light: for variance studies only)")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  cmd->sppOption =
      sub->add_option(
             "--spp", cmd->spp,
             "Samples (camera paths) per pixel; photon-map: passes of one ray per pixel, 1 "
             "unless given")
          ->check(CLI::Range(1, 1 << 20))
          ->capture_default_str();
  sub->add_option("--size", cmd->size, "Image size WIDTHxHEIGHT")->capture_default_str();
  sub->add_option("--gather-rays", cmd->gatherRays,
                  "photon-map: final-gathering rays per pixel (0: the map seen directly)")
      ->check(CLI::Range(0, 65536))
      ->capture_default_str();
  sub->add_option("--photons", cmd->photons, "photon-map: photons emitted")
      ->check(CLI::Range(std::size_t(1), kMaxPhotons))
      ->capture_default_str();
  sub->add_option("--exposure", cmd->exposure,
                  "Radiance multiplier before tone mapping; 0: automatic")
      ->check(FiniteNonNegative)
      ->capture_default_str();
  sub->add_option("--tonemap", cmd->tonemap,
                  "srgb: clamp and sRGB; filmic: ACES fit (Narkowicz 2016), then sRGB")
      ->check(CLI::IsMember({"srgb", "filmic"}))
      ->capture_default_str();
  sub->add_flag("--smooth", cmd->smooth,
                "radiosity: interpolate between patches (never across creases or jumps)");
  sub->add_option(
         "--crease-angle", cmd->smoothing.creaseAngleDeg,
         "--smooth, final-gather: patches whose normals differ by more degrees are not averaged")
      ->check(FiniteRange(0.0, 180.0))
      ->capture_default_str();
  sub->add_option("--smooth-error", cmd->smoothing.relativeError,
                  "--smooth, final-gather: a patch's assumed error as a fraction of its B; "
                  "neighbours that differ "
                  "by more than 3 combined errors are not averaged (a shadow edge stays sharp)")
      ->check(FiniteNonNegative)
      ->capture_default_str();
  sub->add_flag(
      "--unguided", cmd->unguided,
      "final-gather: BSDF-sampled gather rays only, without the form-factor-guided samples");
  sub->add_option("--reference", cmd->references,
                  "PFM render(s) of the same view to report RMSE against, per surface; two or more "
                  "independent "
                  "ones let their own noise be subtracted")
      ->check(CLI::ExistingFile);
  sub->add_option("--report", cmd->report,
                  "With --reference: write the errors and the time as JSON");
  sub->add_option("--g", cmd->masking, "Cook-Torrance shadowing-masking term")
      ->check(CLI::IsMember({"height-correlated", "separable", "schlick", "cook-torrance"}))
      ->capture_default_str();
  sub->add_flag("--compensated", cmd->compensated,
                "Cook-Torrance: Kulla-Conty multiple-scattering compensation");
  sub->add_option(
         "--out", cmd->out,
         "Image file: .png (tone mapped), or .exr or .pfm (linear radiance, W/m²/sr, 32-bit float)")
      ->required();
  sub->callback([cmd] { runRender(*cmd); });
}

}  // namespace radkit::app
