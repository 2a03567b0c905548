#include "render/emitters.h"

#include <gtest/gtest.h>

#include "bsdf/specular.h"
#include "geometry/scene_loader.h"
#include "geometry/subdivision.h"
#include "tests/common/statistics.h"
#include "tests/common/test_util.h"
#include "util/sampling.h"

namespace radkit {
namespace {

TEST(Specular, Exact) {
  // Normal incidence: ((eta - 1)/(eta + 1))², the same from either side.
  EXPECT_NEAR(fresnelDielectric(1, 1.5), 0.04, 1e-15);
  EXPECT_NEAR(fresnelDielectric(-1, 1.5), 0.04, 1e-15);
  // Beyond the critical angle inside glass (sin θc = 1/1.5): total internal reflection.
  EXPECT_EQ(fresnelDielectric(-std::cos(45 * M_PI / 180), 1.5), 1.0);
  // Grazing incidence reflects everything.
  EXPECT_NEAR(fresnelDielectric(1e-9, 1.5), 1.0, 1e-6);
  Vec3 n{0, 0, 1};
  Vec3 wo = normalize(Vec3{1, 0, 1});
  EXPECT_NEAR(length(reflect(wo, n) - Vec3{-wo.x, 0, wo.z}), 0, 1e-15);
  Vec3 wt;
  ASSERT_TRUE(refract(wo, n, 1.5, wt));
  // Snell: sin θi = 1.5 sin θt, and the refracted ray continues on the far side.
  EXPECT_NEAR(std::sqrt(1 - wo.z * wo.z), 1.5 * std::sqrt(1 - wt.z * wt.z), 1e-14);
  EXPECT_LT(wt.z, 0);
  EXPECT_NEAR(length(wt), 1, 1e-14);
  EXPECT_FALSE(refract(normalize(Vec3{1, 0, 0.3}), n, 1 / 1.5, wt));  // glass to air, steep
}

TEST(EmitterSampler, Construct) {
  Scene scene = loadScene(test::dataPath("cornell-box.json"));
  PatchMesh mesh = subdivide(scene, {0, 500});
  EmitterSampler s(scene, mesh);
  ASSERT_FALSE(s.empty());
  // Σ A E over the light: 130 × 105 mm² × (17, 12, 4) W/m², in scene units² · W/m².
  EXPECT_NEAR(s.totalPower().x, 13650.0 * 17, 1e-6);
  EXPECT_NEAR(s.totalPower().z, 13650.0 * 4, 1e-6);
  EmitterSample e = s.sample(0.3, 0.5, 0.5);
  EXPECT_EQ(e.emission, (Vec3{17, 12, 4}));
  EXPECT_NEAR(e.point.y, 548.8, 1e-9);
  EXPECT_NEAR(e.pdfArea, 1.0 / 13650.0, 1e-15);  // uniform over one light of one radiance
}

TEST(EmitterSampler, Statistical) {
  // Two emitters of different power: patch choices must follow power (χ² over patches).
  test::TempDir dir;
  std::string file = dir.file("s.json", R"({"materials": {
      "a": {"reflectance": [0,0,0], "emission": [1, 1, 1]},
      "b": {"reflectance": [0,0,0], "emission": [3, 3, 3]}},
    "surfaces": [{"name": "a", "material": "a", "polygon": [[0,0,0],[2,0,0],[2,1,0],[0,1,0]]},
                 {"name": "b", "material": "b", "polygon": [[0,0,1],[0,1,1],[1,1,1],[1,0,1]]}]})");
  Scene scene = loadScene(file);
  PatchMesh mesh = subdivide(scene, {0.1, 0});
  EmitterSampler s(scene, mesh);
  Rng rng(5, 0, 0);
  const int n = 200000;
  std::vector<double> observed(mesh.size(), 0), expected(mesh.size(), 0);
  Vec3 meanOnB;
  int onB = 0;
  for (int k = 0; k < n; ++k) {
    EmitterSample e = s.sample(rng.uniform(), rng.uniform(), rng.uniform());
    observed[e.patch] += 1;
    if (mesh.patches[e.patch].surface == 1) meanOnB += e.point, ++onB;
  }
  double total = 2 * 1 + 1 * 3;  // A·E of each surface
  for (int i = 0; i < mesh.size(); ++i) {
    const Patch& p = mesh.patches[i];
    expected[i] = n * p.area * (p.surface == 0 ? 1 : 3) / total;
    EXPECT_NEAR(s.pdfArea(i), (p.surface == 0 ? 1 : 3) / total, 1e-12);
  }
  EXPECT_GT(test::chiSquarePValue(observed, expected, "chi2_emitters.csv", 0.01), 0.01);
  // Points are uniform on surface b: their mean is its centre within 4 standard errors
  // (a uniform coordinate on [0, 1] has standard deviation 1/√12).
  meanOnB = meanOnB / onB;
  double se = 1 / std::sqrt(12.0 * onB);
  EXPECT_NEAR(meanOnB.x, 0.5, 4 * se);
  EXPECT_NEAR(meanOnB.y, 0.5, 4 * se);
}

}  // namespace
}  // namespace radkit
