// Cloud noise, media and the volumetric path tracer against oracles outside the code: the
// periodicity the noise promises, Beer-Lambert transmittance and exponential free paths, the
// furnace (albedo 1 under a uniform sky sees exactly the sky), the closed-form single-scattering
// integral of a thin slab, the cloud layer's cover against its setting, the sky sampler against
// the CIE overcast sky's irradiance, next-event estimation to the sky against escape-only paths,
// and determinism.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "media/medium.h"
#include "media/volume_tracer.h"
#include "noise/noise3d.h"
#include "phase/phase_function.h"
#include "tests/common/statistics.h"
#include "util/sampling.h"

namespace radkit::media {
namespace {

/// A slab 0 ≤ z ≤ d, 10⁶ m wide: infinite for the rays these tests send.
HomogeneousBox volumeSlab(double d, double sigmaT, double albedo,
                          std::unique_ptr<PhaseFunction> phase) {
  Bounds3 b;
  b.extend(Vec3{-1e6, -1e6, 0});
  b.extend(Vec3{1e6, 1e6, d});
  return HomogeneousBox(b, sigmaT, albedo, std::move(phase));
}

/// σ_t = a + b·z in the slab 0 ≤ z ≤ d with a majorant twice its maximum, so tracking meets
/// null collisions and ratio tracking's weights are fractional: τ(0 → d) = a·d + b·d²/2.
class VolumeLinearSlab final : public Medium {
 public:
  VolumeLinearSlab(double d, double a, double b) : m_d(d), m_a(a), m_b(b) {}
  double extinction(const Vec3& p) const override {
    return p.z >= 0 && p.z <= m_d && std::fabs(p.x) <= 1e6 && std::fabs(p.y) <= 1e6
               ? m_a + m_b * p.z
               : 0.0;
  }
  double majorant() const override { return 2 * (m_a + m_b * m_d); }
  Bounds3 bounds() const override {
    Bounds3 b;
    b.extend(Vec3{-1e6, -1e6, 0});
    b.extend(Vec3{1e6, 1e6, m_d});
    return b;
  }
  double albedo() const override { return 1; }
  const PhaseFunction& phase() const override { return m_phase; }
  double opticalDepth() const { return m_a * m_d + m_b * m_d * m_d / 2; }

 private:
  double m_d, m_a, m_b;
  IsotropicPhase m_phase;
};

/// A phase function that counts its samples: the number of real scattering events.
class VolumeCountingPhase final : public PhaseFunction {
 public:
  explicit VolumeCountingPhase(std::unique_ptr<PhaseFunction> inner) : m_inner(std::move(inner)) {}
  double eval(double c) const override { return m_inner->eval(c); }
  double sample(double u, double& pdf) const override {
    ++m_count;
    return m_inner->sample(u, pdf);
  }
  double meanCosine() const override { return m_inner->meanCosine(); }
  std::string name() const override { return m_inner->name(); }
  double evalAnisotropyScaled(double c, double scale) const override {
    return m_inner->evalAnisotropyScaled(c, scale);
  }
  long long count() const { return m_count; }

