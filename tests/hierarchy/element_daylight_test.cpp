// Daylight per element in hierarchical radiosity (docs/daylight.md, docs/hierarchical.md): a
// plate held above one large floor face under a uniform sky and a sun. The refined leaves
// must follow the plate's shadow edge inside that face and match a dense solve of a finely
// meshed floor across the edge; the refinement must be deterministic for any thread count, and
// a scene without a sky must not change.
#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "geometry/scene_loader.h"
#include "hierarchy/hierarchical.h"
#include "radiosity/radiosity_pipeline.h"
#include "tests/common/test_util.h"

namespace radkit {
namespace {

constexpr double kRho = 0.5;
constexpr double kSunIrradiance = 200;  // W/m² per channel, normal to the sun
constexpr int kSunSamples = 256;
// The sun at 50° elevation, azimuth 120° (east of south-east): the plate's shadow on the floor
// is the plate moved by (1 m / tan 50°) away from the sun, x ∈ [−1.2267, −0.2267],
// y ∈ [−0.0804, 0.9196]. Its edges fall on no quadtree line of the floor.
const double kSunElevation = 50, kSunAzimuth = 120;

/// A 4 m × 4 m floor as one input face and a 1 m × 1 m plate 1 m above it, facing down.
std::string plateScene(bool sky, const std::string& skyType = "uniform") {
  std::string s = R"({"name": "plate-shadow", "units": "m",
    "materials": {"grey": {"reflectance": [0.5, 0.5, 0.5]},
                  "lamp": {"reflectance": [0.5, 0.5, 0.5], "emission": [20, 20, 20]}},
    "surfaces": [
      {"name": "floor", "material": "grey",
       "polygon": [[-2, -2, 0], [2, -2, 0], [2, 2, 0], [-2, 2, 0]]},
      {"name": "plate", "material": ")" +
                  std::string(sky ? "grey" : "lamp") + R"(",
       "polygon": [[-0.5, -0.5, 1], [-0.5, 0.5, 1], [0.5, 0.5, 1], [0.5, -0.5, 1]]}])";
  if (sky) {
    const std::string radiance =
        skyType == "uniform" ? R"("radiance": 10)" : R"("zenith_radiance": 10)";
    s += R"(, "sky": {"type": ")" + skyType + R"(", )" + radiance;
    if (skyType == "uniform")
      s += R"(, "sun": {"elevation": 50, "azimuth": 120, "irradiance": 200})";
    s += R"(, "samples": 256, "sun_samples": 256})";
  }
  return s + "}";
}

struct Rect {
  double x0, x1, y0, y1;
};

Rect bounds(const PatchMesh& mesh, int i) {
  const Patch& p = mesh.patches[i];
  Rect r{1e300, -1e300, 1e300, -1e300};
  for (int k = 0; k < p.vertexCount; ++k) {
    const Vec3 v = mesh.vertex(p, k);
    r.x0 = std::min(r.x0, v.x), r.x1 = std::max(r.x1, v.x);
    r.y0 = std::min(r.y0, v.y), r.y1 = std::max(r.y1, v.y);
  }
  return r;
}

double overlap(const Rect& a, const Rect& b) {
  return std::max(0.0, std::min(a.x1, b.x1) - std::max(a.x0, b.x0)) *
         std::max(0.0, std::min(a.y1, b.y1) - std::max(a.y0, b.y0));
}

/// Area-weighted radiosity (channel sum) of the floor over a region and its Monte Carlo
/// standard error from the patches' daylight estimates (ρ times their sky and sun errors; the
/// interreflected light, a few per cent here, is taken as exact).
struct RegionValue {
  double mean = 0, standardError = 0;
};

RegionValue region(const Scene& scene, const PatchMesh& mesh, const std::vector<Vec3>& radiosity,
                   const Daylight& daylight, const Rect& rect) {
  const SkyModel sky(*scene.sky);
  const double sunSum = 3 * kSunIrradiance * std::sin(kSunElevation * M_PI / 180);
  double area = 0, sum = 0, variance = 0;
  for (int i = 0; i < mesh.size(); ++i) {
    if (scene.surfaces[mesh.patches[i].surface].name != "floor") continue;
    const double a = overlap(bounds(mesh, i), rect);
    if (a <= 0) continue;
    const Vec3& b = radiosity[i];
    area += a, sum += a * (b.x + b.y + b.z);
    const Vec3& sun = daylight.sun[i];
    const double v = std::clamp((sun.x + sun.y + sun.z) / sunSum, 0.0, 1.0);
    const double sunError = sunSum * std::sqrt(v * (1 - v) / (kSunSamples - 1));
    const double e = daylight.skyStandardError[i];
    variance += a * a * kRho * kRho * (e * e + sunError * sunError);
  }
  return {sum / area, std::sqrt(variance) / area};
}

struct Solutions {
  Scene scene;
  HierarchicalResult hierarchical;
  PipelineResult dense;
};

const Solutions& solutions() {
  static const Solutions s = [] {
    test::TempDir dir;
    Solutions out;
    out.scene = loadScene(dir.file("plate.json", plateScene(true)));
    out.hierarchical = solveHierarchical(out.scene, HierarchicalSettings{});
    PipelineSettings dense;
    dense.mesh.maxArea = 0.01;  // 10 cm squares
    out.dense = runPipeline(out.scene, dense);
    return out;
  }();
  return s;
}

TEST(ElementDaylight, ShadowEdgeInsideOneFaceMatchesDenseFineMesh) {
  const Solutions& s = solutions();
  const HierarchicalResult& h = s.hierarchical;
  ASSERT_TRUE(h.daylightPerLeaf);
  ASSERT_TRUE(h.daylight && s.dense.daylight);
  EXPECT_GT(h.daylightSplits, 0);
  std::printf("%d leaves (%lld split for daylight), dense %d patches\n", h.leaves.size(),
              h.daylightSplits, s.dense.mesh.size());
  // Strips across the shadow's west edge (x = −1.2267) and north edge (y = 0.9196), away
  // from its corners: lit, across the edge, shadowed.
  const std::vector<std::pair<std::string, Rect>> strips = {
      {"west lit", {-1.5, -1.3, 0.2, 0.6}},   {"west edge", {-1.3, -1.1, 0.2, 0.6}},
      {"west shade", {-1.1, -0.9, 0.2, 0.6}}, {"north shade", {-0.9, -0.5, 0.6, 0.8}},
      {"north edge", {-0.9, -0.5, 0.8, 1.0}}, {"north lit", {-0.9, -0.5, 1.0, 1.2}}};
  for (const auto& [name, rect] : strips) {
    const RegionValue a = region(s.scene, h.leaves, h.radiosity, *h.daylight, rect);
    const RegionValue b = region(s.scene, s.dense.mesh, s.dense.radiosity, *s.dense.daylight, rect);
    const double se = std::hypot(a.standardError, b.standardError);
    std::printf("%-12s hierarchical %.3f ± %.3f, dense %.3f ± %.3f, difference %+.2f %%\n",
                name.c_str(), a.mean, a.standardError, b.mean, b.standardError,
                100 * (a.mean / b.mean - 1));
    EXPECT_NEAR(a.mean, b.mean, 0.02 * b.mean + 4 * se) << name;
  }
}

TEST(ElementDaylight, RefinementFollowsTheShadowEdge) {
  const Solutions& s = solutions();
  const HierarchicalResult& h = s.hierarchical;
  // Leaves the shadow's outline crosses against leaves at least 0.5 m from it, on the floor.
  const Rect shadow{-1.2267, -0.2267, -0.0804, 0.9196};
  double nearArea = 0, farArea = 0;
  int nearCount = 0, farCount = 0;
  for (int i = 0; i < h.leaves.size(); ++i) {
    if (s.scene.surfaces[h.leaves.patches[i].surface].name != "floor") continue;
    const Rect r = bounds(h.leaves, i);
    const double inside = overlap(r, shadow), area = h.leaves.patches[i].area;
    if (inside > 1e-12 && inside < area * (1 - 1e-9)) {
      nearArea += area, ++nearCount;
      continue;
    }
    const Rect grown{shadow.x0 - 0.5, shadow.x1 + 0.5, shadow.y0 - 0.5, shadow.y1 + 0.5};
    if (overlap(r, grown) <= 0) farArea += area, ++farCount;
  }
  ASSERT_GT(nearCount, 0);
  ASSERT_GT(farCount, 0);
  std::printf(
      "leaves crossing the shadow's outline: %d, mean area %.4g m²; at least 0.5 m away: "
      "%d, mean area %.4g m²\n",
      nearCount, nearArea / nearCount, farCount, farArea / farCount);
  EXPECT_LT(nearArea / nearCount, farArea / farCount / 16);
  // The outline's leaves carry little light each: none straddles more than τ's worth.
  EXPECT_LT(nearArea / nearCount, 0.01);
}

TEST(ElementDaylight, PerFaceDaylightMissesTheEdge) {
  // The same scene with daylight per input face: the edge strip is far off, so the test above
  // does tell the two apart.
  const Solutions& s = solutions();
  HierarchicalSettings settings;
  settings.elementDaylight = false;
  const HierarchicalResult h = solveHierarchical(s.scene, settings);
  EXPECT_FALSE(h.daylightPerLeaf);
  EXPECT_EQ(h.daylightSplits, 0);
  const Rect edge{-1.3, -1.1, 0.2, 0.6};
  // Per face, the result's daylight is per input face: each leaf takes its face's.
  Daylight leafDaylight;
  for (int n : h.leafNodes) {
    const int f = (*h.hierarchy)[n].face;
    leafDaylight.sun.push_back(h.daylight->sun[f]);
    leafDaylight.skyStandardError.push_back(h.daylight->skyStandardError[f]);
  }
  ASSERT_EQ(leafDaylight.sun.size(), std::size_t(h.leaves.size()));
  const double face = region(s.scene, h.leaves, h.radiosity, leafDaylight, edge).mean;
  const double dense =
      region(s.scene, s.dense.mesh, s.dense.radiosity, *s.dense.daylight, edge).mean;
  std::printf("daylight per input face: west edge strip %.3f against dense %.3f (%+.1f %%)\n", face,
              dense, 100 * (face / dense - 1));
  EXPECT_GT(std::fabs(face / dense - 1), 0.1);
}

TEST(ElementDaylight, EnergyBalanceCountsEachLeafsDaylight) {
  const Solutions& s = solutions();
  const HierarchicalResult& h = s.hierarchical;
  Vec3 taken{0, 0, 0};
  for (int i = 0; i < h.leaves.size(); ++i)
    taken += h.daylight->total(i) * h.leaves.patches[i].area;
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(h.energy.emitted[c], taken[c], 1e-9 * taken[c]);
  EXPECT_LT(h.energy.relativeImbalance, 0.01);
}

TEST(ElementDaylight, SameSeedSameBitsForOneAndTwoThreads) {
  test::TempDir dir;
  const Scene scene = loadScene(dir.file("plate.json", plateScene(true)));
  HierarchicalSettings settings;
  settings.epsilon = 3e-4;
  std::vector<std::vector<Vec3>> answers;
  std::vector<long long> splits;
  for (int threads : {1, 2}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    HierarchicalResult r = solveHierarchical(scene, settings);
    std::vector<Vec3> v = r.radiosity;
    for (int i = 0; i < r.leaves.size(); ++i) v.push_back(r.daylight->total(i));
    answers.push_back(v);
    splits.push_back(r.daylightSplits);
  }
  EXPECT_GT(splits[0], 0);
  EXPECT_EQ(splits[0], splits[1]);
  ASSERT_EQ(answers[0].size(), answers[1].size());
  EXPECT_EQ(std::memcmp(answers[0].data(), answers[1].data(), answers[0].size() * sizeof(Vec3)), 0);
}

TEST(ElementDaylight, NoiseAloneDoesNotSplit) {
  // An open floor under the CIE overcast sky: its daylight is the same everywhere (7πL_z/9),
  // though every sky sample sees a different radiance. Nothing may be split for daylight.
  test::TempDir dir;
  std::string s = plateScene(true, "cie-overcast");
  // The floor alone, without the plate.
  const std::size_t plate = s.find(R"(,
      {"name": "plate")");
  ASSERT_NE(plate, std::string::npos);
  s.erase(plate, s.find("}]", plate) + 1 - plate);
  const Scene scene = loadScene(dir.file("open.json", s));
  const HierarchicalResult r = solveHierarchical(scene, HierarchicalSettings{});
  EXPECT_EQ(r.daylightSplits, 0);
  for (int i = 0; i < r.leaves.size(); ++i) {
    const Vec3 d = r.daylight->total(i);
    EXPECT_NEAR(d.x, 7 * M_PI * 10 / 9, 0.05 * 7 * M_PI * 10 / 9);
  }
}

TEST(ElementDaylight, SceneWithoutSkyIsUnchanged) {
  // The lamp plate lights the floor; with no sky the switch changes nothing, bit for bit.
  test::TempDir dir;
  const Scene scene = loadScene(dir.file("lamp.json", plateScene(false)));
  std::vector<std::vector<Vec3>> answers;
  for (bool perElement : {true, false}) {
    HierarchicalSettings settings;
    settings.elementDaylight = perElement;
    HierarchicalResult r = solveHierarchical(scene, settings);
    EXPECT_FALSE(r.daylight);
    EXPECT_EQ(r.daylightSplits, 0);
    EXPECT_EQ(r.daylightElements, 0);
    answers.push_back(r.radiosity);
  }
  ASSERT_EQ(answers[0].size(), answers[1].size());
  EXPECT_EQ(std::memcmp(answers[0].data(), answers[1].data(), answers[0].size() * sizeof(Vec3)), 0);
}

}  // namespace
}  // namespace radkit
