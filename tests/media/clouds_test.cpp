// The real-time cloud model against closed forms on a homogeneous slab, its blue noise, and
// against the volumetric path tracer where both must agree; `radkit clouds` end to end.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

#include <nlohmann/json.hpp>

#include "atmosphere/atmosphere.h"
#include "media/cloud_marcher.h"
#include "media/medium.h"
#include "media/volume_tracer.h"
#include "tests/common/test_util.h"

namespace radkit::media {
namespace {

/// A slab 0 ≤ z ≤ d, wide enough to be infinite for rays along z.
HomogeneousBox slab(double d, double sigmaT, double albedo, std::unique_ptr<PhaseFunction> p) {
  Bounds3 b;
  b.extend(Vec3{-1e6, -1e6, 0});
  b.extend(Vec3{1e6, 1e6, d});
  return HomogeneousBox(b, sigmaT, albedo, std::move(p));
}

/// Sun overhead, looking straight up from below the slab: every scattering angle is 0 and the
/// light's path through the slab is d whatever the depth of the scattering point.
Lighting overheadSun(double e) {
  Lighting l;
  l.sky = [](const Vec3&) { return Vec3{0, 0, 0}; };
  l.sunDirection = {0, 0, 1};
  l.sunIrradiance = {e, e, e};
  return l;
}

TEST(CloudMarcher, OneOctaveIsSingleScattering) {
  // Single scattering seen from below along z, sun overhead: L = σ_s d p(0°) E e^{−σ_t d}
  // (the light goes d − z down to the point and z on to the eye).
  const double d = 100, sigmaT = 0.02, albedo = 0.9, e = 3;
  const HomogeneousBox box =
      slab(d, sigmaT, albedo, makePhaseFunction("henyey-greenstein", "g=0.6"));
  MarchSettings s;
  s.octaves = 1, s.ambient = false, s.jitter = false;
  s.primarySteps = 2048, s.lightSteps = 1;
  const Vec3 l = marchCloud(box, overheadSun(e), {0, 0, -1}, {0, 0, 1}, s, 0.5);
  const double expected =
      albedo * sigmaT * d * henyeyGreensteinPhase(1, 0.6) * e * std::exp(-sigmaT * d);
  EXPECT_NEAR(l.x / expected, 1, 1e-6);
}

TEST(CloudMarcher, OctavesFollowWrenninge) {
  // Σ_i b^i σ_s p(0°; c^i g) E ∫₀^d e^{−a^i σ_t (d − z)} e^{−σ_t z} dz, each term in closed form.
  const double d = 60, sigmaT = 0.05, albedo = 1, e = 1, g = 0.8;
  const HomogeneousBox box =
      slab(d, sigmaT, albedo, makePhaseFunction("henyey-greenstein", "g=0.8"));
  MarchSettings s;
  s.octaves = 4, s.ambient = false, s.jitter = false;
  s.a = 0.4, s.b = 0.6, s.c = 0.7;
  s.primarySteps = 4096, s.lightSteps = 1;
  const Vec3 l = marchCloud(box, overheadSun(e), {0, 0, -1}, {0, 0, 1}, s, 0.5);
  double expected = 0;
  for (int i = 0; i < 4; ++i) {
    const double ai = std::pow(s.a, i), k = (ai - 1) * sigmaT;
    const double integral =
        i == 0 ? d * std::exp(-sigmaT * d) : std::exp(-ai * sigmaT * d) * (std::exp(k * d) - 1) / k;
    expected += std::pow(s.b, i) * albedo * sigmaT *
                henyeyGreensteinPhase(1, std::pow(s.c, i) * g) * e * integral;
  }
  EXPECT_NEAR(l.y / expected, 1, 1e-6);
  // One octave fewer is a different answer: the test sees the octaves.
  s.octaves = 3;
  EXPECT_GT(
      std::fabs(marchCloud(box, overheadSun(e), {0, 0, -1}, {0, 0, 1}, s, 0.5).y / expected - 1),
      1e-3);
}

TEST(CloudMarcher, AmbientUnderHomogeneousIsotropicAssumptions) {
  // Only sky light L_a from above: σ_s/2 · L_a e^{−σ_t (d − z)} · e^{−σ_t z}, integrated:
  // σ_s d L_a e^{−σ_t d}/2.
  const double d = 80, sigmaT = 0.03, albedo = 0.95, la = 2;
  const HomogeneousBox box = slab(d, sigmaT, albedo, makePhaseFunction("isotropic"));
  MarchSettings s;
  s.octaves = 1, s.ambient = true, s.jitter = false, s.primarySteps = 2048;
  s.ambientTop = {la, la, la};
  Lighting dark;  // no sun, no sky behind
  dark.sky = [](const Vec3&) { return Vec3{0, 0, 0}; };
  const Vec3 l = marchCloud(box, dark, {0, 0, -1}, {0, 0, 1}, s, 0.5);
  EXPECT_NEAR(l.z / (albedo * sigmaT * d * la * std::exp(-sigmaT * d) / 2), 1, 1e-6);
}

TEST(CloudMarcher, JitteredStartsAverageToTheIntegral) {
  // With 8 steps a fixed start offset is biased to first order in the step (here the first
  // sample at each step's start); offsets spread over [0, 1) average the source over each step,
  // leaving only the correlation of source and transmittance inside a step, second order:
  // |bias| ≲ σ_t · 2σ_t · Δt²/12 relative for these exponentials (σ_t Δt = 0.05: 4e-4).
  const double d = 200, sigmaT = 0.002;
  const HomogeneousBox box = slab(d, sigmaT, 1, makePhaseFunction("isotropic"));
  MarchSettings s;
  s.octaves = 2, s.ambient = false, s.primarySteps = 8, s.lightSteps = 1;
  const Lighting light = overheadSun(1);
  MarchSettings fine = s;
  fine.primarySteps = 8192;
  const double exact = marchCloud(box, light, {0, 0, -1}, {0, 0, 1}, fine, 0.5).x;
  double mean = 0;
  const int k = 4096;
  for (int i = 0; i < k; ++i)
    mean += marchCloud(box, light, {0, 0, -1}, {0, 0, 1}, s, (i + 0.5) / k).x / k;
  const double dt = d / 8;
  EXPECT_NEAR(mean / exact, 1, sigmaT * 2 * sigmaT * dt * dt / 12);
  EXPECT_GT(std::fabs(marchCloud(box, light, {0, 0, -1}, {0, 0, 1}, s, 0.0).x / exact - 1), 1e-2);
  std::printf("8 steps: start offset 0 %+.2e, jittered mean %+.2e relative\n",
              marchCloud(box, light, {0, 0, -1}, {0, 0, 1}, s, 0.0).x / exact - 1,
              mean / exact - 1);
}

TEST(CloudMarcher, BlueNoiseTileIsAPermutationWithSpreadOutPoints) {
  const std::vector<double> tile = blueNoiseTile(3);
  ASSERT_EQ(tile.size(), 4096u);
  std::set<double> distinct(tile.begin(), tile.end());
  EXPECT_EQ(distinct.size(), 4096u);
  EXPECT_EQ(*std::min_element(tile.begin(), tile.end()), 0.0);
  // The 410 lowest ranks (10 %) keep apart: mean nearest-neighbour distance on the torus. For
  // random points it is about ½·√(4096/410) = 1.6 pixels; blue noise approaches the ideal 3.2.
  std::vector<int> first;
  for (int p = 0; p < 4096; ++p)
    if (tile[p] < 410.0 / 4096) first.push_back(p);
  double sum = 0;
  for (int p : first) {
    double best = 1e9;
    for (int q : first) {
      if (q == p) continue;
      int dx = std::abs(p % 64 - q % 64), dy = std::abs(p / 64 - q / 64);
      dx = std::min(dx, 64 - dx), dy = std::min(dy, 64 - dy);
      best = std::min(best, std::hypot(dx, dy));
    }
    sum += best;
  }
  EXPECT_GT(sum / first.size(), 2.5);
  EXPECT_EQ(blueNoiseTile(3), tile);  // deterministic
}

TEST(CloudMarcher, StatisticalMatchesThePathTracerInAThinSlab) {
  // At σ_t d = 0.02 multiple scattering is ~1 % of single scattering: the path tracer (which
  // has every order) and the fine single-scattering march agree within the path tracer's
  // standard error plus that 2 %. A tilted view and sun exercise the phase function.
  const double d = 10, sigmaT = 0.002, albedo = 1;
  const HomogeneousBox box =
      slab(d, sigmaT, albedo, makePhaseFunction("henyey-greenstein", "g=0.5"));
  Lighting light;
  light.sky = [](const Vec3&) { return Vec3{0, 0, 0}; };
  light.sunDirection = normalize(Vec3{0.3, 0, 1});
  light.sunIrradiance = {1, 1, 1};
  const Vec3 dir = normalize(Vec3{-0.2, 0.1, 1});
  MarchSettings s;
  s.octaves = 1, s.ambient = false, s.jitter = false, s.primarySteps = 1024, s.lightSteps = 64;
  const double march = marchCloud(box, light, {0, 0, -1}, dir, s, 0.5).x;
  Rng rng(11, 0, 0);
  const int n = 400000;
  double sum = 0, sum2 = 0;
  for (int i = 0; i < n; ++i) {
    const double v = traceVolumePath(box, light, {0, 0, -1}, dir, rng).x;
    sum += v, sum2 += v * v;
  }
  const double mean = sum / n, se = std::sqrt((sum2 / n - mean * mean) / (n - 1));
  EXPECT_LT(se, 0.05 * mean);
  EXPECT_NEAR(mean, march, 4 * se + 0.02 * march) << "path tracer " << mean << " ± " << se;
}

TEST(CloudsCli, WritesTheTableAndRefusesAnUnknownPhase) {
  test::TempDir dir;
  const std::string out = dir.path("c");
  test::RunResult r = test::runRadkit(
      "clouds --width 16 --height 9 --samples 2 --extinction 0.01 --phase henyey-greenstein "
      "--phase-params g=0.8 --out " +
          out,
      600);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (const char* f : {"clouds-reference.pfm", "clouds-realtime.png", "clouds-difference.png"})
    EXPECT_TRUE(std::filesystem::exists(out + "/" + f)) << f;
  std::ifstream in(out + "/report.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  ASSERT_EQ(report["realtime"].size(), 6u);
  for (const auto& row : report["realtime"]) {
    EXPECT_TRUE(std::isfinite(row["relative_rmse"].get<double>()));
    EXPECT_GT(row["seconds"].get<double>(), 0);
  }
  // Another phase function without parameters takes its own defaults (HG's g = 0.86 does not
  // carry over), and the sky's next-event estimation can be switched on.
  r = test::runRadkit(
      "clouds --width 8 --height 8 --samples 1 --extinction 0.01 --phase "
      "mie-cloud --sky-nee --out " +
          dir.path("mie"),
      600);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  std::ifstream mie(dir.path("mie") + "/report.json");
  const nlohmann::json mieReport = nlohmann::json::parse(mie);
  EXPECT_EQ(mieReport["settings"]["phase"], "mie-cloud");
  EXPECT_TRUE(mieReport["settings"]["sky_nee"].get<bool>());
  EXPECT_GT(mieReport["settings"]["phase_mean_cosine"].get<double>(), 0.8);
  r = test::runRadkit("clouds --width 8 --height 8 --phase fog --out " + dir.path("bad"), 60);
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.output.find("fog"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir.path("bad")));
}

}  // namespace
}  // namespace radkit::media
