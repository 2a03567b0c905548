// monte-carlo within 4 standard errors of the closed forms; error bars shrink as 1/sqrt(K).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "geometry/ray_scene.h"
#include "radiosity/form_factor_method.h"
#include "test_scenes.h"

namespace radkit {
namespace {
RowEntry estimate(const test::MeshBuilder& b, int i, int j, int K, std::uint64_t seed = 1) {
  RayScene scene(b.mesh());
  FormFactorSettings s;
  s.method = "monte-carlo";
  s.samples = K;
  s.seed = seed;
  auto method = makeFormFactorMethod(b.mesh(), scene, s);
  RowResult row;
  method->computeRow(std::min(i, j), row);
  for (const RowEntry& e : row.entries)
    if (e.column == std::max(i, j)) {
      if (i < j) return e;
      double ratio = b.mesh().patches[j].area / b.mesh().patches[i].area;
      return {j, e.value * ratio, e.standardError * ratio};
    }
  return {};
}
}  // namespace

TEST(MonteCarlo, Construct) {
  test::MeshBuilder b = test::parallelRectangles(1, 1, 1);
  RayScene scene(b.mesh());
  FormFactorSettings s;
  s.method = "monte-carlo";
  auto m = makeFormFactorMethod(b.mesh(), scene, s);
  EXPECT_EQ(m->coverage(), RowCoverage::UpperTriangle);
  EXPECT_NE(m->describe().find("K=16"), std::string::npos);
  s.samples = 0;
  EXPECT_THROW(makeFormFactorMethod(b.mesh(), scene, s), std::invalid_argument);
}

// C-11 at several aspect ratios and the cube's opposite faces. (C-14 is left out: at a shared
// edge cos cos/r² is not square-integrable, so the sample variance does not converge.)
TEST(MonteCarlo, StatisticalClosedForms) {
  struct Case {
    double a, b, c;
  };
  for (Case k : {Case{1, 1, 1}, Case{2, 2, 1}, Case{1, 1.5, 0.5}}) {
    test::MeshBuilder b = test::parallelRectangles(k.a, k.b, k.c);
    RowEntry e = estimate(b, 0, 1, 4096);
    double exact = test::c11ParallelRectangles(k.a / k.c, k.b / k.c);
    std::printf("[ monte-carlo ] C-11 %gx%g at %g  K=4096  F=%.6f  exact %.6f  se %.2e\n", k.a, k.b,
                k.c, e.value, exact, e.standardError);
    EXPECT_GT(e.standardError, 0);
    EXPECT_LE(std::fabs(e.value - exact), 4 * e.standardError);
  }
}

TEST(MonteCarlo, StatisticalStandardErrorHalves) {
  test::MeshBuilder b = test::parallelRectangles(1, 1, 1);
  RowEntry k1 = estimate(b, 0, 1, 2000), k4 = estimate(b, 0, 1, 8000);
  std::printf("[ monte-carlo ] se(K=2000) %.3e  se(K=8000) %.3e  ratio %.3f\n", k1.standardError,
              k4.standardError, k4.standardError / k1.standardError);
  EXPECT_NEAR(k4.standardError / k1.standardError, 0.5, 0.1);
}

}  // namespace radkit