 private:
  std::unique_ptr<PhaseFunction> m_inner;
  mutable std::atomic<long long> m_count{0};
};

/// Mean and standard error of n draws.
struct VolumeMoments {
  double sum = 0, sum2 = 0;
  long long n = 0;
  void add(double v) { sum += v, sum2 += v * v, ++n; }
  double mean() const { return sum / double(n); }
  double se() const {
    const double m = mean();
    return std::sqrt(std::max(0.0, (sum2 / double(n) - m * m) / double(n - 1)));
  }
};

/// A small, fast cloud layer for tests (32³ shape, 16³ detail textures).
CloudLayerSettings smallCloudSettings(double coverage, double type) {
  CloudLayerSettings s;
  s.coverage = coverage;
  s.cloudType = type;
  s.shapeSize = 32;
  s.detailSize = 16;
  return s;
}

// ---- Noise ----

TEST(VolumeNoise, TilesWithItsPeriodInEveryAxis) {
  Rng rng(1, 0, 0);
  for (int i = 0; i < 300; ++i) {
    const int period = 2 + i % 7;
    const Vec3 p{rng.uniform() * 20 - 10, rng.uniform() * 20 - 10, rng.uniform() * 20 - 10};
    for (int axis = 0; axis < 3; ++axis) {
      Vec3 q = p;
      q[axis] += period;
      EXPECT_NEAR(perlin3(p, period, 3), perlin3(q, period, 3), 1e-12);
      EXPECT_NEAR(worley3(p, period, 3), worley3(q, period, 3), 1e-12);
      EXPECT_NEAR(perlinFbm3(p, period, 4, 0.5, 3), perlinFbm3(q, period, 4, 0.5, 3), 1e-12);
      EXPECT_NEAR(worleyFbm3(p, period, 4, 0.5, 3), worleyFbm3(q, period, 4, 0.5, 3), 1e-12);
      EXPECT_NEAR(perlinWorley3(p, period, 3), perlinWorley3(q, period, 3), 1e-12);
      q[axis] -= 2 * period;  // and backwards across the origin
      EXPECT_NEAR(worley3(p, period, 3), worley3(q, period, 3), 1e-12);
      EXPECT_NEAR(perlin3(p, period, 3), perlin3(q, period, 3), 1e-12);
    }
  }
}

TEST(VolumeNoise, RangesAndLatticeZeros) {
  Rng rng(2, 0, 0);
  double pmin = 1, pmax = -1, wmin = 1, wmax = 0, pwmin = 1, pwmax = 0;
  for (int i = 0; i < 100000; ++i) {
    const Vec3 p{rng.uniform() * 8, rng.uniform() * 8, rng.uniform() * 8};
    const double pn = perlin3(p, 8, 5), wn = worley3(p, 8, 5), pw = perlinWorley3(p, 4, 5);
    pmin = std::min(pmin, pn), pmax = std::max(pmax, pn);
    wmin = std::min(wmin, wn), wmax = std::max(wmax, wn);
    pwmin = std::min(pwmin, pw), pwmax = std::max(pwmax, pw);
    const double wf = worleyFbm3(p, 4, 3, 0.5, 5), pf = perlinFbm3(p, 4, 3, 0.5, 5);
    ASSERT_GE(wf, 0);
    ASSERT_LE(wf, 1);
    ASSERT_LE(std::fabs(pf), 1.1);
  }
  // Improved Perlin noise (12 edge gradients) stays within about ±1, and spans most of it.
  EXPECT_LT(std::fabs(pmin), 1.05);
  EXPECT_LT(pmax, 1.05);
  EXPECT_LT(pmin, -0.5);
  EXPECT_GT(pmax, 0.5);
  EXPECT_GE(wmin, 0);
  EXPECT_LE(wmax, 1);
  EXPECT_GE(pwmin, 0);
  EXPECT_LE(pwmax, 1);
  // Gradient noise vanishes at lattice points.
  for (int x = -3; x < 3; ++x) EXPECT_EQ(perlin3(Vec3{double(x), 1, 2}, 4, 9), 0.0);
}

TEST(VolumeNoise, DeterministicPerSeedAndSeedsDiffer) {
  Rng rng(3, 0, 0);
  int differ = 0;
  for (int i = 0; i < 200; ++i) {
    const Vec3 p{rng.uniform() * 4, rng.uniform() * 4, rng.uniform() * 4};
    EXPECT_EQ(perlin3(p, 4, 7), perlin3(p, 4, 7));
    EXPECT_EQ(worley3(p, 4, 7), worley3(p, 4, 7));
    differ += perlin3(p, 4, 7) != perlin3(p, 4, 8) && worley3(p, 4, 7) != worley3(p, 4, 8);
  }
  EXPECT_GT(differ, 190);
}

TEST(VolumeNoise, TextureReturnsTexelsAtCentresAndWraps) {
  const CloudNoise a = makeCloudNoise(16, 8, 4);
  ASSERT_EQ(a.shape.size(), 16);
  ASSERT_EQ(a.shape.channels(), 4);
  ASSERT_EQ(a.detail.channels(), 3);
  NoiseTexture shape = a.shape;  // at() is non-const
  for (int z = 0; z < 16; z += 3)
    for (int y = 0; y < 16; y += 5)
      for (int x = 0; x < 16; ++x)
        for (int c = 0; c < 4; ++c) {
          const Vec3 p{(x + 0.5) / 16, (y + 0.5) / 16, (z + 0.5) / 16};
          EXPECT_NEAR(a.shape.sample(p, c), shape.at(x, y, z, c), 1e-6);
          EXPECT_NEAR(a.shape.sample(p + Vec3{1, -2, 3}, c), shape.at(x, y, z, c), 1e-6);
          EXPECT_GE(shape.at(x, y, z, c), 0);
          EXPECT_LE(shape.at(x, y, z, c), 1);
        }
  // Halfway between two texel centres: their mean (trilinear), also across the wrap.
  const Vec3 mid{1.0 / 16, 0.5 / 16, 0.5 / 16}, wrap{0, 0.5 / 16, 0.5 / 16};
  EXPECT_NEAR(a.shape.sample(mid, 0), 0.5 * (shape.at(0, 0, 0, 0) + shape.at(1, 0, 0, 0)), 1e-6);
  EXPECT_NEAR(a.shape.sample(wrap, 0), 0.5 * (shape.at(15, 0, 0, 0) + shape.at(0, 0, 0, 0)), 1e-6);
}

TEST(VolumeNoise, CloudNoiseIsTheSameOnAnyThreadCountAndDiffersBySeed) {
  CloudNoise one, two;
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
    one = makeCloudNoise(24, 12, 5);
  }
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
    two = makeCloudNoise(24, 12, 5);
  }
  CloudNoise other = makeCloudNoise(24, 12, 6);
  int differ = 0;
  for (int z = 0; z < 24; ++z)
    for (int y = 0; y < 24; ++y)
      for (int x = 0; x < 24; ++x)
        for (int c = 0; c < 4; ++c) {
          ASSERT_EQ(one.shape.at(x, y, z, c), two.shape.at(x, y, z, c));
          differ += one.shape.at(x, y, z, c) != other.shape.at(x, y, z, c);
        }
  for (int z = 0; z < 12; ++z)
    for (int x = 0; x < 12; ++x)
      for (int c = 0; c < 3; ++c) ASSERT_EQ(one.detail.at(x, 3, z, c), two.detail.at(x, 3, z, c));
  EXPECT_GT(differ, 24 * 24 * 24 * 4 * 9 / 10);
  // The Worley channels are worleyFbm3 of texture coordinates: periodic in the texture.
  EXPECT_NEAR(one.shape.sample({0.3, 0.7, 0.1}, 2), one.shape.sample({1.3, -0.3, 2.1}, 2), 1e-6);
}

