// Photon emission and tracing: powers that sum to the emitted power, χ² of emission
// positions and directions against photonEmissionPdf, determinism across thread counts.
#include "photon/tracer.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <cstring>

#include "daylight/sky.h"
#include "geometry/ray_scene.h"
#include "geometry/scene_loader.h"
#include "geometry/subdivision.h"
#include "photon/image.h"
#include "tests/common/statistics.h"
#include "tests/common/test_util.h"
#include "util/sampling.h"

namespace radkit {
namespace {

// Šidák-corrected level for the two χ² tests of this file (positions, directions).
const double kAlpha = test::sidakAlpha(0.01, 2);

/// Two lamps facing down over nothing: a (2 × 1 m², exitance ea) at z = 1 and b (1 × 1 m²,
/// exitance eb) at z = 2, 3 m to the side.
std::string twoLamps(const test::TempDir& dir, const std::string& ea, const std::string& eb) {
  return dir.file("lamps.json", R"({"materials": {
      "a": {"reflectance": [0,0,0], "emission": )" +
                                    ea + R"(},
      "b": {"reflectance": [0,0,0], "emission": )" +
                                    eb + R"(}},
    "surfaces": [{"name": "a", "material": "a", "polygon": [[0,0,1],[0,1,1],[2,1,1],[2,0,1]]},
                 {"name": "b", "material": "b", "polygon": [[5,0,2],[5,1,2],[6,1,2],[6,0,2]]}]})");
}

TEST(PhotonEmission, ConstructPowersSumToEmittedPower) {
  test::TempDir dir;
  Scene scene = loadScene(twoLamps(dir, "[1, 1, 1]", "[3, 3, 3]"));
  PatchMesh mesh = subdivide(scene, {0.3, 0});
  EmitterSampler emitters(scene, mesh);
  const std::size_t n = 100000;
  Rng rng(3, 0, 0);
  Vec3 sum;
  for (std::size_t i = 0; i < n; ++i) {
    double u[5];
    for (double& v : u) v = rng.uniform();
    PhotonEmission e = samplePhotonEmission(emitters, n, u[0], u[1], u[2], u[3], u[4]);
    // One colour for every lamp: each photon carries exactly totalPower/N.
    EXPECT_NEAR(e.power.x, emitters.totalPower().x / n, 4e-16 * emitters.totalPower().x / n);
    sum += e.power;
  }
  // Σ of n terms each within 4·10⁻¹⁶ of totalPower/N, plus n roundings of at most 2^-53.
  const double tolerance = 4e-16 + n * 1.2e-16;
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(sum[c], emitters.totalPower()[c], tolerance * sum[c]);
  RayScene rays(mesh);
  PhotonSettings s;
  s.photons = n;
  PhotonTrace t = tracePhotons(scene, mesh, rays, emitters, s);
  EXPECT_EQ(t.stats.emitted, n);
  EXPECT_EQ(t.stats.stored,
            0u);  // nothing diffuse below the lamps; some of b's light hits a's back
  EXPECT_EQ(t.stats.escaped + t.stats.absorbed, n);
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(t.emittedPower[c], emitters.totalPower()[c], tolerance * sum[c]);
}

TEST(PhotonEmission, StatisticalPowersOfColouredLamps) {
  // Lamps of different colours: powers differ between lamps; their sum is the emitted power
  // in expectation. Compare within z standard errors of the mean, z for α = 0.01 over 3 channels.
  test::TempDir dir;
  Scene scene = loadScene(twoLamps(dir, "[1, 0.2, 0.1]", "[0.5, 2, 3]"));
  PatchMesh mesh = subdivide(scene, {0.3, 0});
  EmitterSampler emitters(scene, mesh);
  const std::size_t n = 200000;
  Rng rng(4, 0, 0);
  Vec3 sum, sum2;
  for (std::size_t i = 0; i < n; ++i) {
    double u[5];
    for (double& v : u) v = rng.uniform();
    Vec3 p = samplePhotonEmission(emitters, n, u[0], u[1], u[2], u[3], u[4]).power;
    sum += p;
    sum2 += mul(p, p);
  }
  for (int c = 0; c < 3; ++c) {
    const double se = std::sqrt(n * (sum2[c] / n - (sum[c] / n) * (sum[c] / n)));  // of Σ
    EXPECT_NEAR(sum[c], emitters.totalPower()[c], 3.4 * se) << "channel " << c;
    EXPECT_GT(se, 0);
  }
}

/// Expected counts: P(cell) = ∫ p_A dA over an (u, v) cell of a lamp (p_A is constant on a
/// patch, so the cell's area times p_A at its centre), and ∫ p_ω dω over a (cos θ, φ) cell by
/// an 8 × 8 midpoint rule on photonEmissionPdf / p_A.
TEST(PhotonEmission, StatisticalPositionsAndDirections) {
  test::TempDir dir;
  Scene scene = loadScene(twoLamps(dir, "[1, 1, 1]", "[3, 3, 3]"));
  PatchMesh mesh = subdivide(scene, {10, 0});  // one patch per lamp
  ASSERT_EQ(mesh.size(), 2);
  EmitterSampler emitters(scene, mesh);
  const int cells = 8, nz = 10, nphi = 16, n = 200000;
  std::vector<double> posObs(2 * cells * cells, 0), posExp(posObs.size(), 0);
  std::vector<double> dirObs(nz * nphi, 0), dirExp(dirObs.size(), 0);
  Rng rng(9, 0, 0);
  const Vec3 down{0, 0, -1};
  for (int i = 0; i < n; ++i) {
    double u[5];
    for (double& v : u) v = rng.uniform();
    PhotonEmission e = samplePhotonEmission(emitters, n, u[0], u[1], u[2], u[3], u[4]);
    ASSERT_GT(photonEmissionPdf(emitters, e.patch, e.normal, e.direction), 0);
    const double x0 = e.patch == 0 ? 0 : 5, width = e.patch == 0 ? 2 : 1;
    const int cx = std::min(cells - 1, int((e.origin.x - x0) / width * cells));
    const int cy = std::min(cells - 1, int(e.origin.y * cells));
    posObs[(e.patch * cells + cy) * cells + cx] += 1;
    const Vec3 local = Frame(down).toLocal(e.direction);
    const double phi = std::atan2(local.y, local.x) + M_PI;
    dirObs[std::min(nz - 1, int(local.z * nz)) * nphi +
           std::min(nphi - 1, int(phi / (2 * M_PI) * nphi))] += 1;
  }
  for (int p = 0; p < 2; ++p)
    for (int c = 0; c < cells * cells; ++c)
      posExp[p * cells * cells + c] =
          n * emitters.pdfArea(p) * mesh.patches[p].area / (cells * cells);
  const Frame frame(down);
  for (int iz = 0; iz < nz; ++iz)
    for (int ip = 0; ip < nphi; ++ip) {
      double integral = 0;
      for (int a = 0; a < 8; ++a)
        for (int b = 0; b < 8; ++b) {
          const double z = (iz + (a + 0.5) / 8) / nz,
                       phi = (ip + (b + 0.5) / 8) / nphi * 2 * M_PI - M_PI;
          const double s = std::sqrt(1 - z * z);
          const Vec3 w = frame.toWorld({s * std::cos(phi), s * std::sin(phi), z});
          integral += photonEmissionPdf(emitters, 0, down, w) / emitters.pdfArea(0);
        }
      dirExp[iz * nphi + ip] =
          n * integral / 64 * (1.0 / nz) * (2 * M_PI / nphi);  // dω = d(cos θ) dφ
    }
  EXPECT_GT(test::chiSquarePValue(posObs, posExp, "chi2_photon_positions.csv", kAlpha), kAlpha);
  EXPECT_GT(test::chiSquarePValue(dirObs, dirExp, "chi2_photon_directions.csv", kAlpha), kAlpha);
}

TEST(PhotonTracer, ExactSameForAnyThreadCount) {
  Scene scene = loadScene(test::dataPath("cornell-box-specular.json"));
  PatchMesh mesh = subdivide(scene, {0, 300});
  RayScene rays(mesh);
  EmitterSampler emitters(scene, mesh);
  PhotonSettings s;
  s.photons = 20000;
  s.seed = 17;
  PhotonTrace all = tracePhotons(scene, mesh, rays, emitters, s);
  PhotonTrace one;
  tbb::task_arena arena(1);
  arena.execute([&] { one = tracePhotons(scene, mesh, rays, emitters, s); });
  ASSERT_EQ(all.photons.size(), one.photons.size());
  ASSERT_GT(all.stats.caustic, 0u);  // glass and mirror blocks make caustics
  for (std::size_t k = 0; k < all.photons.size(); ++k) {
    ASSERT_EQ(0, std::memcmp(all.photons[k].position, one.photons[k].position, sizeof(float) * 3))
        << k;
    ASSERT_EQ(0, std::memcmp(all.photons[k].power, one.photons[k].power, sizeof(float) * 3)) << k;
    ASSERT_EQ(all.photons[k].patch, one.photons[k].patch);
  }
  EXPECT_EQ(all.emittedPower, one.emittedPower);
  // Every path ends exactly one way.
  EXPECT_EQ(all.stats.escaped + all.stats.absorbed + all.stats.truncated, all.stats.emitted);
  s.seed = 18;
  EXPECT_NE(tracePhotons(scene, mesh, rays, emitters, s).photons.size(), all.photons.size());
}

TEST(PhotonTracer, ConstructRejectsSceneWithoutEmitters) {
  test::TempDir dir;
  Scene scene =
      loadScene(dir.file("dark.json", R"({"materials": {"g": {"reflectance": [0.5,0.5,0.5]}},
    "surfaces": [{"name": "a", "material": "g", "polygon": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]]}]})"));
  PatchMesh mesh = subdivide(scene, {1, 0});
  RayScene rays(mesh);
  EmitterSampler emitters(scene, mesh);
  EXPECT_THROW(tracePhotons(scene, mesh, rays, emitters, PhotonSettings{}), std::invalid_argument);
}

