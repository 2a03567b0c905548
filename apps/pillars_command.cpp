// radkit pillars: light pillars over a night town (docs/pillars.md) — five lamps reflected by
// ice plates, rendered by the per-pixel closed form and by the Monte Carlo reference, with the
// images, their difference and report.json (timing, RMSE, agreement within standard errors).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "apps/common.h"
#include "job/report.h"
#include "media/pillars.h"
#include "render/hdr_io.h"
#include "render/radiosity_image.h"
#include "util/canvas.h"
#include "util/errors.h"
#include "util/output_folder.h"

namespace radkit::app {

namespace {

using nlohmann::json;

struct PillarsCommand {
  std::vector<int> size{160, 96};
  long long samples = 20000;
  std::uint64_t seed = 1;
  double plateDensity = 1e-4, extinction = 2e-4, sigmaTiltDeg = 5.0 / 3.0, cutDeg = 5;
  double lampRadius = 1.0, slabTop = 300, elevation = 8, fov = 40, exposure = 0;
  std::string out = "out/pillars";
};

/// Maps the 99th percentile of the lit pixels' luminance to 0.8: pillars cover few pixels.
double pillarsExposure(const media::PillarImage& image) {
  std::vector<double> lum;
  for (const Vec3& v : image.radiance)
    if (luminance(v) > 0) lum.push_back(luminance(v));
  if (lum.empty()) return 1;
  const std::size_t q = std::min(lum.size() - 1, std::size_t(0.99 * lum.size()));
  std::nth_element(lum.begin(), lum.begin() + q, lum.end());
  return lum[q] > 0 ? 0.8 / lum[q] : 1;
}

/// |Y_closed − Y_mc| in viridis, full scale at 5 % of the closed form's peak luminance.
Canvas differenceCanvas(const media::PillarImage& closed, const media::PillarImage& mc) {
  double peak = 0;
  for (const Vec3& v : closed.radiance) peak = std::max(peak, luminance(v));
  Canvas c(closed.width, closed.height);
  for (int y = 0; y < closed.height; ++y)
    for (int x = 0; x < closed.width; ++x) {
      const std::size_t i = std::size_t(y) * closed.width + x;
      const double diff = std::fabs(luminance(closed.radiance[i]) - luminance(mc.radiance[i]));
      c.set(x, y, viridis(peak > 0 ? std::min(1.0, diff / (0.05 * peak)) : 0));
    }
  return c;
}

json lampsJson(const media::PillarScene& scene) {
  json a = json::array();
  for (const media::PillarLamp& l : scene.lamps)
    a.push_back({{"position_m", vec3Json(l.position)},
                 {"intensity_w_per_sr", vec3Json(l.intensity)},
                 {"radius_m", l.radius}});
  return a;
}

void run(const PillarsCommand& cmd) {
  const auto start = std::chrono::steady_clock::now();
  OutputFolder folder(cmd.out);  // refuses an --out it cannot replace before the work
  media::PillarScene scene = media::pillarNightScene();
  scene.plateDensity = cmd.plateDensity;
  scene.extinction = cmd.extinction;
  scene.slabTop = cmd.slabTop;
  scene.tilt.sigma = cmd.sigmaTiltDeg * kPi / 180;
  scene.tilt.cut = cmd.cutDeg * kPi / 180;
  for (media::PillarLamp& l : scene.lamps) l.radius = cmd.lampRadius;
  try {
    media::pillarValidate(scene);
  } catch (const std::invalid_argument& e) {
    throw InputError(std::string(e.what()) +
                     ". Fix: keep --slab-top above the lamps (10 m) and --lamp-radius below 5 m");
  }
  media::PillarCamera camera;
  camera.width = cmd.size[0], camera.height = cmd.size[1];
  camera.elevationDeg = cmd.elevation;
  camera.fovDeg = cmd.fov;

  const media::PillarImage closed = media::pillarRenderClosed(scene, camera);
  printField("closed form", fmt("%.3f s", closed.seconds));
  const media::PillarImage mc = media::pillarRenderMonteCarlo(scene, camera, cmd.samples, cmd.seed);
  printField("monte carlo", fmt("%.3f s", mc.seconds) + fmt(", %.0f samples/pixel", cmd.samples));
  const media::PillarComparison cmp = media::pillarCompare(closed, mc);

  const double exposure = cmd.exposure > 0 ? cmd.exposure : pillarsExposure(closed);
  writeLinearAndPng(folder.path("pillars-closed"),
                    pixelImage(closed.width, closed.height, closed.radiance, exposure));
  writeLinearAndPng(folder.path("pillars-mc"),
                    pixelImage(mc.width, mc.height, mc.radiance, exposure));
  writePng(folder.path("pillars-difference.png"), differenceCanvas(closed, mc));

  json report{{"radkit", RADKIT_VERSION},
              {"command", "pillars"},
              {"settings",
               {{"width", camera.width},
                {"height", camera.height},
                {"samples_per_pixel", cmd.samples},
                {"seed", cmd.seed},
                {"plate_density_per_m", scene.plateDensity},
                {"extinction_per_m", scene.extinction},
                {"sigma_tilt_deg", cmd.sigmaTiltDeg},
                {"cut_deg", cmd.cutDeg},
                {"rho0", scene.rho0},
                {"slab_top_m", scene.slabTop},
                {"camera_eye_m", vec3Json(camera.eye)},
                {"camera_elevation_deg", camera.elevationDeg},
                {"camera_fov_deg", camera.fovDeg},
                {"exposure", exposure}}},
              {"lamps", lampsJson(scene)},
              {"closed_form", {{"seconds", closed.seconds}}},
              {"monte_carlo", {{"seconds", mc.seconds}}},
              {"comparison",
               {{"signal_pixels", cmp.signalPixels},
                {"relative_rmse", cmp.relativeRmse},
                {"fraction_within_3_se", cmp.within3Se},
                {"mean_z2", cmp.meanZ2},
                {"pixels_with_se", cmp.zPixels},
                {"max_abs_z", cmp.maxAbsZ}}}};
  printField("relative RMSE", fmt("%.4f", cmp.relativeRmse));
  printField("within 3 SE", fmt("%.3f", cmp.within3Se) + fmt(" of %.0f pixels", cmp.signalPixels));
  report["seconds"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  writeJson(folder.path("report.json"), report);
  folder.commit();
  printField("wrote", cmd.out);
}

}  // namespace

void addPillarsCommand(CLI::App& app) {
  auto cmd = std::make_shared<PillarsCommand>();
  CLI::App* sub = app.add_subcommand(
      "pillars",
      "Light pillars over five night lamps: ice-plate reflection by the exact per-pixel closed "
      "form and by Monte Carlo, with their difference and agreement (docs/pillars.md)");
  sub->add_option("--size", cmd->size, "Image WIDTH HEIGHT in pixels")
      ->expected(2)
      ->check(CLI::Range(8, 8192))
      ->capture_default_str();
  sub->add_option("--samples", cmd->samples, "Monte Carlo samples per pixel")
      ->check(CLI::Range(1LL, 100000000LL))
      ->capture_default_str();
  sub->add_option("--seed", cmd->seed, "Random seed of the Monte Carlo image")
      ->check(Unsigned)
      ->capture_default_str();
  sub->add_option("--plate-density", cmd->plateDensity,
                  "Plate area per volume n_p·A in m⁻¹ (single scattering: keep it ≪ 1/distance)")
      ->check(FiniteRange(0, 1))
      ->capture_default_str();
  sub->add_option("--extinction", cmd->extinction, "Extinction σ_t of air and ice in m⁻¹")
      ->check(FiniteRange(0, 1))
      ->capture_default_str();
  sub->add_option("--sigma-tilt", cmd->sigmaTiltDeg, "σ of the half-Gaussian plate tilt, degrees")
      ->check(FiniteRange(0.01, 20))
      ->capture_default_str();
  sub->add_option("--cut", cmd->cutDeg, "Largest plate tilt, degrees")
      ->check(FiniteRange(0.01, 60))
      ->capture_default_str();
  sub->add_option("--lamp-radius", cmd->lampRadius,
                  "Monte Carlo lamp sphere radius in metres (the closed form's lamps are points)")
      ->check(FinitePositive)
      ->capture_default_str();
  sub->add_option("--slab-top", cmd->slabTop, "Height of the plate layer's top in metres")
      ->check(FiniteRange(11, 20000))
      ->capture_default_str();
  sub->add_option("--elevation", cmd->elevation, "Camera elevation in degrees")
      ->check(FiniteRange(-30, 80))
      ->capture_default_str();
  sub->add_option("--fov", cmd->fov, "Horizontal field of view in degrees")
      ->check(FiniteRange(1, 120))
      ->capture_default_str();
  sub->add_option("--exposure", cmd->exposure,
                  "Radiance multiplier before tone mapping; 0: automatic (closed-form image)")
      ->check(FiniteNonNegative)
      ->capture_default_str();
  sub->add_option("--out", cmd->out, "Output folder")->capture_default_str();
  sub->callback([cmd] { run(*cmd); });
}

}  // namespace radkit::app
