// radkit sky: images of the physically based sky of atmosphere/ (docs/atmosphere.md) —
// fisheye, panorama and camera views as PFM and PNG — with their timing, and optionally the
// model against the brute-force path tracer (--compare). Writes report.json.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "apps/common.h"
#include "atmosphere/atmosphere.h"
#include "atmosphere/sky_image.h"
#include "experiments/sky_comparison.h"
#include "job/report.h"
#include "render/exr_io.h"
#include "render/hdr_io.h"
#include "render/radiosity_image.h"
#include "util/canvas.h"
#include "util/errors.h"
#include "util/output_folder.h"

namespace radkit::app {

namespace {

using nlohmann::json;
namespace atmo = radkit::atmosphere;

struct SkyCommand {
  double elevation = 30, azimuth = 180, density = 1, altitude = 1, fov = 90, exposure = 0;
  int size = 512;
  std::string projection = "all", out = "out/sky";
  atmo::SkySettings sky;
  bool noMultipleScattering = false, exr = false;
  std::vector<double> cameraDirection{180, 20};  ///< azimuth, elevation (degrees)
  long long compare = 0;
  std::vector<double> compareElevations{2, 10, 30, 60, 90};
  std::uint64_t seed = 1;
};

/// Maps the 95th percentile of the luminance of the pixels with a direction to 0.8, as
/// render's automatic exposure does.
double skyExposure(const std::vector<Vec3>& pixels, const atmo::SkyImageSettings& s) {
  std::vector<double> lum;
  for (int row = 0; row < s.height; ++row)
    for (int column = 0; column < s.width; ++column)
      if (atmo::pixelDirection(s, column, row))
        lum.push_back(luminance(pixels[std::size_t(row) * s.width + column]));
  if (lum.empty()) return 1;
  const std::size_t q = std::min(lum.size() - 1, std::size_t(0.95 * lum.size()));
  std::nth_element(lum.begin(), lum.begin() + q, lum.end());
  return lum[q] > 0 ? 0.8 / lum[q] : 1;
}

json comparisonJson(const std::vector<atmo::ComparisonRow>& rows) {
  json a = json::array();
  for (const atmo::ComparisonRow& r : rows)
    a.push_back({{"sun_elevation_deg", r.sunElevationDeg},
                 {"quantity", r.quantity},
                 {"direction", vec3Json(r.direction)},
                 {"single_scattering", vec3Json(r.singleScattering)},
                 {"single_scattering_fine", vec3Json(r.singleScatteringFine)},
                 {"single_plus_multiple_scattering", vec3Json(r.withMultipleScattering)},
                 {"reference", vec3Json(r.reference.mean)},
                 {"reference_standard_error", vec3Json(r.reference.standardError)},
                 {"reference_paths", r.reference.paths},
                 {"reference_seconds", r.seconds}});
  return a;
}

void run(const SkyCommand& cmd) {
  const auto start = std::chrono::steady_clock::now();
  OutputFolder folder(cmd.out);  // refuses an --out it cannot replace before the work
  atmo::AtmosphereParameters parameters;
  parameters.relativeDensity = cmd.density;
  const atmo::Atmosphere air(parameters);
  atmo::SkySettings sky = cmd.sky;
  sky.multipleScattering = !cmd.noMultipleScattering;
  const Vec3 sun = atmo::sunDirection(cmd.elevation, cmd.azimuth);
  const Vec3 eye = air.pointAtAltitude(cmd.altitude);

  std::vector<atmo::SkyProjection> projections;
  if (cmd.projection == "fisheye" || cmd.projection == "all")
    projections.push_back(atmo::SkyProjection::Fisheye);
  if (cmd.projection == "panorama" || cmd.projection == "all")
    projections.push_back(atmo::SkyProjection::Panorama);
  if (cmd.projection == "camera" || cmd.projection == "all")
    projections.push_back(atmo::SkyProjection::Camera);

  json images = json::array();
  for (atmo::SkyProjection projection : projections) {
    atmo::SkyImageSettings s;
    s.projection = projection;
    s.width = projection == atmo::SkyProjection::Panorama ? 2 * cmd.size : cmd.size;
    s.height = cmd.size;
    s.altitude = cmd.altitude;
    s.fovDeg = cmd.fov;
    s.cameraDirection = atmo::sunDirection(cmd.cameraDirection[1], cmd.cameraDirection[0]);
    s.sky = sky;
    RadianceImage image;
    image.width = s.width;
    image.height = s.height;
    const atmo::SkyBenchmark bench = atmo::benchmarkSky(air, sun, s, &image.radiance);
    image.exposure = cmd.exposure > 0 ? cmd.exposure : skyExposure(image.radiance, s);
    const std::string name = std::string("sky-") + atmo::projectionName(projection);
    writeLinearAndPng(folder.path(name), image);
    if (cmd.exr) writeExr(folder.path(name + ".exr"), image);
    images.push_back({{"projection", atmo::projectionName(projection)},
                      {"width", s.width},
                      {"height", s.height},
                      {"exposure", image.exposure},
                      {"seconds", bench.seconds},
                      {"view_rays", bench.viewRays},
                      {"view_rays_per_second", bench.viewRaysPerSecond},
                      {"view_sample_points_per_second", bench.samplePointsPerSecond}});
    printField(name, fmt("%.0f", s.width) + fmt("×%.0f", s.height) +
                         fmt(", %.3f s", bench.seconds) +
                         fmt(", %.3g view rays/s", bench.viewRaysPerSecond));
  }

  const Vec3 zenith = air.skyRadiance(eye, {0, 0, 1}, sun, sky);
  const Vec3 towardSun = air.skyRadiance(eye, atmo::sunDirection(2, cmd.azimuth), sun, sky);
  const Vec3 awayFromSun = air.skyRadiance(eye, atmo::sunDirection(2, cmd.azimuth + 180), sun, sky);
  const Vec3 diffuse = atmo::modelHorizontalIrradiance(air, eye, sun, sky);
  const Vec3 direct = air.sunIrradiance(eye, sun) * std::max(0.0, sun.z);
  json report{{"radkit", RADKIT_VERSION},
              {"command", "sky"},
              {"settings",
               {{"sun_elevation_deg", cmd.elevation},
                {"sun_azimuth_deg", cmd.azimuth},
                {"relative_density", cmd.density},
                {"altitude_m", cmd.altitude},
                {"view_samples", sky.viewSamples},
                {"light_samples", sky.lightSamples},
                {"multiple_scattering", sky.multipleScattering},
                {"size", cmd.size},
                {"projection", cmd.projection},
                {"camera_azimuth_deg", cmd.cameraDirection[0]},
                {"camera_elevation_deg", cmd.cameraDirection[1]},
                {"fov_deg", cmd.fov},
                {"seed", cmd.seed}}},
              {"images", images},
              {"radiance",
               {{"zenith", vec3Json(zenith)},
                {"horizon_toward_sun_2deg", vec3Json(towardSun)},
                {"horizon_away_from_sun_2deg", vec3Json(awayFromSun)}}},
              {"irradiance",
               {{"diffuse_horizontal", vec3Json(diffuse)},
                {"direct_horizontal", vec3Json(direct)},
                {"direct_normal", vec3Json(air.sunIrradiance(eye, sun))}}}};
  printField("zenith",
             fmt("%.4g", zenith.x) + fmt(" %.4g", zenith.y) + fmt(" %.4g W m⁻² sr⁻¹", zenith.z));
  printField("diffuse E_h",
             fmt("%.4g", diffuse.x) + fmt(" %.4g", diffuse.y) + fmt(" %.4g W/m²", diffuse.z));
  if (cmd.compare > 0) {
    atmo::ComparisonSettings cs;
    cs.sunElevationsDeg = cmd.compareElevations;
    cs.sunAzimuthDeg = cmd.azimuth;
    cs.altitude = cmd.altitude;
    cs.paths = cmd.compare;
    cs.seed = cmd.seed;
    cs.sky = sky;
    const auto t = std::chrono::steady_clock::now();
    const std::vector<atmo::ComparisonRow> rows = atmo::compareWithReference(air, cs);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
    const std::string table = atmo::comparisonMarkdown(rows);
    writeFileAtomically(folder.path("comparison.md"), table);
    report["comparison"] = {
        {"paths", cmd.compare}, {"seconds", seconds}, {"rows", comparisonJson(rows)}};
    std::printf("\n%s\n", table.c_str());
    printField("comparison", fmt("%.1f s", seconds));
  }
  report["seconds"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  writeJson(folder.path("report.json"), report);
  folder.commit();
  printField("wrote", cmd.out);
}

}  // namespace

void addSkyCommand(CLI::App& app) {
  auto cmd = std::make_shared<SkyCommand>();
  CLI::App* sub = app.add_subcommand(
      "sky",
      "Physically based sky (Rayleigh and Mie single scattering with Hillaire's multiple "
      "scattering): fisheye, panorama and camera images, and --compare against a path tracer");
  sub->add_option("--elevation", cmd->elevation, "Sun elevation in degrees")
      ->check(FiniteRange(-90, 90))
      ->capture_default_str();
  sub->add_option("--azimuth", cmd->azimuth, "Sun azimuth in degrees, clockwise from north")
      ->check(FiniteRange(-360, 360))
      ->capture_default_str();
  sub->add_option("--size", cmd->size, "Image height in pixels (the panorama is twice as wide)")
      ->check(CLI::Range(16, 8192))
      ->capture_default_str();
  sub->add_option("--projection", cmd->projection, "Which images to write")
      ->check(CLI::IsMember({"fisheye", "panorama", "camera", "all"}))
      ->capture_default_str();
  sub->add_option("--view-samples", cmd->sky.viewSamples, "Ray-march samples along each view ray")
      ->check(CLI::Range(1, 4096))
      ->capture_default_str();
  sub->add_option("--light-samples", cmd->sky.lightSamples,
                  "Samples along each sample's ray to the sun")
      ->check(CLI::Range(1, 4096))
      ->capture_default_str();
  sub->add_flag("--no-multiple-scattering", cmd->noMultipleScattering,
                "Single scattering only (no Hillaire 2020 term)");
  sub->add_option("--density", cmd->density,
                  "Air density relative to the standard one (scales Rayleigh and Mie alike)")
      ->check(FiniteRange(1e-6, 100))
      ->capture_default_str();
  sub->add_option("--altitude", cmd->altitude, "Observer's height above the ground in metres")
      ->check(FiniteRange(0, 50000))
      ->capture_default_str();
  sub->add_option("--camera-direction", cmd->cameraDirection,
                  "Camera view: AZIMUTH ELEVATION in degrees (azimuth clockwise from north)")
      ->expected(2)
      ->check(FiniteRange(-360, 360))
      ->capture_default_str();
  sub->add_option("--fov", cmd->fov, "Camera view: horizontal field of view in degrees")
      ->check(FiniteRange(1, 179))
      ->capture_default_str();
  sub->add_option("--exposure", cmd->exposure,
                  "Radiance multiplier before tone mapping; 0: automatic per image")
      ->check(FiniteNonNegative)
      ->capture_default_str();
  sub->add_option("--compare", cmd->compare,
                  "Reference paths per direction: compare the model with a volumetric path "
                  "tracer at the --compare-elevations (comparison.md, report.json); 0: skip")
      ->check(CLI::Range(0LL, 10000000000LL))
      ->check(CLI::Validator(
          [](std::string& text) -> std::string {
            // One path has no standard error, and the table's z column divides by it.
            return std::strtoll(text.c_str(), nullptr, 10) == 1
                       ? "1 path gives no standard error. Fix: give 0 or at least 2"
                       : "";
          },
          "0 or >= 2"))
      ->capture_default_str();
  sub->add_option("--compare-elevations", cmd->compareElevations,
                  "Sun elevations (degrees) of the --compare table")
      ->check(FiniteRange(-90, 90))
      ->capture_default_str();
  sub->add_option("--seed", cmd->seed, "Random seed of the reference path tracer")
      ->check(Unsigned)
      ->capture_default_str();
  sub->add_flag("--exr", cmd->exr, "Also write each image as OpenEXR (linear, float)");
  sub->add_option("--out", cmd->out, "Output folder")->capture_default_str();
  sub->callback([cmd] {
    if (std::fabs(cmd->cameraDirection[1]) > 90)
      throw InputError("--camera-direction: elevation " + fmt("%g", cmd->cameraDirection[1]) +
                       " is outside [-90, 90]. Fix: give AZIMUTH ELEVATION in degrees");
    run(*cmd);
  });
}

}  // namespace radkit::app
