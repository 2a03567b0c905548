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
#include "apps/options.h"
#include "apps/report.h"
#include "geometry/scene_loader.h"
#include "render/camera.h"
#include "render/exr_io.h"
#include "render/final_gather.h"
#include "render/hdr_io.h"
#include "render/image_comparison.h"
#include "render/path_tracer.h"
#include "render/photon_image.h"
#include "render/photon_map.h"
#include "render/photon_tracer.h"
#include "render/shading.h"
#include "util/output_folder.h"
#include "viewer/viewer.h"  // parseSize (viewer.h has no VTK)

namespace radkit::app {

namespace {

/// The radiosity mesh of `render` when none is given: surface radiosities on the Cornell
/// box lie within 0.1 % of a 2 000-patch run, in about 3 s on two cores.
constexpr int kDefaultRenderPatches = 1000;

struct RenderCommand {
  MeshOptions mesh;
  FormFactorOptions ff;
  SolverOptions solver;
  std::string shading = "path-trace", size = "512x512", tonemap = "srgb", masking = "height-correlated", out;
  std::string sampler = "sobol", report, camera;
  /// Solid angle lowers the Cornell box's error by 3 % at equal samples but costs 30 % more
  /// time (docs/images.md), so area stays the default.
  std::string lightSampling = "area";
  std::vector<std::string> references;
  int spp = 16;
  int rouletteDepth = PathTraceSettings{}.rouletteDepth, maxDepth = PathTraceSettings{}.maxDepth;
  std::size_t photons = 200000;
  double exposure = 0;
  bool smooth = false, compensated = false, unguided = false;
  CLI::Option* sppOption = nullptr;  ///< photon-map takes --spp only when given
  SmoothSettings smoothing;
};

/// The surface each pixel centre sees, −1 where the ray escapes.
std::vector<int> pixelSurfaces(const RadianceImage& img, const PatchMesh& mesh) {
  std::vector<int> out(img.patch.size(), -1);
  for (std::size_t k = 0; k < out.size(); ++k)
    if (img.patch[k] >= 0) out[k] = mesh.patches[img.patch[k]].surface;
  return out;
}


/// Radiance image of the chosen mode; `emits` marks pixels that show an emitter.
RadianceImage renderMode(const RenderCommand& cmd, const Scene& scene, int width, int height, std::string& what,
                         std::vector<bool>& emits, std::vector<int>& surfaces) {
  const Camera camera = scene.camera ? *scene.camera : automaticCamera(scene);
  BsdfSettings bsdf;
  bsdf.masking = parseMaskingShadowing(cmd.masking);
  bsdf.compensated = cmd.compensated;
  const std::uint64_t seed = cmd.ff.settings.seed;
  if (cmd.shading == "photon-map") {
    // Final gathering over the global map plus the caustic map seen directly (Jensen 1996).
    MeshOptions meshOptions = cmd.mesh;
    if (meshOptions.maxArea <= 0 && meshOptions.patches <= 0) meshOptions.patches = kDefaultRenderPatches;
    PatchMesh mesh = meshScene(scene, meshOptions);
    RayScene rays(mesh);
    EmitterSampler emitters(scene, mesh);
    if (emitters.empty())
      throw InputError(scene.file + ": no surface emits, so no photon can start. Fix: give a material an \"emission\" above zero");
    PhotonSettings ps;
    ps.photons = cmd.photons;
    ps.seed = seed;
    PhotonMaps maps = buildPhotonMaps(mesh, tracePhotons(scene, mesh, rays, emitters, ps).photons);
    maps.global->precomputeIrradiance(ps.neighbours, ps.filter, ps.precomputeStride);
    const PhotonScene in{scene, mesh, rays, emitters, *maps.global, *maps.caustic};
    RadianceImage img = renderPhotonImage(in, camera, width, height, PhotonView::FinalGather, ps);
    // One jittered ray per pixel per pass; --spp given asks for more passes, averaged (each
    // pass its own camera stream). Without it one pass, as before: a pass costs its gathers.
    const int passes = cmd.sppOption && cmd.sppOption->count() > 0 ? cmd.spp : 1;
    for (int pass = 1; pass < passes; ++pass) {
      PhotonSettings more = ps;
      more.seed = seed + std::uint64_t(pass);
      const RadianceImage next = renderPhotonImage(in, camera, width, height, PhotonView::FinalGather, more);
      for (std::size_t k = 0; k < img.radiance.size(); ++k) img.radiance[k] = img.radiance[k] + next.radiance[k];
    }
    for (Vec3& v : img.radiance) v = v / double(passes);
    what = std::to_string(cmd.photons) + " photons, " + std::to_string(maps.global->size()) + " stored, " +
           std::to_string(ps.gatherRays) + " gather rays per pixel, " + std::to_string(passes) + " pass(es)";
    emits = emitterPixels(img, scene, mesh);
    surfaces = pixelSurfaces(img, mesh);
    return img;
  }
  const SamplerType sampler = parseSamplerType(cmd.sampler);
  const LightSampling light = parseLightSampling(cmd.lightSampling);
  if (cmd.shading == "path-trace") {
    PatchMesh mesh = meshScene(scene, cmd.mesh);
    RayScene rays(mesh);
    ShadingScene shading(scene, mesh, rays, bsdf, GlossyModel::AsDeclared, light);
    PathTraceSettings s;
    s.width = width, s.height = height, s.samplesPerPixel = cmd.spp, s.seed = seed, s.sampler = sampler;
    s.rouletteDepth = cmd.rouletteDepth, s.maxDepth = cmd.maxDepth;
    MonteCarloImage img = renderPathTraced(shading, camera, s);
    what = std::to_string(img.paths) + " paths, " + std::to_string(img.rays) + " rays in " +
           std::to_string(img.seconds) + " s";
    emits = emitterPixels(img.image, scene, mesh);
    surfaces = pixelSurfaces(img.image, mesh);
    return img.image;
  }
  PipelineSettings settings;
  settings.mesh = {cmd.mesh.maxArea, cmd.mesh.patches};
  if (settings.mesh.maxArea <= 0 && settings.mesh.targetPatches <= 0) settings.mesh.targetPatches = kDefaultRenderPatches;
  settings.formFactors = cmd.ff.settings;
  settings.solvers = cmd.solver.choices;
  settings.stopping = cmd.solver.stopping;
  Progress progress;
  PipelineLog log;
  log.progress = [&](const std::string& stage, double f) { progress(stage, f); };
  PipelineResult r = runPipeline(scene, settings, log);
  progress.finish();
  what = std::to_string(r.mesh.size()) + " patches";
  if (cmd.shading == "radiosity") {
    ImageSettings s;
    s.width = width, s.height = height, s.smooth = cmd.smooth, s.smoothing = cmd.smoothing;
    std::vector<bool> twoSided;
    for (const Surface& surf : scene.surfaces) twoSided.push_back(scene.materials[surf.material].twoSided);
    RadianceImage img = renderRadiosity(r.mesh, *r.rays, camera, r.radiosity, twoSided, s);
    emits = emitterPixels(img, scene, r.mesh);
    surfaces = pixelSurfaces(img, r.mesh);
    return img;
  }
  if (cmd.shading == "final-gather") {
    ShadingScene shading(scene, r.mesh, *r.rays, bsdf, GlossyModel::AsDeclared, light);
    FinalGatherSettings s;
    s.width = width, s.height = height, s.samplesPerPixel = cmd.spp, s.seed = seed, s.sampler = sampler;
    s.smoothing = cmd.smoothing;
    const RadiosityLighting lighting = radiosityLighting(r);
    std::optional<GatherGuide> guide;
    if (!cmd.unguided) guide.emplace(r.formFactors->matrix, lighting);
    MonteCarloImage img = renderFinalGather(shading, camera, lighting, s, guide ? &*guide : nullptr);
    what += ", " + std::to_string(img.paths) + " gathers in " + std::to_string(img.seconds) + " s";
    emits = emitterPixels(img.image, scene, r.mesh);
    surfaces = pixelSurfaces(img.image, r.mesh);
    return img.image;
  }
  const GlossyModel glossy = cmd.shading == "phong" ? GlossyModel::Phong : GlossyModel::CookTorrance;
  ShadingScene shading(scene, r.mesh, *r.rays, bsdf, glossy, light);
  TwoPassSettings s;
  s.width = width, s.height = height, s.samplesPerPixel = cmd.spp, s.seed = seed, s.sampler = sampler;
  MonteCarloImage img = renderTwoPass(shading, camera, radiosityLighting(r), s);
  what += ", " + std::to_string(img.paths) + " camera samples in " + std::to_string(img.seconds) + " s";
  emits = emitterPixels(img.image, scene, r.mesh);
  surfaces = pixelSurfaces(img.image, r.mesh);
  return img.image;
}

/// Region errors against the reference renders: printed, and written as JSON with --report.
void compareWithReference(const RenderCommand& cmd, const Scene& scene, const RadianceImage& img,
                          const std::vector<int>& surfaces, double seconds, const std::vector<RadianceImage>& refs) {
  std::vector<std::string> names;
  for (const Surface& s : scene.surfaces) names.push_back(s.name);
  names.push_back("edges");
  const std::vector<int> region = surfaceRegions(surfaces, img.width, img.height, int(names.size()) - 1);
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
    std::snprintf(line, sizeof line, "%6.2f %% (raw %.4g, reference noise %.4g, mean %.4g W/m²/sr, %d px)",
                  100 * e.relative(), e.rawRmse, e.referenceNoise, e.referenceMean, e.pixels);
    printField("rmse " + e.name, line);
    rows.push_back({{"region", e.name}, {"pixels", e.pixels}, {"reference_mean", e.referenceMean},
                    {"raw_rmse", e.rawRmse}, {"reference_noise", e.referenceNoise}, {"rmse", e.rmse},
                    {"relative_rmse", e.relative()}});
  }
  if (refs.size() < 2) printField("note", "one reference: its own noise is not subtracted (give --reference twice)");
  if (cmd.report.empty()) return;
  const nlohmann::json j{{"shading", cmd.shading}, {"smooth", cmd.smooth}, {"sampler", cmd.sampler},
                         {"light_sampling", cmd.lightSampling}, {"spp", cmd.spp}, {"width", img.width},
                         {"height", img.height}, {"seconds", seconds}, {"references", cmd.references}, {"regions", rows}};
  writeFileAtomically(cmd.report, j.dump(2) + "\n");
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
      throw InputError("--report " + cmd.report + " needs --reference: the report holds the errors against it");
    checkOutputFile("--report", cmd.report);
  }
  std::string ext = std::filesystem::path(cmd.out).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext != ".png" && ext != ".pfm" && ext != ".exr")
    throw InputError("--out " + cmd.out + ": '" + ext + "' is not an image format render writes (PNG bytes under "
                     "another name would mislead). Fix: end the name in .png (tone mapped), .exr or .pfm (linear "
                     "radiance, W/m²/sr)");
  // References are read and their size checked first: a mismatch found after the render left
  // the image behind.
  std::vector<RadianceImage> refs;
  for (const std::string& f : cmd.references) {
    refs.push_back(readPfm(f));
    if (refs.back().width != width || refs.back().height != height)
      throw InputError("--reference " + f + " is " + std::to_string(refs.back().width) + "x" +
                       std::to_string(refs.back().height) + ", the image --size " + std::to_string(width) + "x" +
                       std::to_string(height) + ". Fix: render at the reference's --size");
  }
  if (cmd.mesh.scene.empty()) cmd.mesh.scene = defaultScenePath();
  const Scene scene = loadSceneReporting(cmd.mesh.scene, cmd.camera);
  std::string what;
  std::vector<bool> emits;
  std::vector<int> surfaces;
  const auto start = std::chrono::steady_clock::now();
  const RadianceImage img = renderMode(cmd, scene, width, height, what, emits, surfaces);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double exposure = cmd.exposure > 0 ? cmd.exposure : autoExposure(img, emits);
  if (ext == ".pfm") writePfm(cmd.out, img);
  else if (ext == ".exr") writeExr(cmd.out, img);
  else writePng(cmd.out, toneMapCurve(img, exposure, cmd.tonemap == "filmic" ? ToneCurve::Filmic : ToneCurve::Srgb));
  printField("scene", scene.name + " (" + scene.file + ")");
  printField("shading", cmd.shading + ": " + what);
  if (ext == ".png") printField("exposure", std::to_string(exposure));
  printField("wrote", cmd.out);
  printField("seconds", std::to_string(seconds));
  if (!cmd.references.empty()) compareWithReference(cmd, scene, img, surfaces, seconds, refs);
}

}  // namespace

