// hemisphere (ray-traced hemicube) within 4 binomial standard errors of the closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "geometry/ray_scene.h"
#include "geometry/scene_loader.h"
#include "radiosity/form_factor_method.h"
#include "radiosity/form_factor_storage.h"
#include "radiosity/radiosity_pipeline.h"
#include "test_scenes.h"
#include "tests/common/test_util.h"

namespace radkit {
namespace {
RowEntry hemisphereEstimate(const test::MeshBuilder& b, int i, int j, int K) {
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
    RowEntry e = hemisphereEstimate(c.b, c.i, c.j, K);
    std::printf("[ hemisphere ] %-18s K=%d  F=%.5f  exact %.5f  se %.2e\n", c.name, K, e.value,
                c.exact, e.standardError);
    EXPECT_LE(std::fabs(e.value - c.exact), 4 * e.standardError) << c.name;
  }
}

TEST(Hemisphere, StatisticalStandardErrorHalves) {
  test::MeshBuilder b = test::parallelRectangles(1, 1, 1);
  RowEntry k1 = hemisphereEstimate(b, 0, 1, 5000), k4 = hemisphereEstimate(b, 0, 1, 20000);
  EXPECT_NEAR(k4.standardError / k1.standardError, 0.5, 0.05);
}

}  // namespace radkit

namespace radkit {
// gatheredLightNoise's predicted variance of H_i = Σ_j F_ij B_j against the spread of H_i over
// independent seeds, B held fixed so only the rows' sampling varies. The ratio of the summed
// observed variances to the summed predictions is 1 within 4 of its standard errors, estimated
// from each patch's fourth moment over the seeds (rows draw from independent streams).
TEST(Hemisphere, StatisticalGatheredLightNoiseMatchesSeedSpread) {
  const Scene scene = loadScene(test::dataPath("cornell-box.json"));
  PipelineSettings ps;
  ps.mesh.targetPatches = 120;
  ps.formFactors.method = "hemisphere";
  ps.formFactors.samples = 256;
  ps.solvers = {{"gauss-seidel", ""}};
  const PipelineResult base = runPipeline(scene, ps);  // B used for every seed
  const std::vector<Vec3> b = base.radiosity;
  ps.solvers.clear();
  const int seeds = 24;
  const std::size_t n = base.mesh.size();
  std::vector<std::vector<double>> h(n);
  std::vector<double> predicted(n, 0.0);
  for (int s = 1; s <= seeds; ++s) {
    ps.formFactors.seed = 100 + s;
    const PipelineResult r = runPipeline(scene, base.mesh, ps);
    std::vector<double> var;
    gatheredLightNoise(r.formFactors->matrix, r.mesh, b, ps.formFactors.samples, &var);
    std::vector<double> hi(n, 0.0);
    forEachNonZero(r.formFactors->matrix,
                   [&](int i, int j, double f) { hi[i] += f * (b[j].x + b[j].y + b[j].z); });
    for (std::size_t i = 0; i < n; ++i) h[i].push_back(hi[i]), predicted[i] += var[i] / seeds;
  }
  double observed = 0, expected = 0, varObserved = 0;
  for (std::size_t i = 0; i < n; ++i) {
    double mean = 0;
    for (double x : h[i]) mean += x / seeds;
    double m2 = 0, m4 = 0;
    for (double x : h[i])
      m2 += (x - mean) * (x - mean) / seeds, m4 += std::pow(x - mean, 4) / seeds;
    const double s2 = m2 * seeds / (seeds - 1);
    observed += s2;
    expected += predicted[i];
    // Var of the sample variance: (μ4 − σ⁴(S − 3)/(S − 1))/S.
    varObserved += std::max(0.0, m4 - m2 * m2 * (seeds - 3.0) / (seeds - 1.0)) / seeds;
  }
  const double ratio = observed / expected, se = std::sqrt(varObserved) / expected;
  std::printf("[ hemisphere ] observed/predicted variance of gathered light %.3f (se %.3f)\n",
              ratio, se);
  EXPECT_LE(std::fabs(ratio - 1), 4 * se);
  EXPECT_LT(se, 0.1);  // the check has power
}
}  // namespace radkit