TEST(PhotonTracer, StatisticalSkyAndSunPhotonsGiveTheSquaresIrradiance) {
  // Photons from a uniform sky L_s and the sun (normal irradiance E_n) onto a lone 1 m square
  // of ρ = 0.5 tilted by β: the power they deposit per unit area is its irradiance
  // πL_s(1 + cos β)/2 + E_n cos θ (a black ground: nothing from below the horizon). The
  // standard error is the spread of the photons' deposits. Sky and sun photons start on the
  // window the scene's bounding box projects to across their direction (the tilted square's
  // box is thick, so some miss).
  test::TempDir dir;
  for (double tilt : {0.0, -60.0}) {
    const double t = tilt * M_PI / 180;
    const Vec3 u{1, 0, 0}, v{0, std::cos(t), -std::sin(t)};
    auto p = [&](double a, double b) {
      const Vec3 x = u * a + v * b;
      return "[" + std::to_string(x.x) + ", " + std::to_string(x.y) + ", " + std::to_string(x.z) +
             "]";
    };
    const Scene scene = loadScene(dir.file(
        "square.json",
        R"({"materials": {"g": {"reflectance": [0.5, 0.5, 0.5]}}, "surfaces": [{"name": "s",
        "material": "g", "polygon": [)" +
            p(-0.5, -0.5) + ", " + p(0.5, -0.5) + ", " + p(0.5, 0.5) + ", " + p(-0.5, 0.5) +
            R"(]}], "sky": {"type": "uniform", "radiance": [10, 20, 40], "up": [0, 0, 1],
        "north": [0, 1, 0], "sun": {"elevation": 40, "azimuth": 135,
        "irradiance": [300, 500, 700]}}})"));
    const PatchMesh mesh = subdivide(scene, {1, 0});
    const RayScene rays(mesh);
    const EmitterSampler emitters = photonEmitters(scene, mesh);
    ASSERT_TRUE(emitters.empty());
    PhotonSettings s;
    s.photons = 400000;
    const PhotonTrace trace = tracePhotons(scene, mesh, rays, emitters, s);
    const SkyModel model(*scene.sky);
    const Vec3 normal = mesh.patches[0].normal;
    const double cosSun = dot(normal, model.sunDirection());
    ASSERT_GT(cosSun, 0.1);
    const Vec3 expected =
        Vec3{10, 20, 40} * (M_PI * (1 + normal.z) / 2) + Vec3{300, 500, 700} * cosSun;
    Vec3 sum, sum2;
    for (const Photon& ph : trace.photons) sum += ph.flux(), sum2 += mul(ph.flux(), ph.flux());
    double area = 0;  // the square's patches'
    for (const Patch& patch : mesh.patches) area += patch.area;
    const double n = double(s.photons);
    for (int c = 0; c < 3; ++c) {
      const double se = std::sqrt(std::max(0.0, sum2[c] - sum[c] * sum[c] / n)) / area;
      EXPECT_NEAR(sum[c] / area, expected[c], 4 * se) << "tilt " << tilt << " channel " << c;
      EXPECT_LT(se, 0.03 * expected[c]);
      // Teeth: without the sun, or without the sky, far off.
      EXPECT_GT(std::fabs(sum[c] / area - (expected[c] - Vec3{300, 500, 700}[c] * cosSun)), 8 * se);
      EXPECT_GT(std::fabs(sum[c] / area - Vec3{300, 500, 700}[c] * cosSun), 8 * se);
    }
    // The windows contain the square's outline seen from every direction, so the power
    // through them is at least what the square intercepts (its irradiance times its area), and
    // the photons that land carry that share of it.
    for (int c = 0; c < 3; ++c) EXPECT_GE(trace.skyPower[c], expected[c] * area) << c;
  }
}