void addRenderCommand(CLI::App& app) {
  auto cmd = std::make_shared<RenderCommand>();
  CLI::App* sub = app.add_subcommand("render", "One camera image: radiosity, two-pass Phong / Cook-Torrance, or a path-traced reference");
  addMeshOptions(*sub, cmd->mesh, false);
  addCameraOption(*sub, cmd->camera);
  addFormFactorOptions(*sub, cmd->ff);
  addSolverOptions(*sub, cmd->solver, "gauss-seidel");
  sub->add_option("--shading", cmd->shading, "Image mode")
      ->check(CLI::IsMember({"radiosity", "phong", "cook-torrance", "path-trace", "photon-map", "final-gather"}))
      ->capture_default_str();
  sub->add_option("--sampler", cmd->sampler, "Monte Carlo modes: the camera samples' numbers")
      ->check(CLI::IsMember({"independent", "stratified", "sobol"}))
      ->capture_default_str();
  sub->add_option("--light-sampling", cmd->lightSampling,
                  "Monte Carlo modes: a point on the chosen emitter uniformly by area, or (rectangles) uniformly "
                  "by solid angle (Urena et al. 2013)")
      ->check(CLI::IsMember({"area", "solid-angle"}))
      ->capture_default_str();
  sub->add_option("--roulette-depth", cmd->rouletteDepth,
                  "path-trace: vertices before Russian roulette may end a path")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  sub->add_option("--max-depth", cmd->maxDepth,
                  "path-trace: the most vertices a path has (fewer drop light: for variance studies only)")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  cmd->sppOption = sub->add_option("--spp", cmd->spp,
                                   "Samples (camera paths) per pixel; photon-map: passes of one ray per pixel, 1 "
                                   "unless given")
                       ->check(CLI::Range(1, 1 << 20))
                       ->capture_default_str();
  sub->add_option("--size", cmd->size, "Image size WIDTHxHEIGHT")->capture_default_str();
  sub->add_option("--photons", cmd->photons, "photon-map: photons emitted")
      ->check(CLI::Range(std::size_t(1), kMaxPhotons))
      ->capture_default_str();
  sub->add_option("--exposure", cmd->exposure, "Radiance multiplier before tone mapping; 0: automatic")
      ->check(FiniteNonNegative)
      ->capture_default_str();
  sub->add_option("--tonemap", cmd->tonemap, "srgb: clamp and sRGB; filmic: ACES fit (Narkowicz 2016), then sRGB")
      ->check(CLI::IsMember({"srgb", "filmic"}))
      ->capture_default_str();
  sub->add_flag("--smooth", cmd->smooth, "radiosity: interpolate between patches (never across creases or jumps)");
  sub->add_option("--crease-angle", cmd->smoothing.creaseAngleDeg,
                  "--smooth, final-gather: patches whose normals differ by more degrees are not averaged")
      ->check(FiniteRange(0.0, 180.0))
      ->capture_default_str();
  sub->add_option("--smooth-error", cmd->smoothing.relativeError,
                  "--smooth, final-gather: a patch's assumed error as a fraction of its B; neighbours that differ "
                  "by more than 3 combined errors are not averaged (a shadow edge stays sharp)")
      ->check(FiniteNonNegative)
      ->capture_default_str();
  sub->add_flag("--unguided", cmd->unguided,
                "final-gather: BSDF-sampled gather rays only, without the form-factor-guided samples");
  sub->add_option("--reference", cmd->references,
                  "PFM render(s) of the same view to report RMSE against, per surface; two or more independent "
                  "ones let their own noise be subtracted")
      ->check(CLI::ExistingFile);
  sub->add_option("--report", cmd->report, "With --reference: write the errors and the time as JSON");
  sub->add_option("--g", cmd->masking, "Cook-Torrance shadowing-masking term")
      ->check(CLI::IsMember({"height-correlated", "separable", "schlick", "cook-torrance"}))
      ->capture_default_str();
  sub->add_flag("--compensated", cmd->compensated, "Cook-Torrance: Kulla-Conty multiple-scattering compensation");
  sub->add_option("--out", cmd->out, "Image file: .png (tone mapped), or .exr or .pfm (linear radiance, W/m²/sr, 32-bit float)")->required();
  sub->callback([cmd] { runRender(*cmd); });
}

}  // namespace radkit::app
