// radkit clouds: a cloud layer under the physical sky, rendered by the volumetric path tracer
// (the reference) and by the real-time model with each of its features switched on in turn,
// with a table of error against time (docs/clouds.md).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "apps/common.h"
#include "experiments/cloud_comparison.h"
#include "job/report.h"
#include "media/cloud_marcher.h"
#include "media/medium.h"
#include "media/medium_json.h"
#include "media/volume_tracer.h"
#include "render/camera.h"
#include "render/hdr_io.h"
#include "util/canvas.h"
#include "util/errors.h"
#include "util/format.h"
#include "util/output_folder.h"

namespace radkit::app {

namespace {

using nlohmann::json;

struct CloudsCommand {
  media::CloudLayerSettings layer;
  bool skyNee = CloudComparisonSettings{}.skyNee;  ///< CloudComparisonSettings says why
  // HG with the Mie cloud table's g: the table's forward peak (thousands per sr) makes the
  // reference's sun estimates fireflies (docs/clouds.md); --phase mie-cloud uses it.
  // Empty parameters: HG takes g = 0.86 (the Mie table's mean cosine), others their defaults.
  std::string phase = "henyey-greenstein", phaseParams;
  int width = 128, height = 72, samples = 32;
  double sunElevation = 40, sunAzimuth = 150, cameraElevation = 25, fov = 70;
  double exposure = 0;
  std::uint64_t seed = 1;
  media::MarchSettings march;
  std::string out = "out/clouds";
  std::string scene;  ///< a volume scene file (--scene): medium, sun, camera, ground
  // Options that, given explicitly, override the scene file's values.
  CLI::Option *sunElevationOption = nullptr, *sunAzimuthOption = nullptr,
              *cameraElevationOption = nullptr, *fovOption = nullptr;
};

/// Whether an option was given on the command line (its default does not count).
bool given(const CLI::Option* option) { return option != nullptr && option->count() > 0; }

void runClouds(CloudsCommand& cmd) {
  // The scene file is read before the output folder exists: a bad file leaves nothing behind.
  const auto start = std::chrono::steady_clock::now();
  std::optional<media::VolumeScene> scene;
  std::unique_ptr<media::Medium> medium;
  std::string kind = "cloud-layer", phaseName = cmd.phase;
  if (!cmd.scene.empty()) {
    scene = media::loadVolumeScene(cmd.scene);
    medium = std::move(scene->medium);
    kind = scene->kind, phaseName = scene->phaseName;
    if (scene->sunElevationDeg && !given(cmd.sunElevationOption))
      cmd.sunElevation = *scene->sunElevationDeg;
    if (scene->sunAzimuthDeg && !given(cmd.sunAzimuthOption))
      cmd.sunAzimuth = *scene->sunAzimuthDeg;
  } else {
    cmd.layer.seed = std::uint32_t(cmd.seed);  // without a scene file --seed seeds the noise too
    medium = std::make_unique<media::CloudLayer>(
        cmd.layer,
        makePhaseFunction(cmd.phase, cmd.phaseParams.empty() && cmd.phase == "henyey-greenstein"
                                         ? "g=0.86"
                                         : cmd.phaseParams));
  }
  const media::Medium& layer = *medium;
  {
    // Delta and ratio tracking step by the majorant's free path, so a ray across the medium
    // takes about σ̄ · (its extent) steps: 1e5 is a medium 50 times denser than the densest
    // cloud across the default layer, and minutes per sample beyond it.
    const Bounds3 b = layer.bounds();
    const double extent = length(b.hi - b.lo);
    const double depth = layer.majorant() * extent;
    constexpr double kMaxOpticalExtent = 1e5;
    if (!(depth <= kMaxOpticalExtent))
      throw InputError((scene ? cmd.scene + ": the medium's" : std::string("--extinction:")) +
                       " extinction " + fmt("%g", layer.majorant()) + " /m across a medium " +
                       fmt("%g", extent) + " m wide is an optical extent of " + fmt("%g", depth) +
                       ", and a path takes about that many tracking steps (the limit is " +
                       fmt("%g", kMaxOpticalExtent) + "). Fix: give an extinction below " +
                       fmt("%g", kMaxOpticalExtent / extent) +
                       " /m (dense cloud is 0.05-0.12 /m) or a smaller medium");
  }
  const double groundAlbedo = scene ? scene->groundAlbedo : 0.0;
  const double layerSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  OutputFolder folder(cmd.out);
  const Bounds3 bounds = layer.bounds();

  // The file's camera unless --camera-elevation or --fov overrides it; otherwise on the ground
  // looking north, --camera-elevation above the horizon.
  Camera camera;
  const double e = cmd.cameraElevation * M_PI / 180;
  if (scene && scene->camera) {
    camera = *scene->camera;
    if (given(cmd.cameraElevationOption)) {
      // Keep the file's position and heading; tilt to the given elevation.
      const Vec3 f = camera.lookAt - camera.position;
      const double h = std::hypot(f.x, f.y);
      const double hx = h > 0 ? f.x / h : 0, hy = h > 0 ? f.y / h : 1;
      camera.lookAt = camera.position + Vec3{hx * std::cos(e), hy * std::cos(e), std::sin(e)};
    }
    if (given(cmd.fovOption)) camera.fovDeg = cmd.fov;
  } else {
    camera.position = {0, 0, 1.7};
    camera.lookAt = camera.position + Vec3{0, std::cos(e), std::sin(e)};
    camera.up = {0, 0, 1};
    camera.fovDeg = cmd.fov;
  }
  const Vec3 forward = normalize(camera.lookAt - camera.position);
  const double cameraElevation = scene && scene->camera && !given(cmd.cameraElevationOption)
                                     ? std::asin(std::clamp(forward.z, -1.0, 1.0)) * 180 / M_PI
                                     : cmd.cameraElevation;
  if (!(length(cross(camera.lookAt - camera.position, camera.up)) > 0))
    throw InputError((scene ? cmd.scene + ": " : std::string()) +
                     "the camera's view is parallel to its \"up\" after --camera-elevation. "
                     "Fix: give another --camera-elevation, or the camera an \"up\" across "
                     "the view");
  CloudComparisonSettings cs;
  cs.width = cmd.width, cs.height = cmd.height, cs.samples = cmd.samples, cs.seed = cmd.seed;
  cs.sunElevationDeg = cmd.sunElevation, cs.sunAzimuthDeg = cmd.sunAzimuth;
  cs.groundAlbedo = groundAlbedo;
  cs.skyNee = cmd.skyNee;
  cs.march = cmd.march;
  cs.camera = camera;
  const CloudComparison result = compareCloudModels(layer, cs);
  const media::VolumeImage& reference = result.reference;
  const media::Lighting& light = result.light;
  const double mean = result.referenceMean, noiseFloor = result.referenceNoise;
  const media::VolumeImage* defaults = &result.variants[result.defaults].image;

  double exposure = cmd.exposure;
  if (!(exposure > 0)) exposure = mean > 0 ? 0.18 / luminance(Vec3{mean, mean, mean}) : 1;
  json table = json::array();
  for (const CloudVariant& v : result.variants)
    table.push_back({{"variant", v.name},
                     {"primary_steps", v.settings.primarySteps},
                     {"light_steps", v.settings.lightSteps},
                     {"octaves", v.settings.octaves},
                     {"ambient", v.settings.ambient},
                     {"jitter", v.settings.jitter},
                     {"seconds", v.image.seconds},
                     {"relative_rmse", v.relativeRmse},
                     {"relative_bias", v.relativeBias},
                     {"speedup", reference.seconds / std::max(v.image.seconds, 1e-9)}});
  writeLinearAndPng(folder.path("clouds-reference"),
                    pixelImage(cmd.width, cmd.height, reference.radiance, exposure));
  writeLinearAndPng(folder.path("clouds-realtime"),
                    pixelImage(cmd.width, cmd.height, defaults->radiance, exposure));
  writePng(folder.path("clouds-difference.png"),
           toneMapCurve(relativeDifferenceImage(cmd.width, cmd.height, defaults->radiance,
                                                reference.radiance),
                        1, ToneCurve::Srgb));

  json settings{{"width", cmd.width},
                {"height", cmd.height},
                {"samples", cmd.samples},
                {"sky_nee", cmd.skyNee},
                {"seed", cmd.seed},
                {"scene", scene ? json(cmd.scene) : json(nullptr)},
                {"medium", kind},
                {"phase", phaseName},
                {"phase_mean_cosine", layer.phase().meanCosine()},
                {"bottom_m", bounds.lo.z},
                {"top_m", bounds.hi.z},
                {"albedo", layer.albedo()},
                {"ground_albedo", groundAlbedo},
                {"sun_elevation_deg", cmd.sunElevation},
                {"sun_azimuth_deg", cmd.sunAzimuth},
                {"sun_irradiance_W_m2", vec3Json(light.sunIrradiance)},
                {"camera_elevation_deg", cameraElevation},
                {"fov_deg", camera.fovDeg}};
  if (const auto* cloud = dynamic_cast<const media::CloudLayer*>(&layer)) {
    settings["coverage"] = cloud->settings().coverage;
    settings["cloud_type"] = cloud->settings().cloudType;
    settings["extinction_per_m"] = cloud->settings().extinction;
  } else {
    settings["extinction_per_m"] = layer.majorant();  // homogeneous: σ_t everywhere inside
    settings["box_min_m"] = vec3Json(bounds.lo);
    settings["box_max_m"] = vec3Json(bounds.hi);
  }
  json report{{"radkit", RADKIT_VERSION},
              {"command", "clouds"},
              {"settings", settings},
              {"reference",
               {{"seconds", reference.seconds},
                {"paths", reference.paths},
                {"paths_per_second", reference.paths / std::max(reference.seconds, 1e-9)},
                {"relative_noise", noiseFloor}}},
              {"realtime", table},
              {"seconds", {{"layer", layerSeconds}}}};
  writeJson(folder.path("report.json"), report);
  folder.commit();

  printField("clouds", std::to_string(cmd.width) + "x" + std::to_string(cmd.height) + ", " + kind +
                           ", " + phaseName + " phase (g " +
                           fmt("%.3f", layer.phase().meanCosine()) + "), layer " +
                           fmt("%.2f s", layerSeconds));
  printField("reference", fmt("%.2f s", reference.seconds) + ", " + std::to_string(cmd.samples) +
                              " paths per pixel, relative noise " + fmt("%.3f", noiseFloor));
  for (const json& row : table)
    printField(row["variant"].get<std::string>(),
               fmt("%.3f s", row["seconds"].get<double>()) + ", relative RMSE " +
                   fmt("%.3f", row["relative_rmse"].get<double>()) + ", bias " +
                   fmt("%+.3f", row["relative_bias"].get<double>()) + ", " +
                   fmt("%.0fx faster", row["speedup"].get<double>()));
  if (scene) printField("scene", cmd.scene);
  printField("wrote", cmd.out);
}

}  // namespace

void addCloudsCommand(CLI::App& app) {
  auto cmd = std::make_shared<CloudsCommand>();
  CLI::App* sub = app.add_subcommand(
      "clouds",
      "A cloud layer by the volumetric path tracer and by the real-time ray-marching model, "
      "with the model's error and time per feature");
  media::CloudLayerSettings& l = cmd->layer;
  sub->add_option("--width", cmd->width, "Image width")
      ->check(CLI::Range(4, 4096))
      ->capture_default_str();
  sub->add_option("--height", cmd->height, "Image height")
      ->check(CLI::Range(4, 4096))
      ->capture_default_str();
  sub->add_option("--samples", cmd->samples, "Reference paths per pixel")
      ->check(CLI::Range(1, 1 << 20))
      ->capture_default_str();
  CLI::Option* sceneOption =
      sub->add_option("--scene", cmd->scene,
                      "Volume scene file (JSON, docs/formats.md): medium, sun, camera and ground; "
                      "--sun-*, --camera-elevation and --fov given override it");
  CLI::Option* phaseOption =
      sub->add_option("--phase", cmd->phase,
                      "Phase function: isotropic, rayleigh, henyey-greenstein, "
                      "double-henyey-greenstein or mie-cloud")
          ->capture_default_str();
  CLI::Option* phaseParamsOption =
      sub->add_option("--phase-params", cmd->phaseParams, "Its parameters, e.g. \"g=0.85\"");
  CLI::Option* coverageOption = sub->add_option("--coverage", l.coverage, "Cloud cover in [0, 1]")
                                    ->check(FiniteRange(0, 1))
                                    ->capture_default_str();
  CLI::Option* cloudTypeOption =
      sub->add_option("--cloud-type", l.cloudType, "0 stratus, 0.5 stratocumulus, 1 cumulus")
          ->check(FiniteRange(0, 1))
          ->capture_default_str();
  CLI::Option* extinctionOption =
      sub->add_option("--extinction", l.extinction,
                      "Extinction of dense cloud, 1/m (OPAC: 0.04-0.12)")
          ->check(FinitePositive)
          ->capture_default_str();
  CLI::Option* albedoOption = sub->add_option("--albedo", l.albedo, "Single-scattering albedo")
                                  ->check(FiniteRange(0, 1))
                                  ->capture_default_str();
  CLI::Option* bottomOption = sub->add_option("--bottom", l.bottom, "Layer bottom, m")
                                  ->check(FiniteNonNegative)
                                  ->capture_default_str();
  CLI::Option* topOption =
      sub->add_option("--top", l.top, "Layer top, m")->check(FinitePositive)->capture_default_str();
  // The layer's own options describe the medium the scene file gives.
  for (CLI::Option* layerOption : {phaseOption, phaseParamsOption, coverageOption, cloudTypeOption,
                                   extinctionOption, albedoOption, bottomOption, topOption})
    sceneOption->excludes(layerOption);
  sub->add_option("--seed", cmd->seed,
                  "Seed of the samples, and of the cloud noise unless --scene gives the medium")
      ->capture_default_str();
  cmd->sunElevationOption = sub->add_option("--sun-elevation", cmd->sunElevation, "Degrees")
                                ->check(FiniteRange(-90, 90))
                                ->capture_default_str();
  cmd->sunAzimuthOption =
      sub->add_option("--sun-azimuth", cmd->sunAzimuth, "Degrees clockwise from north")
          ->check(FiniteRange(-360, 360))
          ->capture_default_str();
  cmd->cameraElevationOption = sub->add_option("--camera-elevation", cmd->cameraElevation,
                                               "Degrees above the horizon (looking north)")
                                   ->check(FiniteRange(-89, 89))
                                   ->capture_default_str();
  cmd->fovOption = sub->add_option("--fov", cmd->fov, "Vertical field of view, degrees")
                       ->check(FiniteRange(1, 179))
                       ->capture_default_str();
  sub->add_option("--primary-steps", cmd->march.primarySteps, "Real-time model: view steps")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  sub->add_option("--light-steps", cmd->march.lightSteps, "Real-time model: steps to the sun")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  sub->add_option("--octaves", cmd->march.octaves, "Real-time model: multiple-scattering octaves")
      ->check(CLI::Range(1, 16))
      ->capture_default_str();
  sub->add_flag("--sky-nee,!--no-sky-nee", cmd->skyNee,
                "Reference: next-event estimation to the sky at every scattering event")
      ->capture_default_str();
  sub->add_option("--exposure", cmd->exposure, "Image exposure (default: automatic)")
      ->check(FiniteNonNegative);
  sub->add_option("--out", cmd->out, "Output folder")->capture_default_str();
  sub->callback([cmd] {
    if (cmd->scene.empty() && !(cmd->layer.top > cmd->layer.bottom))
      throw CLI::ValidationError("--top", "must be above --bottom");
    runClouds(*cmd);
  });
}

}  // namespace radkit::app
