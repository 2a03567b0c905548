// Per-surface photon estimates against oracles: the furnace (B = E/(1 − ρ)), the empty Cornell
// box's radiosity solution, and a mirror's reflected spot, which radiosity cannot see.
#include "photon/estimate.h"

#include <gtest/gtest.h>

#include <cmath>

#include "geometry/ray_scene.h"
#include "geometry/scene_loader.h"
#include "geometry/subdivision.h"
#include "photon/tracer.h"
#include "radiosity/radiosity_pipeline.h"
#include "render/radiosity_image.h"
#include "tests/common/test_util.h"

namespace radkit {
namespace {

/// Two-sided normal quantile z with P(|Z| > z) = alpha (bisection on erfc).
double normalQuantile(double alpha) {
  double lo = 0, hi = 10;
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (lo + hi);
    (std::erfc(mid / std::sqrt(2.0)) > alpha ? lo : hi) = mid;
  }
  return lo;
}

/// z for one of m checks at family level 0.01 (Šidák).
double zFor(int checks) { return normalQuantile(1 - std::pow(0.99, 1.0 / checks)); }

struct PhotonRun {
  Scene scene;
  PatchMesh mesh;
  PhotonRadiosity estimate;
  PhotonTraceStats stats;
};

PhotonRun runPhotons(const std::string& file, int patches, std::size_t photons,
                     std::uint64_t seed) {
  PhotonRun r{loadScene(test::dataPath(file)), {}, {}, {}};
  r.mesh = subdivide(r.scene, {0, patches});
  RayScene rays(r.mesh);
  EmitterSampler emitters(r.scene, r.mesh);
  PhotonSettings s;
  s.photons = photons;
  s.seed = seed;
  PhotonTrace t = tracePhotons(r.scene, r.mesh, rays, emitters, s);
  r.estimate = estimateRadiosity(r.scene, r.mesh, t.photons, photons);
  r.stats = t.stats;
  return r;
}

TEST(PhotonRadiosity, StatisticalFurnace) {
  // Closed cube, ρ = 0.5, E = 1: B = E/(1 − ρ) = 2 on every surface (and patch).
  const std::size_t n = 200000;
  PhotonRun r = runPhotons("furnace.json", 96, n, 5);
  const double z = zFor(6 + 1);
  for (const SurfaceEstimate& s : r.estimate.surfaces) {
    EXPECT_GT(s.radiosityError.x, 0) << s.name;
    EXPECT_NEAR(s.radiosity.x, 2.0, z * s.radiosityError.x) << s.name;
    EXPECT_EQ(s.radiosity.x, s.radiosity.z) << s.name;  // grey: one photon carries equal channels
  }
  // Quadrupling N halves the standard error: it scales as 1/√N (its own estimate varies by
  // about 1/√(2·paths), far below the 5 % allowed here).
  PhotonRun r4 = runPhotons("furnace.json", 96, 4 * n, 6);
  EXPECT_NEAR(r.estimate.surfaces[0].radiosityError.x / r4.estimate.surfaces[0].radiosityError.x,
              2.0, 0.1);
  // Power balance: with no escape, absorbed + truncated paths are all of them.
  EXPECT_EQ(r.stats.escaped, 0u);
  // Patches too: the total over the cube, weighted by area, is the emitted power times 2.
  double weighted = 0, area = 0;
  for (int i = 0; i < r.mesh.size(); ++i) {
    weighted += r.estimate.radiosity[i].x * r.mesh.patches[i].area;
    area += r.mesh.patches[i].area;
  }
  double se2 = 0;
  for (const SurfaceEstimate& s : r.estimate.surfaces)
    se2 += std::pow(s.radiosityError.x * s.area, 2);
  EXPECT_NEAR(weighted / area, 2.0, z * std::sqrt(se2) / area * std::sqrt(6.0));  // ≤ Σ|cov| bound
}

// The empty Cornell box. The photon estimate of a surface (its power over its area) does not
// depend on the mesh; the radiosity solution's does, and its discretisation error is bounded by
// the change from 125 to 500 patches (errors of constant elements shrink as the mesh refines,
// so the finer solution's error is below its difference to the coarser one).
TEST(PhotonRadiosity, StatisticalCornellBoxMatchesRadiosity) {
  const std::size_t n = 1000000;
  PhotonRun r = runPhotons("cornell-box-empty.json", 500, n, 7);
  PipelineSettings fine, coarse;
  fine.mesh = {0, 500};
  coarse.mesh = {0, 125};
  PipelineResult rf = runPipeline(r.scene, fine), rc = runPipeline(r.scene, coarse);
  const double z = zFor(3 * int(r.scene.surfaces.size()));
  for (std::size_t s = 0; s < r.scene.surfaces.size(); ++s) {
    const SurfaceEstimate& p = r.estimate.surfaces[s];
    const Vec3 b = rf.surfaces[s].radiosity;
    for (int c = 0; c < 3; ++c) {
      const double discretisation = std::fabs(b[c] - rc.surfaces[s].radiosity[c]);
      EXPECT_NEAR(p.radiosity[c], b[c], z * p.radiosityError[c] + discretisation)
          << p.name << " channel " << c;
    }
    const double relative = luminance(p.radiosity) / luminance(b) - 1;
    std::printf("%-10s photon Y %.5f ± %.5f, radiosity %.5f, difference %+.3f %%\n", p.name.c_str(),
                luminance(p.radiosity), luminance(p.radiosityError), luminance(b), 100 * relative);
    EXPECT_LT(std::fabs(relative), 0.02) << p.name;
  }
}

/// Irradiance on the target (x = −1, |y| ≤ 0.05, 0.35 ≤ z ≤ 0.45) of data/mirror-spot.json,
/// by a 40 × 40 midpoint rule: from the lamp directly, E = (Φ/π) cos θ_e cos θ_w / d² with the
/// lamp at (0, 0, 1) facing down; and through the mirror, from the lamp's mirror image at
/// (0.6, 0, 0.4) facing −x, times the mirror's reflectance 0.9 (every target point sees the
/// image through the mirror: docs/photon-mapping.md).
void mirrorSpotIrradiance(double power, double& direct, double& mirrored) {
  direct = mirrored = 0;
  const int n = 40;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double y = -0.05 + 0.1 * (i + 0.5) / n, z = 0.35 + 0.1 * (j + 0.5) / n;
      const double d2 = 1 + y * y + (z - 1) * (z - 1);
      direct += power / M_PI * ((1 - z) / std::sqrt(d2)) * (1 / std::sqrt(d2)) / d2;
      const double m2 = 1.6 * 1.6 + y * y + (z - 0.4) * (z - 0.4);
      mirrored += 0.9 * power / M_PI * (1.6 * 1.6 / m2) / m2;
    }
  direct /= n * n;
  mirrored /= n * n;
}