// ---- Media ----

TEST(VolumeMedium, ClipRay) {
  Bounds3 b;
  b.extend(Vec3{0, 0, 0});
  b.extend(Vec3{1, 1, 1});
  double t0, t1;
  ASSERT_TRUE(clipRay(b, {-1, 0.5, 0.5}, {1, 0, 0}, t0, t1));
  EXPECT_DOUBLE_EQ(t0, 1);
  EXPECT_DOUBLE_EQ(t1, 2);
  ASSERT_TRUE(clipRay(b, {0.5, 0.5, 0.5}, {0, 0, -1}, t0, t1));  // from inside: t0 = 0
  EXPECT_EQ(t0, 0);
  EXPECT_DOUBLE_EQ(t1, 0.5);
  const Vec3 diag = normalize(Vec3{1, 1, 1});
  ASSERT_TRUE(clipRay(b, {-1, -1, -1}, diag, t0, t1));
  EXPECT_NEAR(t0, std::sqrt(3.0), 1e-12);
  EXPECT_NEAR(t1, 2 * std::sqrt(3.0), 1e-12);
  EXPECT_FALSE(clipRay(b, {-1, 0.5, 0.5}, {-1, 0, 0}, t0, t1));               // pointing away
  EXPECT_FALSE(clipRay(b, {-1, 2, 0.5}, {1, 0, 0}, t0, t1));                  // parallel, outside
  EXPECT_FALSE(clipRay(b, {-1, -1, 0.5}, normalize(Vec3{1, 3, 0}), t0, t1));  // passes by
}

TEST(VolumeMedium, HomogeneousBoxIsConstantInsideOnly) {
  const HomogeneousBox box = volumeSlab(2, 0.7, 0.5, std::make_unique<IsotropicPhase>());
  EXPECT_EQ(box.extinction({3, 4, 1}), 0.7);
  EXPECT_EQ(box.extinction({3, 4, -0.01}), 0.0);
  EXPECT_EQ(box.extinction({3, 4, 2.01}), 0.0);
  EXPECT_EQ(box.majorant(), 0.7);
  EXPECT_EQ(box.albedo(), 0.5);
}

TEST(VolumeCloudLayer, DensityBoundedAndZeroOutsideTheLayer) {
  const CloudLayer layer(smallCloudSettings(0.6, 0.8), std::make_unique<IsotropicPhase>());
  const CloudLayerSettings& s = layer.settings();
  EXPECT_EQ(layer.majorant(), s.extinction);
  Rng rng(4, 0, 0);
  int positive = 0;
  for (int i = 0; i < 40000; ++i) {
    const Vec3 p{(rng.uniform() - 0.5) * s.size, (rng.uniform() - 0.5) * s.size,
                 s.bottom + rng.uniform() * (s.top - s.bottom)};
    const double d = layer.density(p);
    ASSERT_GE(d, 0);
    ASSERT_LE(d, 1);
    EXPECT_NEAR(layer.extinction(p), s.extinction * d, 1e-15);
    positive += d > 0;
    // Below, above and beside the layer: nothing.
    EXPECT_EQ(layer.density({p.x, p.y, s.bottom - 1 - rng.uniform() * 1000}), 0.0);
    EXPECT_EQ(layer.density({p.x, p.y, s.top + 1 + rng.uniform() * 1000}), 0.0);
    EXPECT_EQ(layer.density({s.size / 2 + 1, p.y, p.z}), 0.0);
    double c, t;
    layer.weather(p.x, p.y, c, t);
    ASSERT_GE(c, 0);
    ASSERT_LE(c, 1);
    ASSERT_GE(t, 0);
    ASSERT_LE(t, 1);
  }
  EXPECT_GT(positive, 1000);  // and there are clouds
  const Bounds3 b = layer.bounds();
  EXPECT_EQ(b.lo.z, s.bottom);
  EXPECT_EQ(b.hi.z, s.top);
  EXPECT_EQ(b.hi.x - b.lo.x, s.size);
}

