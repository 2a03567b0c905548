// Terrain: the PCG hash against its published outputs and a χ² test of uniformity, the noise's
// defining properties, the heightfield's scaling and the meshes as written and read back.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

#include "geometry/mesh_reader.h"
#include "geometry/ray_scene.h"
#include "noise/noise2d.h"
#include "terrain/heightfield.h"
#include "terrain/landscape.h"
#include "tests/common/statistics.h"
#include "tests/common/test_util.h"
#include "util/sampling.h"

namespace radkit::terrain {
namespace {

TEST(Terrain, PcgHashGivesThePublishedOutputs) {
  // Jarzynski and Olano 2020, pcg_hash: 0 -> 129708002, 1 -> 2831084092.
  EXPECT_EQ(hashPCG(0), 129708002u);
  EXPECT_EQ(hashPCG(1), 2831084092u);
}

TEST(Terrain, PcgHashIsUniform) {
  // Consecutive inputs (what a lattice feeds it) into 1 024 bins by the top bits, and by the
  // low bits: a χ² test at 1e-3 each.
  const int bins = 1024, n = 1 << 20;
  std::vector<double> high(bins, 0), low(bins, 0);
  for (std::uint32_t v = 0; v < std::uint32_t(n); ++v) {
    const std::uint32_t h = hashPCG(v);
    high[h >> 22] += 1, low[h & (bins - 1)] += 1;
  }
  const std::vector<double> expected(bins, double(n) / bins);
  EXPECT_GT(test::chiSquarePValue(high, expected, "pcg-high", 1e-3), 1e-3);
  EXPECT_GT(test::chiSquarePValue(low, expected, "pcg-low", 1e-3), 1e-3);
}

TEST(Terrain, GradientNoiseVanishesOnTheLatticeAndIsContinuous) {
  for (int i = -3; i <= 3; ++i)
    for (int j = -3; j <= 3; ++j) EXPECT_EQ(gradientNoise(i, j, 7), 0.0);
  double largest = 0, jump = 0;
  for (int k = 0; k < 20000; ++k) {
    const double x = -20 + k * 0.002, y = 3.3 + 0.37 * std::sin(k * 0.01);
    const double v = gradientNoise(x, y, 7);
    largest = std::max(largest, std::fabs(v));
    jump = std::max(jump, std::fabs(gradientNoise(x + 1e-7, y, 7) - v));
  }
  EXPECT_LT(largest, 1.0);  // bounded by √2/2 in theory for unit gradients
  EXPECT_GT(largest, 0.3);  // and not degenerate
  EXPECT_LT(jump, 1e-6);    // Lipschitz: no seams between cells
  EXPECT_NE(gradientNoise(0.5, 0.5, 7), gradientNoise(0.5, 0.5, 8));  // the seed matters
}

TEST(Terrain, FractalsFollowTheirDefinitions) {
  FractalSettings one;
  one.octaves = 1;
  EXPECT_EQ(fbm(1.3, 2.7, one), gradientNoise(1.3, 2.7, one.seed));
  // Ridged, one octave: (offset − |n|)².
  const double n = gradientNoise(1.3, 2.7, one.seed);
  EXPECT_DOUBLE_EQ(ridgedMultifractal(1.3, 2.7, one), (1 - std::fabs(n)) * (1 - std::fabs(n)));
  FractalSettings s;
  for (int k = 0; k < 1000; ++k) EXPECT_GE(ridgedMultifractal(k * 0.173, k * 0.091, s), 0.0);
  // fBm's octaves add lac^(−iH)-weighted noise: two octaves by hand.
  FractalSettings two;
  two.octaves = 2, two.H = 0.8;
  EXPECT_DOUBLE_EQ(fbm(0.4, 0.9, two),
                   gradientNoise(0.4, 0.9, two.seed) +
                       gradientNoise(0.8, 1.8, two.seed + 1) * std::pow(2.0, -0.8));
}

TEST(Terrain, HeightfieldIsDeterministicAndScaled) {
  TerrainSettings s;
  s.resolution = 65;
  const Heightfield a = makeHeightfield(s), b = makeHeightfield(s);
  EXPECT_EQ(a.z, b.z);
  EXPECT_DOUBLE_EQ(*std::min_element(a.z.begin(), a.z.end()), 0.0);
  EXPECT_DOUBLE_EQ(*std::max_element(a.z.begin(), a.z.end()), s.height);
  s.fractal.seed = 2;
  EXPECT_NE(makeHeightfield(s).z, a.z);
  EXPECT_DOUBLE_EQ(a.vertex(0, 0).x, -s.size / 2);
  EXPECT_DOUBLE_EQ(a.vertex(64, 64).y, s.size / 2);
}

TEST(Terrain, MeshFacesUpAndMaterialsFollowSlopeAndHeight) {
  TerrainSettings s;
  s.resolution = 97;
  const Heightfield f = makeHeightfield(s);
  const TerrainMesh m = triangulate(f, s);
  ASSERT_EQ(m.triangles.size(), std::size_t(2 * 96 * 96));
  std::set<TerrainMaterial> seen;
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    const auto& tri = m.triangles[t];
    const Vec3 a = m.vertices[tri[0]], b = m.vertices[tri[1]], c = m.vertices[tri[2]];
    const Vec3 normal = normalize(cross(b - a, c - a));
    ASSERT_GT(normal.z, 0);  // a heightfield's faces all face up
    const double slope = std::acos(normal.z) * 180 / M_PI;
    const double h = (a.z + b.z + c.z) / 3 / s.height;
    const TerrainMaterial expect = h > s.snowLine && slope <= s.snowSlopeDeg ? TerrainMaterial::Snow
                                   : slope > s.rockSlopeDeg                  ? TerrainMaterial::Rock
                                                            : TerrainMaterial::Grass;
    EXPECT_EQ(m.material[t], expect) << t;
    seen.insert(m.material[t]);
  }
  EXPECT_EQ(seen.size(), 3u);  // the default landscape has all three
}

TEST(Terrain, WrittenPartsReadBackWithTheirTriangles) {
  TerrainSettings s;
  s.resolution = 33;
  const TerrainMesh m = triangulate(makeHeightfield(s), s);
  test::TempDir dir;
  std::size_t total = 0;
  for (const char* ext : {".obj", ".ply"}) {
    total = 0;
    for (int k = 0; k < 3; ++k) {
      const std::string path = dir.path(std::string("part") + std::to_string(k) + ext);
      const std::size_t n = writeTerrainPart(path, m, TerrainMaterial(k));
      total += n;
      if (n == 0) continue;
      const RawMesh raw = readMeshFile(path);
      EXPECT_EQ(raw.faces.size(), n) << path;
    }
    EXPECT_EQ(total, m.triangles.size());
  }
}

TEST(Terrain, MarchedHitsAgreeWithEmbreeOnTheExportedMesh) {
  // The marcher walks the same piecewise-linear surface Embree gets as triangles: the same
  // rays must hit at the same distance (Embree tests in single precision: 1e-6 of the
  // distance, plus 1 mm, across the surface).
  TerrainSettings s;
  s.resolution = 129;
  const TerrainSurface surface(makeHeightfield(s), s);
  const PatchMesh mesh = terrainPatchMesh(surface.mesh());
  ASSERT_EQ(mesh.size(), int(surface.mesh().triangles.size()));
  const RayScene rays(mesh);
  Rng rng(5, 0, 0);
  int hits = 0, agree = 0, n = 20000;
  double worst = 0;
  for (int k = 0; k < n; ++k) {
    // From above the field, downwards at elevations from 3° to 90°, any azimuth.
    const Vec3 o{(rng.uniform() - 0.5) * s.size, (rng.uniform() - 0.5) * s.size,
                 surface.top() + 50 + 500 * rng.uniform()};
    const double e = (3 + 87 * rng.uniform()) * M_PI / 180, a = 2 * M_PI * rng.uniform();
    const Vec3 d{std::cos(e) * std::sin(a), std::cos(e) * std::cos(a), -std::sin(e)};
    const auto march = marchTerrain(surface, o, d, 100000);
    const auto embree = rays.closestHit(o, d, 0.0);
    if (bool(march) != bool(embree)) continue;
    ++agree;
    if (!march) continue;
    ++hits;
    // Single precision places the hit to ~1e-7 of the coordinates across the surface; along
    // the ray that grows as 1/|cos| of the angle to the normal.
    const double cosine = std::fabs(dot(d, surface.normal(march->triangle)));
    const double err = std::fabs(march->t - embree->distance);
    worst = std::max(worst, err * cosine / (1e-3 + 1e-6 * embree->distance));
  }
  EXPECT_EQ(agree, n);
  EXPECT_GT(hits, n / 2);
  EXPECT_LE(worst, 1.0);
  std::printf("marched vs Embree: %d of %d rays hit, worst difference %.3g of the bound\n", hits, n,
              worst);
}

TEST(Terrain, SoftShadowBehindAWall) {
  // Flat ground with a 100 m wall along one row of vertices, 1 250 m north of the point: the
  // wall's top is atan(100/1250) = 4.574° up. The sun well below that is hidden, well above it
  // seen (how sharp the marcher's penumbra is, the landscape report measures against Embree).
  TerrainSettings s;
  Heightfield f;
  f.n = 33, f.size = 4000;  // 125 m spacing
  f.z.assign(std::size_t(f.n) * f.n, 0.0);
  for (int i = 0; i < f.n; ++i) f.z[std::size_t(20) * f.n + i] = 100;
  const TerrainSurface surface(f, s);
  const Vec3 p = f.vertex(16, 10) + Vec3{0, 0, 1e-6};
  const double radius = 0.004675, edge = std::atan(100.0 / 1250.0);
  auto sun = [](double e) { return Vec3{0, std::cos(e), std::sin(e)}; };
  EXPECT_EQ(softShadow(surface, p, sun(edge - 3 * M_PI / 180), radius, 4096), 0.0);
  EXPECT_EQ(softShadow(surface, p, sun(edge + 3 * M_PI / 180), radius, 4096), 1.0);
  EXPECT_EQ(softShadow(surface, p, {0, 0, 1}, radius, 4096), 1.0);
}

}  // namespace
}  // namespace radkit::terrain
