// The study's measuring tools: patch mapping (oracle: refinePatches' parent of each child),
// error measures on constructed solutions, the Pareto front against its definition, the
// power-law fit, and a small end-to-end study whose budget rules are checked.
#include <gtest/gtest.h>

#include <cmath>

#include "experiments/study.h"
#include "geometry/refine.h"
#include "geometry/scene_loader.h"
#include "tests/common/test_util.h"

namespace radkit {

namespace {
StudySolution solutionOf(const PipelineResult& r) { return {r.mesh, r.radiosity, r.surfaces}; }
}  // namespace

// Every child of a refined mesh maps onto the patch it was split from.
TEST(Study, ExactMapPatchesFindsParents) {
  Scene scene = loadScene(test::dataPath("cornell-box.json"));
  PatchMesh coarse = subdivide(scene, {0, 300});
  RefinedMesh fine = refinePatches(coarse, std::vector<char>(coarse.patches.size(), 1));
  RayScene rays(coarse);
  std::vector<int> map = mapPatches(fine.mesh, coarse, rays);
  for (int k = 0; k < fine.mesh.size(); ++k) EXPECT_EQ(map[k], fine.parent[k]) << "child " << k;
}

// A solution scaled by (1 + ε) is off by exactly ε in every measure; a refined copy carrying its
// parent's values is exact in surface and patch means.
TEST(Study, ExactErrorMeasures) {
  Scene scene = loadScene(test::dataPath("cube-one-emitter.json"));
  PipelineSettings s;
  s.mesh.targetPatches = 54;
  StudySolution ref = solutionOf(runPipeline(scene, s));
  StudySolution scaled = ref;
  for (Vec3& b : scaled.radiosity) b *= 1.01;
  for (SurfaceResult& sr : scaled.surfaces) sr.radiosity *= 1.01;
  StudyRow row;
  measureErrors(scaled, ref, row);
  EXPECT_NEAR(row.surfaceError, 0.01, 1e-12);
  EXPECT_NEAR(row.patchError, 0.01, 1e-12);
  EXPECT_NEAR(row.fieldError, 0.01, 1e-12);

  RefinedMesh fine = refinePatches(ref.mesh, std::vector<char>(ref.mesh.patches.size(), 1));
  StudySolution child{fine.mesh, {}, ref.surfaces};
  for (int p : fine.parent) child.radiosity.push_back(ref.radiosity[p]);
  measureErrors(ref, child, row);  // the coarse solution against its piecewise-constant refinement
  EXPECT_NEAR(row.surfaceError, 0.0, 1e-15);
  EXPECT_NEAR(row.patchError, 0.0, 1e-12);
  EXPECT_NEAR(row.fieldError, 0.0, 1e-12);
}

// The front against a brute-force reading of "no other point is at least as good in both".
TEST(Study, ExactParetoFront) {
  std::vector<double> cost{1, 2, 3, 4, 2, 5, 1.5};
  std::vector<double> err{0.5, 0.3, 0.31, 0.1, 0.3, 0.1, NAN};
  std::vector<bool> front = paretoFront(cost, err);
  EXPECT_EQ(front, (std::vector<bool>{true, true, false, true, true, false, false}));
}

TEST(Study, ExactFitExponent) {
  std::vector<double> x{1000, 2000, 4000, 8000}, y;
  for (double v : x) y.push_back(3e-7 * std::pow(v, 1.83));
  EXPECT_NEAR(fitExponent(x, y), 1.83, 1e-12);
  EXPECT_TRUE(std::isnan(fitExponent({1}, {2})));
}

// A small study of the closed cube: every run row is measured, the reference is twice the
// finest rung, the mesh errors fall, and a budget of nothing still yields the reference.
TEST(Study, ConstructSmallStudy) {
  Scene scene = loadScene(test::dataPath("cube-one-emitter.json"));
  StudySettings st;
  st.maxSeconds = 120;
  st.meshLadder = {24, 54, 96, 216};
  st.knobPatches = 54;
  st.formFactorSamples = {{"point-polygon", {4, 16}}, {"hemisphere", {4096}}};
  st.solvers = {"jacobi", "cg"};
  st.tolerances = {1e-2, 1e-6};
  st.adaptiveBudgets = {100};
  st.adaptiveStartPatches = 24;
  StudyResult r = runStudy(scene, st);
  int mesh = 0, solver = 0;
  double previous = INFINITY;
  for (const StudyRow& w : r.rows) {
    ASSERT_TRUE(w.ran) << w.config.label() << ": " << w.note;
    EXPECT_TRUE(std::isfinite(w.patchError)) << w.config.label();
    solver += w.config.knob == StudyKnob::Solver;
    if (w.config.knob == StudyKnob::Mesh) {
      ++mesh;
      EXPECT_LT(w.patchError, previous) << w.config.label();
      previous = w.patchError;
    }
  }
  EXPECT_EQ(mesh, 4);
  EXPECT_EQ(solver, 4);
  EXPECT_NEAR(r.reference.row.patches, 432, 432 * 0.15);
  EXPECT_GT(r.reference.patchErrorEstimate, 0);

  st.maxSeconds = 1e-9;
  StudyResult none = runStudy(scene, st);
  for (const StudyRow& w : none.rows) EXPECT_FALSE(w.ran) << w.config.label();
  EXPECT_GT(none.reference.row.patches, 0);
}

}  // namespace radkit