TEST(VolumeCloudLayer, CloudCoverFollowsTheSetting) {
  // Cover: the fraction of columns with cloud anywhere above them, on a 50 × 50 grid offset
  // from any texel or calibration grid, 100 heights per column.
  for (double coverage : {0.2, 0.5, 0.8}) {
    const CloudLayer layer(smallCloudSettings(coverage, 0.8), std::make_unique<IsotropicPhase>());
    const CloudLayerSettings& s = layer.settings();
    int cloudy = 0;
    double meanType = 0;
    for (int j = 0; j < 50; ++j)
      for (int i = 0; i < 50; ++i) {
        const double x = -s.size / 2 + (i + 0.31) / 50 * s.size;
        const double y = -s.size / 2 + (j + 0.73) / 50 * s.size;
        bool any = false;
        for (int k = 0; k < 100 && !any; ++k)
          any = layer.density({x, y, s.bottom + (k + 0.5) / 100 * (s.top - s.bottom)}) > 0;
        cloudy += any;
        double c, t;
        layer.weather(x, y, c, t);
        meanType += t / 2500;
      }
    EXPECT_NEAR(cloudy / 2500.0, coverage, 0.1) << "coverage " << coverage;
    EXPECT_NEAR(meanType, s.cloudType, 0.1);
  }
  // No coverage, no cloud.
  const CloudLayer none(smallCloudSettings(0, 0.8), std::make_unique<IsotropicPhase>());
  Rng rng(5, 0, 0);
  for (int i = 0; i < 2000; ++i)
    EXPECT_EQ(none.density({(rng.uniform() - 0.5) * 16000, (rng.uniform() - 0.5) * 16000,
                            1500 + rng.uniform() * 2500}),
              0.0);
}

TEST(VolumeCloudLayer, CloudTypesHaveDifferentProfiles) {
  // Mean density per tenth of the layer's height; the centroid and the top of the profile
  // rise from stratus to stratocumulus to cumulus; mostly-stratus columns (the weather map
  // moves the type by ≤ about 0.3) are empty above 55 %, where stratocumulus ends.
  double centroid[3], top[3];
  std::vector<double> profile[3];
  const double types[3] = {0, 0.5, 1};
  for (int t = 0; t < 3; ++t) {
    const CloudLayer layer(smallCloudSettings(0.7, types[t]), std::make_unique<IsotropicPhase>());
    const CloudLayerSettings& s = layer.settings();
    profile[t].assign(10, 0);
    for (int k = 0; k < 10; ++k)
      for (int j = 0; j < 30; ++j)
        for (int i = 0; i < 30; ++i)
          profile[t][k] += layer.density({-s.size / 2 + (i + 0.5) / 30 * s.size,
                                          -s.size / 2 + (j + 0.5) / 30 * s.size,
                                          s.bottom + (k + 0.5) / 10 * (s.top - s.bottom)}) /
                           900;
    double m0 = 0, m1 = 0;
    top[t] = 0;
    for (int k = 0; k < 10; ++k) {
      m0 += profile[t][k], m1 += profile[t][k] * (k + 0.5) / 10;
      if (profile[t][k] > 0.01) top[t] = (k + 1) / 10.0;
    }
    ASSERT_GT(m0, 0);
    centroid[t] = m1 / m0;
  }
  EXPECT_LT(centroid[0] + 0.05, centroid[1]);
  EXPECT_LT(centroid[1] + 0.05, centroid[2]);
  EXPECT_LT(top[0], top[1]);
  EXPECT_LT(top[1], top[2]);
  for (int k = 6; k < 10; ++k) EXPECT_EQ(profile[0][k], 0.0) << k;
}

// ---- Tracking ----

