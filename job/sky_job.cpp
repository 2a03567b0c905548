#include "job/sky_job.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "atmosphere/rayleigh.h"
#include "atmosphere/sky_image.h"
#include "experiments/sky_comparison.h"
#include "job/report.h"
#include "render/exr_io.h"
#include "render/hdr_io.h"
#include "render/radiosity_image.h"
#include "util/format.h"
#include "util/output_folder.h"

namespace radkit {

namespace {

using nlohmann::json;
namespace atmo = radkit::atmosphere;

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

}  // namespace

SkyJobResult runSkyJob(const SkyJobSettings& cmd) {
  if (cmd.projection != "fisheye" && cmd.projection != "panorama" && cmd.projection != "camera" &&
      cmd.projection != "all")
    throw std::invalid_argument("sky: projection \"" + cmd.projection +
                                "\" is none of fisheye, panorama, camera, all");
  if (std::fabs(cmd.cameraElevationDeg) > 90)
    throw std::invalid_argument("sky: camera elevation " +
                                formatValue("%g", cmd.cameraElevationDeg) +
                                " is outside [-90, 90]");
  if (cmd.comparePaths == 1)
    throw std::invalid_argument(
        "sky: 1 reference path gives no standard error; give 0 or at least 2");
  SkyJobResult result;
  result.out = cmd.out;
  const auto start = std::chrono::steady_clock::now();
  OutputFolder folder(cmd.out);  // refuses an --out it cannot replace before the work
  atmo::AtmosphereParameters parameters;
  parameters.relativeDensity = cmd.relativeDensity;
  atmo::RayleighAir rayleigh;
  try {
    rayleigh = atmo::rayleighAir(cmd.rayleigh);
  } catch (const ParamError& e) {
    throw std::invalid_argument(std::string("sky: ") + e.what());
  }
  atmo::useRayleigh(parameters, rayleigh);
  const atmo::Atmosphere air(parameters);
  const atmo::SkySettings& sky = cmd.sky;
  const Vec3 sun = atmo::sunDirection(cmd.sunElevationDeg, cmd.sunAzimuthDeg);
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
    s.fovDeg = cmd.fovDeg;
    s.cameraDirection = atmo::sunDirection(cmd.cameraElevationDeg, cmd.cameraAzimuthDeg);
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
  }

  const Vec3 zenith = air.skyRadiance(eye, {0, 0, 1}, sun, sky);
  const Vec3 towardSun = air.skyRadiance(eye, atmo::sunDirection(2, cmd.sunAzimuthDeg), sun, sky);
  const Vec3 awayFromSun =
      air.skyRadiance(eye, atmo::sunDirection(2, cmd.sunAzimuthDeg + 180), sun, sky);
  const Vec3 diffuse = atmo::modelHorizontalIrradiance(air, eye, sun, sky);
  const Vec3 direct = air.sunIrradiance(eye, sun) * std::max(0.0, sun.z);
  json& report = result.report;
  report = json{
      {"radkit", RADKIT_VERSION},
      {"command", "sky"},
      {"settings",
       {{"sun_elevation_deg", cmd.sunElevationDeg},
        {"sun_azimuth_deg", cmd.sunAzimuthDeg},
        {"relative_density", cmd.relativeDensity},
        {"rayleigh", cmd.rayleigh},
        {"altitude_m", cmd.altitude},
        {"view_samples", sky.viewSamples},
        {"light_samples", sky.lightSamples},
        {"multiple_scattering", sky.multipleScattering},
        {"size", cmd.size},
        {"projection", cmd.projection},
        {"camera_azimuth_deg", cmd.cameraAzimuthDeg},
        {"camera_elevation_deg", cmd.cameraElevationDeg},
        {"fov_deg", cmd.fovDeg},
        {"seed", cmd.seed}}},
      {"images", images},
      {"radiance",
       {{"zenith", vec3Json(zenith)},
        {"horizon_toward_sun_2deg", vec3Json(towardSun)},
        {"horizon_away_from_sun_2deg", vec3Json(awayFromSun)}}},
      {"rayleigh",
       {{"model", cmd.rayleigh},
        {"scattering_per_m", vec3Json(parameters.rayleighScattering)},
        {"scale_height_m", parameters.rayleighScaleHeight},
        {"wavelengths_nm",
         {1e9 * atmo::kWavelengths[0], 1e9 * atmo::kWavelengths[1], 1e9 * atmo::kWavelengths[2]}},
        // Vertical, ground to the top of the atmosphere, at the run's density.
        {"optical_depth",
         vec3Json(atmo::rayleighOpticalDepth(parameters.rayleighScattering * cmd.relativeDensity,
                                             parameters.rayleighScaleHeight,
                                             parameters.topRadius - parameters.groundRadius))}}},
      {"irradiance",
       {{"diffuse_horizontal", vec3Json(diffuse)},
        {"direct_horizontal", vec3Json(direct)},
        {"direct_normal", vec3Json(air.sunIrradiance(eye, sun))}}}};
  if (cmd.comparePaths > 0) {
    atmo::ComparisonSettings cs;
    cs.sunElevationsDeg = cmd.compareElevationsDeg;
    cs.sunAzimuthDeg = cmd.sunAzimuthDeg;
    cs.altitude = cmd.altitude;
    cs.paths = cmd.comparePaths;
    cs.seed = cmd.seed;
    cs.sky = sky;
    const auto t = std::chrono::steady_clock::now();
    const std::vector<atmo::ComparisonRow> rows = atmo::compareWithReference(air, cs);
    const double seconds = secondsSince(t);
    result.comparisonTable = atmo::comparisonMarkdown(rows);
    writeFileAtomically(folder.path("comparison.md"), result.comparisonTable);
    report["comparison"] = {
        {"paths", cmd.comparePaths}, {"seconds", seconds}, {"rows", comparisonJson(rows)}};
  }
  report["seconds"] = secondsSince(start);
  writeJson(folder.path("report.json"), report);
  folder.commit();
  return result;
}

}  // namespace radkit
