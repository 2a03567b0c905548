// radkit render: one camera image of a scene by one shading mode (radiosity, two-pass Phong
// or Cook-Torrance, path tracing, photon mapping), as PNG (tone mapped) or PFM (linear radiance).
#include <cstdio>
#include <memory>
#include <string>

#include "apps/common.h"
#include "apps/console.h"
#include "apps/options.h"
#include "integrators/integrator.h"
#include "job/render_job.h"
#include "render/hdr_io.h"
#include "util/params.h"
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

/// The render job the command's flags describe (integrators/integrator.h's settings).
RenderJobSettings jobSettings(const RenderCommand& cmd, int width, int height) {
  RenderJobSettings job;
  job.scene = cmd.mesh.scene.empty() ? defaultScenePath() : cmd.mesh.scene;
  job.load = cmd.mesh.load;
  job.camera = cmd.camera;
  job.shading = cmd.shading;
  job.out = cmd.out;
  job.exposure = cmd.exposure;
  job.tonemap = cmd.tonemap == "filmic" ? ToneCurve::Filmic : ToneCurve::Srgb;
  job.references = cmd.references;
  job.report = cmd.report;
  RenderSettings& s = job.render;
  s.film.width = width, s.film.height = height, s.film.samplesPerPixel = cmd.spp;
  s.film.seed = cmd.ff.settings.seed;
  s.film.sampler = parseSamplerType(cmd.sampler);
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
  return job;
}

void runRender(RenderCommand& cmd) {
  cmd.ff.finish();
  cmd.solver.finish();
  int width = 0, height = 0;
  viewer::parseSize(cmd.size, width, height, 1, 16384);  // tests render 8x8 images
  RenderJobSettings job = jobSettings(cmd, width, height);
  Progress progress;
  const PipelineLog log = consoleLog(progress);
  job.render.log.progress = log.progress;
  job.render.warning = [&](const std::string& w) { log.message("warning: " + w); };
  RenderJobResult r;
  try {
    r = runRenderJob(job, log);
  } catch (...) {
    progress.finish();
    throw;
  }
  progress.finish();
  printField("scene", r.sceneName + " (" + r.sceneFile + ")");
  printField("shading", cmd.shading + ": " + r.mode.what);
  if (r.format == "png") printField("exposure", std::to_string(r.exposure));
  printField("wrote", cmd.out);
  printField("seconds", std::to_string(r.seconds));
  if (cmd.references.empty()) return;
  for (const RegionError& e : r.errors) {
    if (e.pixels == 0) continue;
    char line[160];
    std::snprintf(line, sizeof line,
                  "%6.2f %% (raw %.4g, reference noise %.4g, mean %.4g W/m²/sr, %d px)",
                  100 * e.relative(), e.rawRmse, e.referenceNoise, e.referenceMean, e.pixels);
    printField("rmse " + e.name, line);
  }
  if (cmd.references.size() < 2)
    printField("note", "one reference: its own noise is not subtracted (give --reference twice)");
  if (!cmd.report.empty()) printField("report", cmd.report);
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
  sub->add_option("--shading", cmd->shading,
                  modeHelp + "\n  (a mode's own parameters after ':', separated by ';')")
      ->check(CLI::Validator(
          [modes](std::string& text) -> std::string {
            const std::string name = splitPluginChoice(text).name;
            for (const std::string& m : modes)
              if (m == name) return "";
            std::string known;
            for (const std::string& m : modes) known += (known.empty() ? "" : ", ") + m;
            return "'" + name + "' is not an image mode. Fix: use one of " + known;
          },
          "MODE[:key=value;...]"))
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