TEST(VolumeTracer, RatioTrackingGivesBeerLambert) {
  // Homogeneous slabs (majorant = σ_t: the estimate is 0 or 1) and a linear slab with a loose
  // majorant (fractional weights and the estimator's Russian roulette): mean e^{−τ} within 4 SE.
  const Vec3 up{0, 0, 1};
  for (double tau : {0.1, 0.5, 1.0, 2.0, 5.0}) {
    const HomogeneousBox box = volumeSlab(2, tau / 2, 1, std::make_unique<IsotropicPhase>());
    Rng rng(6, std::uint64_t(tau * 10), 0);
    VolumeMoments m;
    for (int i = 0; i < 40000; ++i) m.add(ratioTrack(box, {0, 0, -1}, up, INFINITY, rng));
    EXPECT_NEAR(m.mean(), std::exp(-tau), 4 * m.se()) << "tau " << tau;
  }
  for (double b : {0.1, 1.0}) {
    const VolumeLinearSlab slab(3, 0.2, b);
    Rng rng(7, std::uint64_t(b * 10), 0);
    VolumeMoments m;
    for (int i = 0; i < 40000; ++i) {
      const double T = ratioTrack(slab, {0, 0, -1}, up, INFINITY, rng);
      ASSERT_GE(T, 0);
      ASSERT_LE(T, 1);
      m.add(T);
    }
    EXPECT_NEAR(m.mean(), std::exp(-slab.opticalDepth()), 4 * m.se()) << "b " << b;
  }
  // tMax cuts the segment: half the homogeneous slab.
  const HomogeneousBox box = volumeSlab(2, 0.5, 1, std::make_unique<IsotropicPhase>());
  Rng rng(8, 0, 0);
  VolumeMoments m;
  for (int i = 0; i < 40000; ++i) m.add(ratioTrack(box, {0, 0, -1}, up, 2, rng));
  EXPECT_NEAR(m.mean(), std::exp(-0.5), 4 * m.se());
}

TEST(VolumeTracer, DeltaTrackingFreePathsAreExponential) {
  // Mean free path in an effectively infinite box: 1/σ_t.
  for (double sigmaT : {0.05, 1.0, 20.0}) {
    Bounds3 b;
    b.extend(Vec3{-1e9, -1e9, -1e9});
    b.extend(Vec3{1e9, 1e9, 1e9});
    const HomogeneousBox box(b, sigmaT, 1, std::make_unique<IsotropicPhase>());
    Rng rng(9, std::uint64_t(sigmaT * 100), 0);
    VolumeMoments m;
    for (int i = 0; i < 40000; ++i) m.add(deltaTrack(box, {0, 0, 0}, {0, 1, 0}, INFINITY, rng));
    EXPECT_NEAR(m.mean(), 1 / sigmaT, 4 * m.se()) << sigmaT;
  }
  // The fraction crossing a slab uncollided: e^{−τ}, binomial standard error; the linear slab
  // (null collisions) too, and its collisions' mean depth against the closed form.
  const Vec3 up{0, 0, 1};
  for (double tau : {0.1, 1.0, 3.0}) {
    const HomogeneousBox box = volumeSlab(1, tau, 1, std::make_unique<IsotropicPhase>());
    Rng rng(10, std::uint64_t(tau * 10), 0);
    const int n = 40000;
    int crossed = 0;
    for (int i = 0; i < n; ++i)
      crossed += std::isinf(deltaTrack(box, {0, 0, -1}, up, INFINITY, rng));
    const double p = std::exp(-tau), se = std::sqrt(p * (1 - p) / n);
    EXPECT_NEAR(crossed / double(n), p, 4 * se) << tau;
  }
  const VolumeLinearSlab slab(2, 0.1, 0.5);
  Rng rng(11, 0, 0);
  const int n = 40000;
  int crossed = 0;
  for (int i = 0; i < n; ++i)
    crossed += std::isinf(deltaTrack(slab, {0, 0, -1}, up, INFINITY, rng));
  const double p = std::exp(-slab.opticalDepth()), se = std::sqrt(p * (1 - p) / n);
  EXPECT_NEAR(crossed / double(n), p, 4 * se);
}

// ---- The path tracer ----

TEST(VolumeTracer, FurnaceSeesTheSkyExactly) {
  // Albedo 1 under a uniform sky L: every path escapes eventually and carries L, whatever it
  // scattered; camera rays from outside and from inside the box, both phase functions, with
  // and without next-event estimation to the sky.
  const Vec3 L{0.3, 0.6, 1.2};
  Lighting light;
  light.sky = [L](const Vec3&) { return L; };
  Bounds3 b;
  b.extend(Vec3{-1, -2, 0});
  b.extend(Vec3{1, 2, 3});
  for (int nee = 0; nee < 2; ++nee)
    for (const char* params : {"", "g=0.8"}) {
      light.skySampler = nee ? std::make_shared<const SkySampler>(light.sky) : nullptr;
      auto phase = std::make_unique<VolumeCountingPhase>(
          params[0] ? makePhaseFunction("henyey-greenstein", params)
                    : makePhaseFunction("isotropic"));
      const VolumeCountingPhase* counter = phase.get();
      const HomogeneousBox box(b, 2.0, 1, std::move(phase));
      Rng rng(12, params[0], nee);
      VolumeMoments m[3];
      const int n = 20000;
      for (int i = 0; i < n; ++i) {
        const Vec3 dir = normalize(Vec3{rng.uniform() - 0.5, rng.uniform() - 0.5, 1});
        const Vec3 outside = traceVolumePath(box, light, {0, 0, -2}, dir, rng);
        const Vec3 inside = traceVolumePath(box, light, {0.2, 0.5, 1.5},
                                            normalize(Vec3{rng.uniform() - 0.5, 1, 0.3}), rng);
        m[0].add(outside.x), m[1].add(outside.z), m[2].add(inside.y);
      }
      EXPECT_NEAR(m[0].mean(), L.x, 4 * m[0].se() + 1e-12);
      EXPECT_NEAR(m[1].mean(), L.z, 4 * m[1].se() + 1e-12);
      EXPECT_NEAR(m[2].mean(), L.y, 4 * m[2].se() + 1e-12);
      // Not trivially: the box is optically thick (τ ≥ 4 across), so paths scatter many times.
      EXPECT_GT(counter->count(), 2 * n) << params;
    }
}