TEST(PhotonImage, StatisticalFinalGatherUnderTheSkyMeetsTheClosedForm) {
  // The photon final gather of a lone flat square (ρ = 0.5) under a uniform sky L_s and the
  // sun: its direct term estimates sky and sun (MIS), its gather rays all leave the scene and
  // carry the other half, so the image is ρ(πL_s + E_n sin 40°)/π everywhere on the square.
  // Error bar from 8 seeds' spread of the image mean (photons and gather rays both reseeded).
  test::TempDir dir;
  const Scene scene = loadScene(dir.file("flat.json", R"({"materials": {"g": {"reflectance":
      [0.5, 0.5, 0.5]}}, "surfaces": [{"name": "s", "material": "g", "polygon": [[-0.5, -0.5, 0],
      [0.5, -0.5, 0], [0.5, 0.5, 0], [-0.5, 0.5, 0]]}], "sky": {"type": "uniform", "radiance":
      [10, 20, 40], "up": [0, 0, 1], "north": [0, 1, 0], "sun": {"elevation": 40, "azimuth": 135,
      "irradiance": [300, 500, 700]}}})"));
  const PatchMesh mesh = subdivide(scene, {1, 0});
  const RayScene rays(mesh);
  const EmitterSampler emitters = photonEmitters(scene, mesh);
  Camera camera;
  camera.position = {0, 0, 1};
  camera.lookAt = {0, 0, 0};
  camera.up = {0, 1, 0};
  camera.fovDeg = 30;  // sees only the square
  const double expected = 0.5 * (M_PI * 20 + 500 * std::sin(40 * M_PI / 180)) / M_PI;
  std::vector<double> means;
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    PhotonSettings ps;
    ps.photons = 20000;
    ps.seed = seed;
    ps.gatherRays = 16;
    PhotonMaps maps = buildPhotonMaps(mesh, tracePhotons(scene, mesh, rays, emitters, ps).photons);
    maps.global->precomputeIrradiance(ps.neighbours, ps.filter, ps.precomputeStride);
    const PhotonScene in{scene, mesh, rays, emitters, *maps.global, *maps.caustic};
    const RadianceImage img = renderPhotonImage(in, camera, 8, 8, PhotonView::FinalGather, ps);
    double m = 0;
    for (const Vec3& v : img.radiance) m += v.y / img.radiance.size();
    means.push_back(m);
  }
  double mean = 0, spread = 0;
  for (double m : means) mean += m / means.size();
  for (double m : means) spread += (m - mean) * (m - mean);
  const double se = std::sqrt(spread / (means.size() - 1) / means.size());
  // Student's t with 7 degrees of freedom at two-sided 0.001: 5.41.
  EXPECT_NEAR(mean, expected, 5.41 * se);
  EXPECT_LT(se, 0.01 * expected);
  EXPECT_GT(std::fabs(mean - 0.5 * 20), 10 * se);  // the sun left out
}

}  // namespace
}  // namespace radkit
