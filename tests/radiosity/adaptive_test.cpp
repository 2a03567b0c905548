// Adaptive subdivision: exact tiling and neighbours of refined meshes (geometry/refine.h), the
// shadow-boundary test against the similar-triangle shadow of a blocker, and the closed-form
// furnace and energy balance on meshes with T-junctions.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "geometry/refine.h"
#include "geometry/scene_loader.h"
#include "radiosity/adaptive.h"

#include "daylight/sky.h"
#include "test_scenes.h"
#include "tests/common/test_util.h"

namespace radkit {

// ---- refinement and neighbours (geometry/refine.h)

namespace {
/// A 2×2 grid on the unit square (z = 0, normal +z), one surface.
PatchMesh grid2() {
  test::MeshBuilder b;
  b.addRectangle("floor", {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 2, 2);
  return b.mesh();
}
double surfaceArea(const PatchMesh& m, int s) {
  double a = 0;
  for (int i = m.surfaceBegin[s]; i < m.surfaceBegin[s + 1]; ++i) a += m.patches[i].area;
  return a;
}
}  // namespace

// Splitting tiles the parent exactly: areas per surface unchanged, children on the parent's plane.
TEST(Refine, ExactAreasTileOnTheCornellBox) {
  Scene scene = loadScene(test::dataPath("cornell-box.json"));
  PatchMesh mesh = subdivide(scene, {0, 300});
  for (int round = 0; round < 3; ++round) {
    std::vector<char> split(mesh.patches.size(), 0);
    for (int i = round; i < mesh.size(); i += 3) split[i] = 1;
    RefinedMesh r = refinePatches(mesh, split);
    ASSERT_EQ(r.mesh.size(), mesh.size() + 3 * int(std::count(split.begin(), split.end(), 1)));
    for (std::size_t s = 0; s + 1 < mesh.surfaceBegin.size(); ++s)
      EXPECT_NEAR(surfaceArea(r.mesh, int(s)), surfaceArea(mesh, int(s)),
                  1e-12 * surfaceArea(mesh, int(s)));
    for (int k = 0; k < r.mesh.size(); ++k) {
      const Patch& parent = mesh.patches[r.parent[k]];
      EXPECT_NEAR(dot(r.mesh.patches[k].normal, parent.normal), 1.0, 1e-12);
      EXPECT_NEAR(dot(r.mesh.patches[k].centroid - parent.centroid, parent.normal), 0.0, 1e-9);
      EXPECT_EQ(r.mesh.patches[k].surface, parent.surface);
    }
    mesh = r.mesh;
  }
}

// One quarter of a 2×2 grid split, then one of its children split again: the whole neighbours
// see the children across the T-junctions, by construction of the grid.
TEST(Refine, ExactNeighboursAcrossTJunctions) {
  PatchMesh mesh = grid2();  // patches 0 (x<½,y<½), 1 (x>½,y<½), 2 (x<½,y>½), 3 (x>½,y>½)
  auto nb = surfaceNeighbours(mesh);
  EXPECT_EQ(nb[0], (std::vector<int>{1, 2, 3}));
  std::vector<char> split{1, 0, 0, 0};
  RefinedMesh r = refinePatches(mesh, split);  // children 0..3 of patch 0, then 1, 2, 3 as 4, 5, 6
  ASSERT_EQ(r.mesh.size(), 7);
  nb = surfaceNeighbours(r.mesh);
  auto near = [&](int i, double x, double y) {  // does patch i's list contain the child at (x, y)?
    for (int j : nb[i])
      if (std::fabs(r.mesh.patches[j].centroid.x - x) < 1e-9 &&
          std::fabs(r.mesh.patches[j].centroid.y - y) < 1e-9)
        return true;
    return false;
  };
  EXPECT_TRUE(near(4, 0.375, 0.125));  // right neighbour sees both children on its edge
  EXPECT_TRUE(near(4, 0.375, 0.375));
  EXPECT_FALSE(near(4, 0.125, 0.125));  // not the far child
  EXPECT_TRUE(near(5, 0.125, 0.375));   // top neighbour
  EXPECT_TRUE(near(5, 0.375, 0.375));
  std::vector<char> again(7, 0);
  for (int k = 0; k < 4; ++k)
    if (std::fabs(r.mesh.patches[k].centroid.x - 0.375) < 1e-9 &&
        std::fabs(r.mesh.patches[k].centroid.y - 0.125) < 1e-9)
      again[k] = 1;
  RefinedMesh r2 = refinePatches(r.mesh, again);
  nb = surfaceNeighbours(r2.mesh);
  int right = -1;
  for (int k = 0; k < r2.mesh.size(); ++k)
    if (std::fabs(r2.mesh.patches[k].centroid.x - 0.75) < 1e-9 &&
        std::fabs(r2.mesh.patches[k].centroid.y - 0.25) < 1e-9)
      right = k;
  ASSERT_GE(right, 0);
  int grandchildren = 0;  // the two grandchildren at x = 7/16 touching x = ½
  for (int j : nb[right]) grandchildren += std::fabs(r2.mesh.patches[j].centroid.x - 0.4375) < 1e-9;
  EXPECT_EQ(grandchildren, 2);
}

// ---- solveAdaptive

// A furnace has B = E/(1 − ρ) = 2 on every patch: no differences, nothing to refine.
TEST(Adaptive, ExactFurnaceNeedsNoRefinement) {
  Scene scene = loadScene(test::dataPath("furnace.json"));
  PipelineSettings s;
  s.mesh.targetPatches = 54;
  AdaptiveSettings a;
  a.tolerance = 1e-3;
  AdaptiveResult r = solveAdaptive(scene, s, a);
  ASSERT_EQ(r.rounds.size(), 1u);
  EXPECT_EQ(r.stopReason, "indicator below tolerance");
  EXPECT_LT(r.rounds[0].maxIndicator, 1e-4);
  for (const Vec3& b : r.final.radiosity) EXPECT_NEAR(b.x, 2.0, 1e-4);
}

// Closed cube, uniform ρ = 0.5: Σ A_i B_i = Σ A_i E_i / (1 − ρ) on any mesh, T-junctions
// included, up to the row-sum deviation δ of F: relative error ≤ ρδ/(1 − ρ(1 + δ)) + tolerance.
TEST(Adaptive, ExactEnergyBalanceWithTJunctions) {
  Scene scene = loadScene(test::dataPath("cube-one-emitter.json"));
  PipelineSettings s;
  s.mesh.targetPatches = 24;
  s.stopping.tolerance = 1e-10;
  AdaptiveSettings a;
  a.maxPatches = 200;
  a.tolerance = 0;
  AdaptiveResult r = solveAdaptive(scene, s, a);
  ASSERT_GT(r.rounds.size(), 2u);
  ASSERT_GT(r.final.mesh.size(), 100);
  double sumB = 0, sumE = 0, area = 0;
  for (int i = 0; i < r.final.mesh.size(); ++i) {
    const Patch& p = r.final.mesh.patches[i];
    sumB += p.area * r.final.radiosity[i].x;
    sumE += p.area * scene.materials[scene.surfaces[p.surface].material].emission.x;
    area += p.area;
  }
  EXPECT_NEAR(area, 6.0, 1e-12);
  double delta = r.final.formFactors->diagnostics.maxDeviationFromOne;
  EXPECT_NEAR(sumB / (sumE / 0.5), 1.0, 0.5 * delta / (1 - 0.5 * (1 + delta)) + 1e-8);
}

namespace {
/// Floor [0,1]² (10×10 patches) under a blocker [0.425, 0.575]² at z = ½ and a 1 cm lamp at
/// z = 1 centred over (½, ½): the blocker's shadow is [0.35, 0.65]² (similar triangles, factor 2).
Scene shadowScene(const test::TempDir& dir) {
  using nlohmann::json;
  auto sq = [](double x0, double x1, double z, bool up) {
    json a = {x0, x0, z}, b = {x1, x0, z}, c = {x1, x1, z}, d = {x0, x1, z};
    return up ? json::array({a, b, c, d}) : json::array({a, d, c, b});
  };
  json s = {{"name", "shadow"}, {"units", "m"}};
  s["materials"]["grey"] = {{"reflectance", {0.5, 0.5, 0.5}}};
  s["materials"]["lamp"] = {{"reflectance", {0, 0, 0}}, {"emission", {10, 10, 10}}};
  s["surfaces"] = {
      {{"name", "floor"}, {"material", "grey"}, {"polygon", sq(0, 1, 0, true)}},
      {{"name", "blocker"}, {"material", "grey"}, {"polygon", sq(0.425, 0.575, 0.5, true)}},
      {{"name", "lamp"}, {"material", "lamp"}, {"polygon", sq(0.495, 0.505, 1, false)}}};
  return loadScene(dir.file("shadow.json", s.dump()));
}
}  // namespace

// Exactly the floor patches that the shadow's edge crosses are flagged.
TEST(Adaptive, ExactShadowBoundaryPatches) {
  test::TempDir dir;
  Scene scene = shadowScene(dir);
  PatchMesh mesh = subdivide(scene, {0.01, 0});
  ASSERT_EQ(mesh.surfaceBegin[1], 100);
  RayScene rays(mesh);
  std::vector<char> flagged = shadowBoundaryPatches(scene, mesh, rays, 16);
  auto crosses = [](double lo, double hi) {
    return (lo < 0.35 && hi > 0.35) || (lo < 0.65 && hi > 0.65);
  };
  auto inside = [](double lo, double hi) { return hi > 0.35 && lo < 0.65; };
  for (int i = 0; i < 100; ++i) {
    const Patch& p = mesh.patches[i];
    double x0 = p.centroid.x - 0.05, x1 = p.centroid.x + 0.05, y0 = p.centroid.y - 0.05,
           y1 = p.centroid.y + 0.05;
    bool expected = (crosses(x0, x1) && inside(y0, y1)) || (crosses(y0, y1) && inside(x0, x1));
    EXPECT_EQ(bool(flagged[i]), expected)
        << "floor patch at " << p.centroid.x << ", " << p.centroid.y;
  }
  for (int i = 100; i < mesh.size(); ++i)
    EXPECT_FALSE(flagged[i]) << "patch " << i << " of the blocker or lamp";
}

// The sun overhead casts the blocker's square exactly (its disc's penumbra, 2.3 mm wide, lies
// within the corners' 1e-3 pull): exactly the floor patches whose corners straddle x or y =
// 0.425 or 0.575 inside the shadow are flagged, with no emitter in the scene.
TEST(Adaptive, ExactSunShadowBoundaryPatches) {
  test::TempDir dir;
  using nlohmann::json;
  auto sq = [](double x0, double x1, double z) {
    return json::array({json{x0, x0, z}, json{x1, x0, z}, json{x1, x1, z}, json{x0, x1, z}});
  };
  json s = {{"name", "sun-shadow"}, {"units", "m"}};
  s["materials"]["grey"] = {{"reflectance", {0.5, 0.5, 0.5}}};
  s["surfaces"] = {{{"name", "floor"}, {"material", "grey"}, {"polygon", sq(0, 1, 0)}},
                   {{"name", "blocker"}, {"material", "grey"}, {"polygon", sq(0.425, 0.575, 0.5)}}};
  s["sky"] = {{"type", "uniform"},
              {"radiance", 0},
              {"up", {0, 0, 1}},
              {"north", {0, 1, 0}},
              {"sun", {{"elevation", 90}, {"irradiance", 1000}}}};
  const Scene scene = loadScene(dir.file("sun.json", s.dump()));
  PatchMesh mesh = subdivide(scene, {0.01, 0});
  ASSERT_EQ(mesh.surfaceBegin[1], 100);
  RayScene rays(mesh);
  const SkyModel sky(*scene.sky);
  const std::vector<char> none = shadowBoundaryPatches(scene, mesh, rays, 16);
  EXPECT_EQ(std::count(none.begin(), none.end(), 1), 0);  // without the sky: no emitter
  const std::vector<char> flagged = shadowBoundaryPatches(scene, mesh, rays, 16, &sky);
  auto crosses = [](double lo, double hi) {
    return (lo < 0.425 && hi > 0.425) || (lo < 0.575 && hi > 0.575);
  };
  auto inside = [](double lo, double hi) { return hi > 0.425 && lo < 0.575; };
  for (int i = 0; i < 100; ++i) {
    const Patch& p = mesh.patches[i];
    const double x0 = p.centroid.x - 0.05, x1 = p.centroid.x + 0.05, y0 = p.centroid.y - 0.05,
                 y1 = p.centroid.y + 0.05;
    const bool expected =
        (crosses(x0, x1) && inside(y0, y1)) || (crosses(y0, y1) && inside(x0, x1));
    EXPECT_EQ(bool(flagged[i]), expected)
        << "floor patch at " << p.centroid.x << ", " << p.centroid.y;
  }
  EXPECT_EQ(std::count(flagged.begin(), flagged.end(), 1), 4);
}

// Refinement goes where the shadow edge is: after one round every patch the edge crosses is
// split, and nothing far from the edge (beyond its neighbours) is.
TEST(Adaptive, ExactRefinesAroundTheShadowEdge) {
  test::TempDir dir;
  Scene scene = shadowScene(dir);
  PipelineSettings s;
  s.mesh.maxArea = 0.01;
  AdaptiveSettings a;
  a.maxRounds = 1;
  a.splitFraction = 0.3;
  a.tolerance = 0;
  AdaptiveResult r = solveAdaptive(scene, s, a);
  ASSERT_EQ(r.rounds.size(), 2u);
  EXPECT_EQ(r.rounds[0].shadowPatches, 12);
  auto distance = [](const Vec3& c) {  // from the centroid to the shadow square's outline
    double dx = std::max(std::fabs(c.x - 0.5) - 0.15, 0.0),
           dy = std::max(std::fabs(c.y - 0.5) - 0.15, 0.0);
    double outside = std::hypot(dx, dy);
    double inside = std::min(0.15 - std::fabs(c.x - 0.5), 0.15 - std::fabs(c.y - 0.5));
    return outside > 0 ? outside : inside;
  };
  int ringChildren = 0;
  for (int i = r.final.mesh.surfaceBegin[0]; i < r.final.mesh.surfaceBegin[1]; ++i) {
    const Patch& p = r.final.mesh.patches[i];
    bool child = p.area < 0.005;
    if (child)
      EXPECT_LT(distance(p.centroid), 0.16) << p.centroid.x << ", " << p.centroid.y;
    else
      EXPECT_GT(distance(p.centroid), 0.04)
          << "unsplit patch on the edge " << p.centroid.x << ", " << p.centroid.y;
    ringChildren += child && distance(p.centroid) < 0.05;
  }
  EXPECT_EQ(ringChildren, 48);
}

}  // namespace radkit