TEST(VolumeTracer, RussianRouletteIsUnbiased) {
  // Albedo 0.7 in an optically thick box under a uniform sky: roulette from the first event
  // and (practically) none must agree within 4 combined standard errors; roulette that forgot
  // to divide the survivors by their probability would lose ~20 % here.
  Lighting light;
  light.sky = [](const Vec3&) { return Vec3{1, 1, 1}; };
  light.sunDirection = normalize(Vec3{0.2, 0.1, 1});
  light.sunIrradiance = {3, 3, 3};
  Bounds3 b;
  b.extend(Vec3{-1, -1, 0});
  b.extend(Vec3{1, 1, 2});
  const HomogeneousBox box(b, 3.0, 0.7, makePhaseFunction("henyey-greenstein", "g=0.3"));
  VolumeMoments m[2];
  for (int r = 0; r < 2; ++r) {
    Rng rng(15, r, 0);
    for (int i = 0; i < 40000; ++i)
      m[r].add(traceVolumePath(box, light, {0, 0, -1}, {0, 0, 1}, rng, r == 0 ? 0 : 100000).x);
  }
  const double se = std::hypot(m[0].se(), m[1].se());
  EXPECT_NEAR(m[0].mean(), m[1].mean(), 4 * se);
  EXPECT_LT(se, 0.02 * m[1].mean());
}

TEST(VolumeTracer, SingleScatteringInAThinSlabMatchesTheClosedForm) {
  // Slab 0 ≤ z ≤ d viewed from below along its normal (d = +z); the sun above it at angle θs
  // from the normal, so its light crosses (d − z)/μs to the scattering height z and then z to
  // the camera: L = E α p(μs) σ_t ∫₀^d e^{−σ_t z} e^{−σ_t (d − z)/μs} dz
  //   = E α p(μs) σ_t e^{−τ/μs} (1 − e^{−kd})/k,  k = σ_t (1 − 1/μs)  (k → 0: σ_t d e^{−τ}).
  // At τ = 0.01 multiple scattering adds ~τ/2 relative, below the ~1 % standard error.
  const double d = 10, sigmaT = 0.001, albedo = 0.9, E = 2.0;
  for (double thetaDeg : {0.0, 60.0}) {
    const double mu = std::cos(thetaDeg * kPi / 180);
    auto hg = makePhaseFunction("henyey-greenstein", "g=0.5");
    const HenyeyGreensteinPhase exact(0.5);
    const HomogeneousBox box = volumeSlab(d, sigmaT, albedo, std::move(hg));
    Lighting light;
    light.sunDirection = {std::sqrt(1 - mu * mu), 0, mu};
    light.sunIrradiance = {E, E, E};
    const double k = sigmaT * (1 - 1 / mu);
    const double integral = std::fabs(k) < 1e-15 ? d : (1 - std::exp(-k * d)) / k;
    const double common = E * albedo * sigmaT * std::exp(-sigmaT * d / mu) * integral;
    const double expected = common * exact.eval(mu);
    Rng rng(13, std::uint64_t(thetaDeg), 0);
    VolumeMoments m;
    for (int i = 0; i < 1000000; ++i)
      m.add(traceVolumePath(box, light, {0, 0, -1}, {0, 0, 1}, rng).x);
    EXPECT_LT(m.se(), 0.015 * expected);
    EXPECT_NEAR(m.mean(), expected, 4 * m.se()) << thetaDeg;
    // Teeth: the phase function at −μs (the wrong sign of cos θ) or isotropic lies far off.
    EXPECT_GT(std::fabs(common * exact.eval(-mu) - m.mean()), 8 * m.se());
    EXPECT_GT(std::fabs(common / (4 * kPi) - m.mean()), 8 * m.se());
  }
}

