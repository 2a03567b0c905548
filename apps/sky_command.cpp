// radkit sky: images of the physically based sky of atmosphere/ (docs/atmosphere.md) —
// fisheye, panorama and camera views as PFM and PNG — with their timing, and optionally the
// model against the brute-force path tracer (--compare). Writes report.json.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "apps/common.h"
#include "atmosphere/rayleigh.h"
#include "job/sky_job.h"
#include "util/errors.h"

namespace radkit::app {

namespace {

using nlohmann::json;

struct SkyCommand {
  SkyJobSettings job;
  bool noMultipleScattering = false;
  std::vector<double> cameraDirection{180, 20};  ///< azimuth, elevation (degrees)
};

void printSummary(const SkyJobResult& r) {
  for (const json& image : r.report["images"])
    printField("sky-" + image["projection"].get<std::string>(),
               fmt("%.0f", image["width"].get<double>()) +
                   fmt("×%.0f", image["height"].get<double>()) +
                   fmt(", %.3f s", image["seconds"].get<double>()) +
                   fmt(", %.3g view rays/s", image["view_rays_per_second"].get<double>()));
  const json& zenith = r.report["radiance"]["zenith"];
  const json& diffuse = r.report["irradiance"]["diffuse_horizontal"];
  printField("zenith", fmt("%.4g", zenith[0].get<double>()) +
                           fmt(" %.4g", zenith[1].get<double>()) +
                           fmt(" %.4g W m⁻² sr⁻¹", zenith[2].get<double>()));
  printField("diffuse E_h", fmt("%.4g", diffuse[0].get<double>()) +
                                fmt(" %.4g", diffuse[1].get<double>()) +
                                fmt(" %.4g W/m²", diffuse[2].get<double>()));
  if (r.report.contains("comparison")) {
    std::printf("\n%s\n", r.comparisonTable.c_str());
    printField("comparison", fmt("%.1f s", r.report["comparison"]["seconds"].get<double>()));
  }
  printField("wrote", r.out);
}

}  // namespace

void addSkyCommand(CLI::App& app) {
  auto cmd = std::make_shared<SkyCommand>();
  CLI::App* sub = app.add_subcommand(
      "sky",
      "Physically based sky (Rayleigh and Mie single scattering with Hillaire's multiple "
      "scattering): fisheye, panorama and camera images, and --compare against a path tracer");
  sub->add_option("--elevation", cmd->job.sunElevationDeg, "Sun elevation in degrees")
      ->check(FiniteRange(-90, 90))
      ->capture_default_str();
  sub->add_option("--azimuth", cmd->job.sunAzimuthDeg,
                  "Sun azimuth in degrees, clockwise from north")
      ->check(FiniteRange(-360, 360))
      ->capture_default_str();
  sub->add_option("--size", cmd->job.size, "Image height in pixels (the panorama is twice as wide)")
      ->check(CLI::Range(16, 8192))
      ->capture_default_str();
  sub->add_option("--projection", cmd->job.projection, "Which images to write")
      ->check(CLI::IsMember({"fisheye", "panorama", "camera", "all"}))
      ->capture_default_str();
  sub->add_option("--view-samples", cmd->job.sky.viewSamples,
                  "Ray-march samples along each view ray")
      ->check(CLI::Range(1, 4096))
      ->capture_default_str();
  sub->add_option("--light-samples", cmd->job.sky.lightSamples,
                  "Samples along each sample's ray to the sun")
      ->check(CLI::Range(1, 4096))
      ->capture_default_str();
  sub->add_flag("--no-multiple-scattering", cmd->noMultipleScattering,
                "Single scattering only (no Hillaire 2020 term)");
  sub->add_option("--density", cmd->job.relativeDensity,
                  "Air density relative to the standard one (scales Rayleigh and Mie alike)")
      ->check(FiniteRange(1e-6, 100))
      ->capture_default_str();
  sub->add_option("--rayleigh", cmd->job.rayleigh,
                  "The air's Rayleigh scattering: " + atmosphere::rayleighRegistry().namesText() +
                      " (bodhaine:co2=PPM; docs/atmosphere.md)")
      ->capture_default_str();
  sub->add_option("--altitude", cmd->job.altitude, "Observer's height above the ground in metres")
      ->check(FiniteRange(0, 50000))
      ->capture_default_str();
  sub->add_option("--camera-direction", cmd->cameraDirection,
                  "Camera view: AZIMUTH ELEVATION in degrees (azimuth clockwise from north)")
      ->expected(2)
      ->check(FiniteRange(-360, 360))
      ->capture_default_str();
  sub->add_option("--fov", cmd->job.fovDeg, "Camera view: horizontal field of view in degrees")
      ->check(FiniteRange(1, 179))
      ->capture_default_str();
  sub->add_option("--exposure", cmd->job.exposure,
                  "Radiance multiplier before tone mapping; 0: automatic per image")
      ->check(FiniteNonNegative)
      ->capture_default_str();
  sub->add_option("--compare", cmd->job.comparePaths,
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
  sub->add_option("--compare-elevations", cmd->job.compareElevationsDeg,
                  "Sun elevations (degrees) of the --compare table")
      ->check(FiniteRange(-90, 90))
      ->capture_default_str();
  sub->add_option("--seed", cmd->job.seed, "Random seed of the reference path tracer")
      ->check(Unsigned)
      ->capture_default_str();
  sub->add_flag("--exr", cmd->job.exr, "Also write each image as OpenEXR (linear, float)");
  sub->add_option("--out", cmd->job.out, "Output folder")->capture_default_str();
  sub->callback([cmd] {
    if (std::fabs(cmd->cameraDirection[1]) > 90)
      throw InputError("--camera-direction: elevation " + fmt("%g", cmd->cameraDirection[1]) +
                       " is outside [-90, 90]. Fix: give AZIMUTH ELEVATION in degrees");
    cmd->job.sky.multipleScattering = !cmd->noMultipleScattering;
    cmd->job.cameraAzimuthDeg = cmd->cameraDirection[0];
    cmd->job.cameraElevationDeg = cmd->cameraDirection[1];
    printSummary(runSkyJob(cmd->job));
  });
}

}  // namespace radkit::app
