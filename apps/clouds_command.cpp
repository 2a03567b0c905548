// radkit clouds: a cloud layer under the physical sky, rendered by the volumetric path tracer
// (the reference) and by the real-time model with each of its features switched on in turn,
// with a table of error against time (docs/clouds.md).
#include <memory>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "apps/common.h"
#include "job/clouds_job.h"
#include "phase/phase_function.h"

namespace radkit::app {

namespace {

using nlohmann::json;

struct CloudsCommand {
  CloudsJobSettings job;
  double sunElevation = 40, sunAzimuth = 150, cameraElevation = 25, fov = 70;
  // Options that, given explicitly, override the scene file's values.
  CLI::Option *sunElevationOption = nullptr, *sunAzimuthOption = nullptr,
              *cameraElevationOption = nullptr, *fovOption = nullptr, *phaseOption = nullptr,
              *phaseParamsOption = nullptr;
};

/// The option's value when it was given on the command line (its default does not count).
std::optional<double> ifGiven(const CLI::Option* option, double value) {
  return option != nullptr && option->count() > 0 ? std::optional<double>(value) : std::nullopt;
}

void printSummary(const CloudsJobSettings& job, const CloudsJobResult& r) {
  const json& s = r.report["settings"];
  const json& reference = r.report["reference"];
  printField("clouds", std::to_string(job.width) + "x" + std::to_string(job.height) + ", " +
                           s["medium"].get<std::string>() + ", " + s["phase"].get<std::string>() +
                           " phase (g " + fmt("%.3f", s["phase_mean_cosine"].get<double>()) +
                           "), layer " + fmt("%.2f s", r.report["seconds"]["layer"].get<double>()));
  printField("reference", fmt("%.2f s", reference["seconds"].get<double>()) + ", " +
                              std::to_string(job.samples) + " paths per pixel, relative noise " +
                              fmt("%.3f", reference["relative_noise"].get<double>()));
  for (const json& row : r.report["realtime"])
    printField(row["variant"].get<std::string>(),
               fmt("%.3f s", row["seconds"].get<double>()) + ", relative RMSE " +
                   fmt("%.3f", row["relative_rmse"].get<double>()) + ", bias " +
                   fmt("%+.3f", row["relative_bias"].get<double>()) + ", " +
                   fmt("%.0fx faster", row["speedup"].get<double>()));
  if (!job.scene.empty()) printField("scene", job.scene);
  printField("wrote", r.out);
}

}  // namespace

void addCloudsCommand(CLI::App& app) {
  auto cmd = std::make_shared<CloudsCommand>();
  CLI::App* sub = app.add_subcommand(
      "clouds",
      "A cloud layer by the volumetric path tracer and by the real-time ray-marching model, "
      "with the model's error and time per feature");
  media::CloudLayerSettings& l = cmd->job.layer;
  sub->add_option("--width", cmd->job.width, "Image width")
      ->check(CLI::Range(4, 4096))
      ->capture_default_str();
  sub->add_option("--height", cmd->job.height, "Image height")
      ->check(CLI::Range(4, 4096))
      ->capture_default_str();
  sub->add_option("--samples", cmd->job.samples, "Reference paths per pixel")
      ->check(CLI::Range(1, 1 << 20))
      ->capture_default_str();
  CLI::Option* sceneOption =
      sub->add_option("--scene", cmd->job.scene,
                      "Volume scene file (JSON, docs/formats.md): medium, sun, camera and ground; "
                      "--sun-*, --camera-elevation and --fov given override it");
  CLI::Option* phaseOption = cmd->phaseOption =
      sub->add_option("--phase", cmd->job.phase,
                      "Phase function: " + phaseRegistry().namesText() +
                          " (henyey-greenstein with g 0.86 when not given)")
          ->capture_default_str();
  CLI::Option* phaseParamsOption = cmd->phaseParamsOption =
      sub->add_option("--phase-params", cmd->job.phaseParams, "Its parameters, e.g. \"g=0.85\"");
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
  sub->add_option("--seed", cmd->job.seed,
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
  sub->add_option("--primary-steps", cmd->job.march.primarySteps, "Real-time model: view steps")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  sub->add_option("--light-steps", cmd->job.march.lightSteps, "Real-time model: steps to the sun")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  sub->add_option("--octaves", cmd->job.march.octaves,
                  "Real-time model: multiple-scattering octaves")
      ->check(CLI::Range(1, 16))
      ->capture_default_str();
  sub->add_flag("--sky-nee,!--no-sky-nee", cmd->job.skyNee,
                "Reference: next-event estimation to the sky at every scattering event")
      ->capture_default_str();
  sub->add_option("--exposure", cmd->job.exposure, "Image exposure (default: automatic)")
      ->check(FiniteNonNegative);
  sub->add_option("--out", cmd->job.out, "Output folder")->capture_default_str();
  sub->callback([cmd] {
    CloudsJobSettings& job = cmd->job;
    if (job.scene.empty() && !(job.layer.top > job.layer.bottom))
      throw CLI::ValidationError("--top", "must be above --bottom");
    // A phase named without --phase-params takes its own defaults, as in a scene file.
    if (cmd->phaseOption->count() > 0 && cmd->phaseParamsOption->count() == 0)
      job.phaseParams.clear();
    job.sunElevationDeg = ifGiven(cmd->sunElevationOption, cmd->sunElevation);
    job.sunAzimuthDeg = ifGiven(cmd->sunAzimuthOption, cmd->sunAzimuth);
    job.cameraElevationDeg = ifGiven(cmd->cameraElevationOption, cmd->cameraElevation);
    job.fovDeg = ifGiven(cmd->fovOption, cmd->fov);
    printSummary(job, runCloudsJob(job));
  });
}

}  // namespace radkit::app
