// radkit clouds: a cloud layer under the physical sky, rendered by the volumetric path tracer
// (the reference) and by the real-time model with each of its features switched on in turn,
// with a table of error against time (docs/clouds.md).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "apps/common.h"
#include "apps/report.h"
#include "atmosphere/atmosphere.h"
#include "daylight/sky.h"
#include "media/cloud_marcher.h"
#include "media/medium.h"
#include "media/volume_tracer.h"
#include "render/camera.h"
#include "render/hdr_io.h"
#include "util/canvas.h"
#include "util/format.h"
#include "util/output_folder.h"

namespace radkit::app {

namespace {

using nlohmann::json;

struct CloudsCommand {
  media::CloudLayerSettings layer;
  // HG with the Mie cloud table's g: the table's forward peak (thousands per sr) makes the
  // reference's sun estimates fireflies (docs/clouds.md); --phase mie-cloud uses it.
  std::string phase = "henyey-greenstein", phaseParams = "g=0.86";
  int width = 128, height = 72, samples = 32;
  double sunElevation = 40, sunAzimuth = 150, cameraElevation = 25, fov = 70;
  double exposure = 0;
  std::uint64_t seed = 1;
  media::MarchSettings march;
  std::string out = "out/clouds";
};

/// (Σ a − Σ reference)/Σ reference over pixels and channels: the brightness bias, which the
/// reference's noise averages out of.
double relativeBias(const std::vector<Vec3>& a, const std::vector<Vec3>& reference) {
  double sa = 0, sr = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    sa += a[i].x + a[i].y + a[i].z, sr += reference[i].x + reference[i].y + reference[i].z;
  return sr > 0 ? (sa - sr) / sr : 0.0;
}

/// Root-mean-square difference over pixels and channels, relative to the reference's mean.
double relativeRmse(const std::vector<Vec3>& a, const std::vector<Vec3>& reference) {
  double sum = 0, mean = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const Vec3 e = a[i] - reference[i];
    sum += dot(e, e) / 3;
    mean += (reference[i].x + reference[i].y + reference[i].z) / 3;
  }
  mean /= double(a.size());
  return mean > 0 ? std::sqrt(sum / double(a.size())) / mean : 0.0;
}

void runClouds(CloudsCommand& cmd) {
  OutputFolder folder(cmd.out);
  const auto start = std::chrono::steady_clock::now();
  media::CloudLayer layer(cmd.layer, media::makePhaseFunction(cmd.phase, cmd.phaseParams));
  const double layerSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  // Sun and sky from the atmosphere: the sun's irradiance at the layer's middle altitude, the
  // sky tabulated as daylight/ does for scenes (black ground below the horizon).
  SkyDescription sd;
  sd.type = SkyDescription::Type::Physical;
  sd.sun = true, sd.sunElevationDeg = cmd.sunElevation, sd.sunAzimuthDeg = cmd.sunAzimuth;
  const SkyModel sky(sd);
  const atmosphere::Atmosphere air;
  const Vec3 sunLocal = atmosphere::sunDirection(cmd.sunElevation, cmd.sunAzimuth);
  media::Lighting light;
  light.sunDirection = sunLocal;
  light.sunIrradiance =
      air.sunIrradiance(air.pointAtAltitude((cmd.layer.bottom + cmd.layer.top) / 2), sunLocal);
  light.sky = [&](const Vec3& d) { return sky.radiance(d); };
  light.skySampler = std::make_shared<const media::SkySampler>(light.sky);
  cmd.march.ambientTop = sky.horizontalSky() / M_PI;  // cosine-weighted mean sky radiance
  cmd.march.ambientBottom = {0, 0, 0};                // black ground, as the reference's

  Camera camera;
  camera.position = {0, 0, 1.7};
  const double e = cmd.cameraElevation * M_PI / 180;
  camera.lookAt = camera.position + Vec3{0, std::cos(e), std::sin(e)};
  camera.up = {0, 0, 1};
  camera.fovDeg = cmd.fov;
  const PinholeCamera pinhole(camera, cmd.width, cmd.height);
  const auto ray = [&](double x, double y) { return pinhole.direction(x, y); };

  const media::VolumeImage reference = media::renderVolume(
      layer, light, camera.position, ray, cmd.width, cmd.height, cmd.samples, cmd.seed);
  // The reference's own noise: the RMSE an exact image would show against it.
  double noise = 0, mean = 0;
  for (std::size_t i = 0; i < reference.radiance.size(); ++i) {
    noise += dot(reference.standardError[i], reference.standardError[i]) / 3;
    mean += (reference.radiance[i].x + reference.radiance[i].y + reference.radiance[i].z) / 3;
  }
  mean /= double(reference.radiance.size());
  const double noiseFloor =
      mean > 0 ? std::sqrt(noise / double(reference.radiance.size())) / mean : 0;

  // The features switched on one by one, then the step counts.
  struct Variant {
    std::string name;
    media::MarchSettings settings;
  };
  std::vector<Variant> variants;
  media::MarchSettings s = cmd.march;
  s.octaves = 1, s.ambient = false, s.jitter = false;
  variants.push_back({"single scattering", s});
  s.ambient = true;
  variants.push_back({"+ ambient", s});
  s.octaves = cmd.march.octaves;
  variants.push_back({"+ " + std::to_string(s.octaves) + " octaves", s});
  s.jitter = true;
  variants.push_back({"+ blue-noise jitter (defaults)", s});
  media::MarchSettings coarse = s, fine = s;
  coarse.primarySteps = std::max(1, s.primarySteps / 2),
  coarse.lightSteps = std::max(1, s.lightSteps / 2);
  fine.primarySteps = s.primarySteps * 4, fine.lightSteps = s.lightSteps * 4;
  variants.push_back({"defaults, half the steps", coarse});
  variants.push_back({"defaults, 4x the steps", fine});

  double exposure = cmd.exposure;
  if (!(exposure > 0)) exposure = mean > 0 ? 0.18 / luminance(Vec3{mean, mean, mean}) : 1;
  json table = json::array();
  const media::VolumeImage* defaults = nullptr;
  std::vector<media::VolumeImage> images;
  images.reserve(variants.size());
  for (const Variant& v : variants) {
    images.push_back(media::renderMarched(layer, light, camera.position, ray, cmd.width, cmd.height,
                                          v.settings, cmd.seed));
    const media::VolumeImage& img = images.back();
    if (v.name.rfind("+ blue-noise", 0) == 0) defaults = &img;
    table.push_back({{"variant", v.name},
                     {"primary_steps", v.settings.primarySteps},
                     {"light_steps", v.settings.lightSteps},
                     {"octaves", v.settings.octaves},
                     {"ambient", v.settings.ambient},
                     {"jitter", v.settings.jitter},
                     {"seconds", img.seconds},
                     {"relative_rmse", relativeRmse(img.radiance, reference.radiance)},
                     {"relative_bias", relativeBias(img.radiance, reference.radiance)},
                     {"speedup", reference.seconds / std::max(img.seconds, 1e-9)}});
  }
  writeLinearAndPng(folder.path("clouds-reference"),
                    pixelImage(cmd.width, cmd.height, reference.radiance, exposure));
  writeLinearAndPng(folder.path("clouds-realtime"),
                    pixelImage(cmd.width, cmd.height, defaults->radiance, exposure));
  writePng(folder.path("clouds-difference.png"),
           toneMapCurve(relativeDifferenceImage(cmd.width, cmd.height, defaults->radiance,
                                                reference.radiance),
                        1, ToneCurve::Srgb));

  const media::CloudLayerSettings& l = cmd.layer;
  json report{{"radkit", RADKIT_VERSION},
              {"command", "clouds"},
              {"settings",
               {{"width", cmd.width},
                {"height", cmd.height},
                {"samples", cmd.samples},
                {"seed", cmd.seed},
                {"phase", cmd.phase},
                {"phase_mean_cosine", layer.phase().meanCosine()},
                {"bottom_m", l.bottom},
                {"top_m", l.top},
                {"coverage", l.coverage},
                {"cloud_type", l.cloudType},
                {"extinction_per_m", l.extinction},
                {"albedo", l.albedo},
                {"sun_elevation_deg", cmd.sunElevation},
                {"sun_azimuth_deg", cmd.sunAzimuth},
                {"sun_irradiance_W_m2", vec3Json(light.sunIrradiance)},
                {"camera_elevation_deg", cmd.cameraElevation}}},
              {"reference",
               {{"seconds", reference.seconds},
                {"paths", reference.paths},
                {"paths_per_second", reference.paths / std::max(reference.seconds, 1e-9)},
                {"relative_noise", noiseFloor}}},
              {"realtime", table},
              {"seconds", {{"layer", layerSeconds}}}};
  writeFileAtomically(folder.path("report.json"), report.dump(2) + "\n");
  folder.commit();

  printField("clouds", std::to_string(cmd.width) + "x" + std::to_string(cmd.height) + ", " +
                           cmd.phase + " phase (g " + fmt("%.3f", layer.phase().meanCosine()) +
                           "), layer " + fmt("%.2f s", layerSeconds));
  printField("reference", fmt("%.2f s", reference.seconds) + ", " + std::to_string(cmd.samples) +
                              " paths per pixel, relative noise " + fmt("%.3f", noiseFloor));
  for (const json& row : table)
    printField(row["variant"].get<std::string>(),
               fmt("%.3f s", row["seconds"].get<double>()) + ", relative RMSE " +
                   fmt("%.3f", row["relative_rmse"].get<double>()) + ", bias " +
                   fmt("%+.3f", row["relative_bias"].get<double>()) + ", " +
                   fmt("%.0fx faster", row["speedup"].get<double>()));
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
  sub->add_option("--phase", cmd->phase,
                  "Phase function: isotropic, rayleigh, henyey-greenstein, "
                  "double-henyey-greenstein or mie-cloud")
      ->capture_default_str();
  sub->add_option("--phase-params", cmd->phaseParams, "Its parameters, e.g. \"g=0.85\"");
  sub->add_option("--coverage", l.coverage, "Cloud cover in [0, 1]")
      ->check(FiniteRange(0, 1))
      ->capture_default_str();
  sub->add_option("--cloud-type", l.cloudType, "0 stratus, 0.5 stratocumulus, 1 cumulus")
      ->check(FiniteRange(0, 1))
      ->capture_default_str();
  sub->add_option("--extinction", l.extinction, "Extinction of dense cloud, 1/m (OPAC: 0.04-0.12)")
      ->check(FinitePositive)
      ->capture_default_str();
  sub->add_option("--albedo", l.albedo, "Single-scattering albedo")
      ->check(FiniteRange(0, 1))
      ->capture_default_str();
  sub->add_option("--bottom", l.bottom, "Layer bottom, m")
      ->check(FiniteNonNegative)
      ->capture_default_str();
  sub->add_option("--top", l.top, "Layer top, m")->check(FinitePositive)->capture_default_str();
  sub->add_option("--seed", cmd->seed, "Seed of the noise and of the samples")
      ->capture_default_str();
  sub->add_option("--sun-elevation", cmd->sunElevation, "Degrees")
      ->check(FiniteRange(-90, 90))
      ->capture_default_str();
  sub->add_option("--sun-azimuth", cmd->sunAzimuth, "Degrees clockwise from north")
      ->check(FiniteRange(-360, 360))
      ->capture_default_str();
  sub->add_option("--camera-elevation", cmd->cameraElevation,
                  "Degrees above the horizon (looking north)")
      ->check(FiniteRange(-89, 89))
      ->capture_default_str();
  sub->add_option("--fov", cmd->fov, "Vertical field of view, degrees")
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
  sub->add_option("--exposure", cmd->exposure, "Image exposure (default: automatic)")
      ->check(FiniteNonNegative);
  sub->add_option("--out", cmd->out, "Output folder")->capture_default_str();
  sub->callback([cmd] {
    if (!(cmd->layer.top > cmd->layer.bottom))
      throw CLI::ValidationError("--top", "must be above --bottom");
    runClouds(*cmd);
  });
}

}  // namespace radkit::app