TEST(PhotonRadiosity, StatisticalMirrorSpotExceedsRadiosity) {
  PhotonRun r = runPhotons("mirror-spot.json", 40, 1000000, 9);
  const int target = r.scene.surfaces[2].name == "target" ? 2 : -1;
  ASSERT_EQ(target, 2);
  double direct, mirrored;
  mirrorSpotIrradiance(1.0, direct, mirrored);
  const SurfaceEstimate& p = r.estimate.surfaces[target];
  PipelineSettings settings;
  settings.mesh = {0, 40};
  PipelineResult rad = runPipeline(r.scene, settings);
  const double hRad = rad.surfaces[target].irradiance.x;
  const double z = zFor(3);
  std::printf(
      "target H: photons %.5f ± %.5f (caustic %.5f ± %.5f); radiosity %.5f; predicted direct %.5f "
      "+ mirror "
      "%.5f\n",
      p.irradiance.x, p.irradianceError.x, p.causticIrradiance.x, p.causticIrradianceError.x, hRad,
      direct, mirrored);
  EXPECT_NEAR(p.irradiance.x, direct + mirrored, z * p.irradianceError.x);
  EXPECT_NEAR(p.causticIrradiance.x, mirrored, z * p.causticIrradianceError.x);
  // Radiosity (the mirror is black to it) misses the mirrored light: the photon estimate
  // exceeds it by the mirror's share, up to the photons' error and radiosity's own error.
  EXPECT_NEAR(p.irradiance.x - hRad, mirrored, z * p.irradianceError.x + std::fabs(hRad - direct));
  EXPECT_NEAR(p.radiosity.x, 0.5 * p.irradiance.x, 1e-12);
}

}  // namespace
}  // namespace radkit