TEST(VolumeTracer, LambertianGroundUnderSunAndSky) {
  // No medium to speak of (σ_t = 0): looking down at the ground, the sun's reflected radiance
  // ρ E μs / π by next-event estimation plus the bounce that escapes to the sky, ρ L_sky.
  const HomogeneousBox empty = volumeSlab(1, 0, 1, std::make_unique<IsotropicPhase>());
  Lighting light;
  light.groundAlbedo = 0.3;
  light.sunDirection = normalize(Vec3{0, 1, 1});
  light.sunIrradiance = {1, 2, 3};
  light.sky = [](const Vec3& w) { return w.z > 0 ? Vec3{0.1, 0.1, 0.1} : Vec3{0, 0, 0}; };
  Rng rng(14, 0, 0);
  const Vec3 v = traceVolumePath(empty, light, {0, 0, 5}, normalize(Vec3{0.3, 0, -1}), rng);
  const double mus = std::sqrt(0.5);
  EXPECT_NEAR(v.x, 0.3 * 1 * mus / kPi + 0.3 * 0.1, 1e-12);
  EXPECT_NEAR(v.z, 0.3 * 3 * mus / kPi + 0.3 * 0.1, 1e-12);
  // Without a ground the ray passes to the sky below the horizon (black here).
  light.groundAlbedo = 0;
  EXPECT_EQ(traceVolumePath(empty, light, {0, 0, 5}, normalize(Vec3{0.3, 0, -1}), rng).y, 0.0);
  // A camera ray that escapes unscattered sees the sky, not the sun's disc.
  EXPECT_EQ(traceVolumePath(empty, light, {0, 0, 5}, light.sunDirection, rng).x, 0.1);
}

/// A sky with a small bright cap: CIE overcast (Moon & Spencer 1942, L(θ) = L_z(1 + 2 cos θ)/3)
/// above the horizon, black below, plus radiance `capL` within `capDeg` of `capDir`.
SkyRadiance volumeCapSky(const Vec3& capDir, double capDeg, double capL) {
  const double cosCap = std::cos(capDeg * kPi / 180);
  return [=](const Vec3& w) {
    if (w.z <= 0) return Vec3{0, 0, 0};
    const double cie = (1 + 2 * w.z) / 3;
    const double cap = dot(w, capDir) >= cosCap ? capL : 0.0;
    return Vec3{cie + cap, 0.5 * cie + cap, 0.25 * cie + cap};
  };
}

TEST(VolumeSkySampler, DensityIntegratesToOneAndDrawsFollowIt) {
  const SkySampler sampler(volumeCapSky(normalize(Vec3{1, 0.5, 0.4}), 4, 200));
  // ∫ pdf dω by the midpoint rule on a grid 8 × 8 finer than the sampler's 64 × 128 cells, where
  // the density is constant: exact but for rounding.
  const int rows = 512, cols = 1024;
  double integral = 0;
  const double dOmega = 4 * kPi / (double(rows) * cols);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c)
      integral +=
          sampler.pdf(localDirection(1 - 2 * (r + 0.5) / rows, 2 * kPi * (c + 0.5) / cols)) *
          dOmega;
  EXPECT_NEAR(integral, 1.0, 1e-9);
  // χ² of draws in 16 × 32 equal-area bins against the density's integral over each bin.
  const int br = 16, bc = 32, n = 400000;
  std::vector<double> expected(br * bc, 0.0), observed(br * bc, 0.0);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c)
      expected[(r * br / rows) * bc + c * bc / cols] +=
          n * dOmega *
          sampler.pdf(localDirection(1 - 2 * (r + 0.5) / rows, 2 * kPi * (c + 0.5) / cols));
  Rng rng(31, 0, 0);
  for (int i = 0; i < n; ++i) {
    double pdf;
    const double u0 = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
    const Vec3 d = sampler.sample(u0, u1, u2, pdf);
    ASSERT_NEAR(length(d), 1.0, 1e-12);
    ASSERT_DOUBLE_EQ(pdf, sampler.pdf(d));
    double phi = std::atan2(d.y, d.x);
    if (phi < 0) phi += 2 * kPi;
    const int r = std::min(br - 1, int((1 - d.z) / 2 * br)),
              c = std::min(bc - 1, int(phi / (2 * kPi) * bc));
    observed[r * bc + c] += 1;
  }
  EXPECT_GT(test::chiSquarePValue(observed, expected, "media_sky_sampler", 1e-3), 1e-3);
}

