// The photon map: k-nearest queries against brute force, the kernels' exact weights, and the
// density estimate's bias under a point light, which must shrink as k/N does.
#include "photon/map.h"

#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "geometry/ray_scene.h"
#include "geometry/scene_loader.h"
#include "geometry/subdivision.h"
#include "photon/tracer.h"
#include "render/radiosity_image.h"
#include "tests/common/test_util.h"
#include "util/sampling.h"

namespace radkit {
namespace {

Photon photonAt(const Vec3& x, double power, int patch) {
  Photon p;
  for (int c = 0; c < 3; ++c) p.position[c] = float(x[c]), p.power[c] = float(power);
  p.patch = patch;
  return p;
}

/// A uniform point on patch p of the mesh (a quad).
Vec3 pointOnPatch(const PatchMesh& mesh, int p, Rng& rng) {
  Vec3 v[4];
  for (int c = 0; c < 4; ++c) v[c] = mesh.vertex(mesh.patches[p], c);
  return samplePatchUniform(v, 4, rng.uniform(), rng.uniform());
}

TEST(PhotonMap, ExactKernelWeights) {
  // Three unit photons at d = 0, 0.5, 1 on one patch: r = 1 (the third gets weight zero).
  Scene scene = loadScene(test::dataPath("parallel-squares.json"));
  PatchMesh mesh = subdivide(scene, {10, 0});
  const Vec3 n = mesh.patches[0].normal;
  const Vec3 c = mesh.patches[0].centroid;
  const Frame f(n);
  PhotonMap map(mesh, {photonAt(c, 1, 0), photonAt(c + f.s * 0.5, 1, 0), photonAt(c + f.t, 1, 0)});
  // Epanechnikov: (2/πr²) Σ (1 − d²/r²) = (2/π)(1 + 0.75); cone: (3/πr²) Σ (1 − d/r) = (3/π)(1 +
  // 0.5).
  EXPECT_NEAR(map.irradiance(c, n, 3, IrradianceFilter::Epanechnikov).irradiance.x, 3.5 / M_PI,
              1e-6);
  EXPECT_NEAR(map.irradiance(c, n, 3, IrradianceFilter::Cone).irradiance.y, 4.5 / M_PI, 1e-6);
  EXPECT_NEAR(map.irradiance(c, n, 3, IrradianceFilter::Cone).radius, 1, 1e-6);
  // A query facing another way sees none of them.
  EXPECT_EQ(map.irradiance(c, f.s, 3, IrradianceFilter::Cone).photons, 0);
}

TEST(PhotonMap, ExactNearestMatchesBruteForce) {
  Scene scene = loadScene(test::dataPath("perpendicular-squares.json"));
  PatchMesh mesh = subdivide(scene, {10, 0});
  ASSERT_EQ(mesh.size(), 2);
  std::vector<Photon> photons;
  Rng rng(21, 0, 0);
  for (int k = 0; k < 20000; ++k)
    photons.push_back(photonAt(pointOnPatch(mesh, k % 2, rng), 1, k % 2));
  // One kd-tree, and the same photons cut into octree cells of at most 1000 (many parts, some
  // of whose boxes lie nearer than the k-th photon): both must find exactly the brute force's.
  for (std::size_t perPart : {kMaxPhotonsPerKdPart, std::size_t(1000)}) {
    PhotonMap map(mesh, photons, perPart);
    EXPECT_EQ(map.kdParts() > 1, perPart == 1000) << map.kdParts();
    const std::vector<Photon> ordered = map.photons();  // indices refer to the map's (Morton) order
    ASSERT_EQ(ordered.size(), 20000u);
    std::vector<std::uint32_t> index;
    std::vector<float> d2;
    for (int q = 0; q < 50; ++q) {
      const Photon& at = ordered[std::size_t(q) * 397 % ordered.size()];
      const Vec3 n = mesh.patches[at.patch].normal;
      map.nearest(at.point(), n, 30, index, d2);
      std::vector<std::pair<float, std::uint32_t>> brute;
      for (std::uint32_t i = 0; i < ordered.size(); ++i) {
        if (ordered[i].patch != at.patch) continue;  // the other square is perpendicular
        float s = 0;
        for (int c = 0; c < 3; ++c)
          s +=
              (ordered[i].position[c] - at.position[c]) * (ordered[i].position[c] - at.position[c]);
        brute.push_back({s, i});
      }
      std::partial_sort(brute.begin(), brute.begin() + 30, brute.end());
      ASSERT_EQ(index.size(), 30u);
      for (int k = 0; k < 30; ++k) {
        EXPECT_EQ(d2[k], brute[k].first) << "query " << q << " rank " << k;
        EXPECT_EQ(index[k], brute[k].second) << "query " << q << " rank " << k;
      }
    }
  }
}

// Precomputed irradiance (every 4th photon, its own octree cells) looked up through many kd
// parts gives the one-tree map's bits, on the photons and between them.
TEST(PhotonMap, ExactPrecomputedLookupIndependentOfParts) {
  Scene scene = loadScene(test::dataPath("perpendicular-squares.json"));
  PatchMesh mesh = subdivide(scene, {10, 0});
  std::vector<Photon> photons;
  Rng rng(5, 0, 0);
  for (int k = 0; k < 12000; ++k) {
    photons.push_back(photonAt(pointOnPatch(mesh, k % 2, rng), 1 + k % 7, k % 2));
    photons.back().path = std::uint32_t(k);
  }
  PhotonMap one(mesh, photons), many(mesh, photons, 500);
  ASSERT_EQ(one.kdParts(), 1u);
  ASSERT_GT(many.kdParts(), 8u);
  ASSERT_EQ(one.photons().size(), many.photons().size());
  for (std::size_t i = 0; i < one.photons().size(); ++i)  // the cut keeps the Morton order
    ASSERT_EQ(one.photons()[i].path, many.photons()[i].path);
  one.precomputeIrradiance(40, IrradianceFilter::Epanechnikov, 4);
  many.precomputeIrradiance(40, IrradianceFilter::Epanechnikov, 4);
  int nonzero = 0;
  for (int q = 0; q < 400; ++q) {
    const Vec3 x = pointOnPatch(mesh, q % 2, rng);
    const Vec3 n = mesh.patches[q % 2].normal;
    const Vec3 a = one.precomputedIrradiance(x, n), b = many.precomputedIrradiance(x, n);
    EXPECT_EQ(a.x, b.x) << q;
    EXPECT_EQ(a.z, b.z) << q;
    nonzero += a.x > 0;
  }
  EXPECT_GT(nonzero, 390);
}

/// Relative errors of independent estimates at the point below the lamp of
/// data/point-light-plane.json, with N photons (config B) and with N/4 (config A), both at k.
/// Each of R traces (seeds 1..R) of N photons gives one B map and, split by path into four
/// quarters whose powers count four times, four A maps.
struct BiasMeasurement {
  double mean = 0, standardError = 0;
  explicit BiasMeasurement(const std::vector<double>& e) {
    double s2 = 0;
    for (double v : e) mean += v / e.size();
    for (double v : e) s2 += (v - mean) * (v - mean);
    standardError = std::sqrt(s2 / (e.size() - 1) / e.size());
  }
};

std::pair<BiasMeasurement, BiasMeasurement> pointLightBias(std::size_t photons, int k,
                                                           int repeats) {
  Scene scene = loadScene(test::dataPath("point-light-plane.json"));
  PatchMesh mesh = subdivide(scene, {1e4, 0});
  RayScene rays(mesh);
  EmitterSampler emitters(scene, mesh);
  // Lambertian lamp of power Φ: intensity (Φ/π) cos θ, so E(x) = (Φ/π) h²/(h² + x²)²; the
  // square's size s adds a relative O(s²/h²) = 10⁻⁶.
  const double h = 1, exact = luminance(emitters.totalPower()) / (M_PI * h * h);
  const IrradianceFilter filter = IrradianceFilter::Epanechnikov;
  std::vector<double> quarter(4 * repeats), full(repeats);
  tbb::parallel_for(0, repeats, [&](int j) {
    PhotonSettings s;
    s.photons = photons;
    s.seed = std::uint64_t(j) + 1;
    std::vector<Photon> all = tracePhotons(scene, mesh, rays, emitters, s).photons;
    auto relativeError = [&](std::vector<Photon> p, double scale) {
      PhotonMap map(mesh, std::move(p));
      return scale * luminance(map.irradiance({0, 0, 0}, {0, 0, 1}, k, filter).irradiance) / exact -
             1;
    };
    for (std::size_t q = 0; q < 4; ++q) {
      std::vector<Photon> part;
      for (const Photon& p : all)
        if (p.path / (photons / 4) == q) part.push_back(p);
      quarter[4 * j + q] = relativeError(std::move(part), 4);
    }
    full[j] = relativeError(std::move(all), 1);
  });
  return {BiasMeasurement(quarter), BiasMeasurement(full)};
}

// Below the lamp E(ρ) ≈ E₀(1 − 2ρ²/h²), and the estimate's expected relative error is
// −2 (k−1)/(3N) for the Epanechnikov kernel (docs/photon-mapping.md): proportional to k/N.
// Measured at k/N = 0.05 (a) and at N four times larger (b): a must be resolved (beyond z
// standard errors) and agree with the prediction; b must be a quarter of a within the
// combined error. Each estimate's own spread is about 1.15/√k (the kernel's ∫K²).
TEST(PhotonMap, StatisticalPointLightBiasShrinksAsKOverN) {
  const double z = 3.3;  // two-sided α = 0.01 Šidák-corrected over 3 checks
  const int k = 200, repeats = 200;
  const std::size_t photons = 16000;
  auto [a, b] = pointLightBias(photons, k, repeats);
  const double predictedA = -2.0 * (k - 1) / (3.0 * photons / 4);
  std::printf("bias at k/N = 0.05: %.5f ± %.5f (predicted %.5f); at 0.0125: %.5f ± %.5f\n", a.mean,
              a.standardError, predictedA, b.mean, b.standardError);
  EXPECT_LT(a.mean + z * a.standardError, 0);
  EXPECT_NEAR(a.mean, predictedA, z * a.standardError);
  EXPECT_NEAR(b.mean, a.mean / 4, z * std::hypot(b.standardError, a.standardError / 4));
}

}  // namespace
}  // namespace radkit
