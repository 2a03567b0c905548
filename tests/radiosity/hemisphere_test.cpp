// hemisphere (ray-traced hemicube) within 4 binomial standard errors of the closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "geometry/ray_scene.h"
#include "radiosity/form_factor_method.h"
#include "test_scenes.h"

namespace radkit {
namespace {
RowEntry estimate(const test::MeshBuilder& b, int i, int j, int K) {
  RayScene scene(b.mesh());
  FormFactorSettings s;
  s.method = "hemisphere";
  s.samples = K;
  auto method = makeFormFactorMethod(b.mesh(), scene, s);
  RowResult row;
  method->computeRow(i, row);
  for (const RowEntry& e : row.entries)
    if (e.column == j) return e;
  return {j, 0, 0};
}
}  // namespace

TEST(Hemisphere, Construct) {
  test::MeshBuilder b = test::cubeInterior(1);
  RayScene scene(b.mesh());
  FormFactorSettings s;
  s.method = "hemisphere";
  auto m = makeFormFactorMethod(b.mesh(), scene, s);
  EXPECT_EQ(m->coverage(), RowCoverage::FullRow);
  RowResult row;
  m->computeRow(0, row);  // closed cube: every ray hits a face
  double sum = 0;
  for (const RowEntry& e : row.entries) sum += e.value;
  EXPECT_DOUBLE_EQ(sum, 1.0);
}

TEST(Hemisphere, StatisticalClosedForms) {
  const int K = 20000;
  struct Case {
    const char* name;
    test::MeshBuilder b;
    int i, j;
    double exact;
  };
  Case cases[] = {
      {"C-11 1x1 at 1", test::parallelRectangles(1, 1, 1), 0, 1, test::c11ParallelRectangles(1, 1)},
      {"C-11 1x1.5 at 0.5", test::parallelRectangles(1, 1.5, 0.5), 0, 1,
       test::c11ParallelRectangles(2, 3)},
      {"C-14 W=1 H=2", test::perpendicularRectangles(1, 1, 2), 0, 1,
       test::c14PerpendicularRectangles(1, 2)},
      {"cube adjacent", test::cubeInterior(1), 0, 2, 0.200043776075403},
      {"cube opposite", test::cubeInterior(1), 0, 1, 0.199824895698387},
  };
  for (const Case& c : cases) {
    RowEntry e = estimate(c.b, c.i, c.j, K);
    std::printf("[ hemisphere ] %-18s K=%d  F=%.5f  exact %.5f  se %.2e\n", c.name, K, e.value,
                c.exact, e.standardError);
    EXPECT_LE(std::fabs(e.value - c.exact), 4 * e.standardError) << c.name;
  }
}

TEST(Hemisphere, StatisticalStandardErrorHalves) {
  test::MeshBuilder b = test::parallelRectangles(1, 1, 1);
  RowEntry k1 = estimate(b, 0, 1, 5000), k4 = estimate(b, 0, 1, 20000);
  EXPECT_NEAR(k4.standardError / k1.standardError, 0.5, 0.05);
}

}  // namespace radkit