TEST(VolumeSkySampler, EstimatesTheOvercastSkysIrradiance) {
  // The CIE overcast sky's horizontal irradiance is 7πL_z/9 (Moon & Spencer 1942). Estimated
  // with the sampler's directions it is within 4 standard errors, and far less noisy than with
  // uniform directions (the sampler follows the sky's gradient).
  const SkyRadiance cie = [](const Vec3& w) {
    const double l = w.z > 0 ? (1 + 2 * w.z) / 3 : 0.0;
    return Vec3{l, l, l};
  };
  const SkySampler fitted(cie, true), uniform(cie, true, 64, 128, 1.0);
  VolumeMoments m[2];
  for (int k = 0; k < 2; ++k) {
    const SkySampler& s = k == 0 ? fitted : uniform;
    Rng rng(32, k, 0);
    for (int i = 0; i < 200000; ++i) {
      double pdf;
      const double u0 = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
      const Vec3 d = s.sample(u0, u1, u2, pdf);
      m[k].add(cie(d).x * std::max(0.0, d.z) / pdf);
    }
    EXPECT_NEAR(m[k].mean(), 7 * kPi / 9, 4 * m[k].se()) << k;
  }
  EXPECT_LT(m[0].se(), 0.5 * m[1].se());
}

TEST(VolumeTracer, SkyNextEventEstimationAgreesWithEscapeAndCutsNoise) {
  // A slab of optical depth 1 (albedo 0.9, HG g = 0.6) under the overcast sky with a bright
  // 3° cap low in the east, seen from below at an angle: next-event estimation to the sky with
  // MIS and escape-only paths are both unbiased, so they agree within 4 combined standard
  // errors; the cap, which phase sampling rarely finds, makes escape-only far noisier.
  const HomogeneousBox slab =
      volumeSlab(100, 0.01, 0.9, makePhaseFunction("henyey-greenstein", "g=0.6"));
  Lighting plain;
  plain.sky = volumeCapSky(normalize(Vec3{1, 0, 0.3}), 3, 300);
  Lighting nee = plain;
  nee.skySampler = std::make_shared<const SkySampler>(nee.sky);
  const Vec3 dir = normalize(Vec3{0.5, 0.2, 1});
  VolumeMoments m[2][3];
  for (int k = 0; k < 2; ++k) {
    Rng rng(33, k, 0);
    for (int i = 0; i < 100000; ++i) {
      const Vec3 v = traceVolumePath(slab, k == 0 ? nee : plain, {0, 0, -1}, dir, rng);
      m[k][0].add(v.x), m[k][1].add(v.y), m[k][2].add(v.z);
    }
  }
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(m[0][c].mean(), m[1][c].mean(), 4 * std::hypot(m[0][c].se(), m[1][c].se())) << c;
    EXPECT_LT(m[0][c].se(), 0.5 * m[1][c].se()) << c;
  }
}

TEST(VolumeTracer, RenderIsTheSameOnAnyThreadCount) {
  CloudLayerSettings s = smallCloudSettings(0.5, 0.8);
  s.extinction = 0.01;  // thin clouds keep the paths short
  const CloudLayer layer(s, makePhaseFunction("henyey-greenstein", "g=0.6"));
  Lighting light;
  light.sunDirection = normalize(Vec3{0.3, 0.5, 0.8});
  light.sunIrradiance = {1, 1, 1};
  light.sky = [](const Vec3& w) { return w.z > 0 ? Vec3{0.05, 0.1, 0.2} : Vec3{0, 0, 0}; };
  light.groundAlbedo = 0.2;
  const int w = 16, h = 9;
  const CameraRay camera = [&](double x, double y) {
    return normalize(Vec3{(x - w / 2.0) / w, 1, 0.8 - (y - h / 2.0) / w});
  };
  VolumeImage one, two;
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
    one = renderVolume(layer, light, {0, 0, 2}, camera, w, h, 4, 21);
  }
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
    two = renderVolume(layer, light, {0, 0, 2}, camera, w, h, 4, 21);
  }
  const VolumeImage other = renderVolume(layer, light, {0, 0, 2}, camera, w, h, 4, 22);
  ASSERT_EQ(one.radiance.size(), std::size_t(w * h));
  EXPECT_EQ(one.paths, w * h * 4);
  // Pixels whose paths all escape straight to the (constant) sky have no noise and match any
  // seed; the others (some variance) must differ with the seed.
  int noisy = 0, differ = 0;
  for (std::size_t i = 0; i < one.radiance.size(); ++i) {
    ASSERT_EQ(one.radiance[i], two.radiance[i]) << i;
    ASSERT_EQ(one.standardError[i], two.standardError[i]) << i;
    ASSERT_TRUE(isFinite(one.radiance[i]));
    const bool hasNoise = maxComponent(one.standardError[i]) > 0;
    noisy += hasNoise;
    differ += hasNoise && one.radiance[i] != other.radiance[i];
  }
  EXPECT_GT(noisy, w * h / 4);
  EXPECT_GE(differ, noisy * 9 / 10);
}

}  // namespace
}  // namespace radkit::media
