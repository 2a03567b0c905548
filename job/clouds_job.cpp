#include "job/clouds_job.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "experiments/cloud_comparison.h"
#include "job/report.h"
#include "media/medium_json.h"
#include "media/volume_tracer.h"
#include "render/camera.h"
#include "render/hdr_io.h"
#include "util/canvas.h"
#include "util/errors.h"
#include "util/format.h"
#include "util/output_folder.h"
#include "util/setting_names.h"

namespace radkit {

using nlohmann::json;

CloudsJobSettings::CloudsJobSettings() : skyNee(CloudComparisonSettings{}.skyNee) {}

CloudsJobResult runCloudsJob(const CloudsJobSettings& cmd) {
  CloudsJobResult r;
  r.out = cmd.out;
  // The scene file is read before the output folder exists: a bad file leaves nothing behind.
  const auto start = std::chrono::steady_clock::now();
  std::optional<media::VolumeScene> scene;
  std::unique_ptr<media::Medium> medium;
  std::string kind = "cloud-layer", phaseName = cmd.phase;
  double sunElevation = 40, sunAzimuth = 150;
  if (!cmd.scene.empty()) {
    scene = media::loadVolumeScene(cmd.scene);
    medium = std::move(scene->medium);
    kind = scene->kind, phaseName = scene->phaseName;
    if (scene->sunElevationDeg) sunElevation = *scene->sunElevationDeg;
    if (scene->sunAzimuthDeg) sunAzimuth = *scene->sunAzimuthDeg;
  } else {
    if (!(cmd.layer.top > cmd.layer.bottom))
      throw std::invalid_argument("clouds: the layer's top must be above its bottom");
    media::CloudLayerSettings layerSettings = cmd.layer;
    layerSettings.seed = std::uint32_t(cmd.seed);  // without a scene file the seed seeds the noise
    medium = std::make_unique<media::CloudLayer>(layerSettings,
                                                 makePhaseFunction(cmd.phase, cmd.phaseParams));
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
      throw InputError(
          (scene ? cmd.scene + ": the medium's" : std::string(setting("extinction") + ":")) +
          " extinction " + formatValue("%g", layer.majorant()) + " /m across a medium " +
          formatValue("%g", extent) + " m wide is an optical extent of " +
          formatValue("%g", depth) +
          ", and a path takes about that many tracking steps (the limit is " +
          formatValue("%g", kMaxOpticalExtent) + "). Fix: give an extinction below " +
          formatValue("%g", kMaxOpticalExtent / extent) +
          " /m (dense cloud is 0.05-0.12 /m) or a smaller medium");
  }
  const double groundAlbedo = scene ? scene->groundAlbedo : 0.0;
  const double layerSeconds = secondsSince(start);
  OutputFolder folder(cmd.out);
  const Bounds3 bounds = layer.bounds();

  // The file's camera unless --camera-elevation or --fov overrides it; otherwise on the ground
  // looking north, --camera-elevation above the horizon.
  sunElevation = cmd.sunElevationDeg.value_or(sunElevation);
  sunAzimuth = cmd.sunAzimuthDeg.value_or(sunAzimuth);
  const double fov = cmd.fovDeg.value_or(70);
  Camera camera;
  const double e = cmd.cameraElevationDeg.value_or(25) * M_PI / 180;
  if (scene && scene->camera) {
    camera = *scene->camera;
    if (cmd.cameraElevationDeg) {
      // Keep the file's position and heading; tilt to the given elevation.
      const Vec3 f = camera.lookAt - camera.position;
      const double h = std::hypot(f.x, f.y);
      const double hx = h > 0 ? f.x / h : 0, hy = h > 0 ? f.y / h : 1;
      camera.lookAt = camera.position + Vec3{hx * std::cos(e), hy * std::cos(e), std::sin(e)};
    }
    if (cmd.fovDeg) camera.fovDeg = *cmd.fovDeg;
  } else {
    camera.position = {0, 0, 1.7};
    camera.lookAt = camera.position + Vec3{0, std::cos(e), std::sin(e)};
    camera.up = {0, 0, 1};
    camera.fovDeg = fov;
  }
  const Vec3 forward = normalize(camera.lookAt - camera.position);
  const double cameraElevation = scene && scene->camera && !cmd.cameraElevationDeg
                                     ? std::asin(std::clamp(forward.z, -1.0, 1.0)) * 180 / M_PI
                                     : cmd.cameraElevationDeg.value_or(25);
  if (!(length(cross(camera.lookAt - camera.position, camera.up)) > 0))
    throw InputError((scene ? cmd.scene + ": " : std::string()) +
                     "the camera's view is parallel to its \"up\" after " +
                     setting("camera_elevation") +
                     ". "
                     "Fix: give another " +
                     setting("camera_elevation") +
                     ", or the camera an \"up\" across "
                     "the view");
  CloudComparisonSettings cs;
  cs.width = cmd.width, cs.height = cmd.height, cs.samples = cmd.samples, cs.seed = cmd.seed;
  cs.sunElevationDeg = sunElevation, cs.sunAzimuthDeg = sunAzimuth;
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
                {"sun_elevation_deg", sunElevation},
                {"sun_azimuth_deg", sunAzimuth},
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
  json& report = r.report;
  report = json{{"radkit", RADKIT_VERSION},
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
  return r;
}

}  // namespace radkit
