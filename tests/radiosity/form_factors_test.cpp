// The driver: storage choices, determinism, reciprocity enforcement, diagnostics, bad input.
#include <gtest/gtest.h>

#include <tbb/task_arena.h>

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "geometry/ray_scene.h"
#include "radiosity/form_factors.h"
#include "test_scenes.h"

namespace radkit {

namespace {
/// A floor of 10×10 patches under a 2×2 lamp: 104 patches, only 400 facing pairs.
test::MeshBuilder floorAndLamp() {
  test::MeshBuilder b;
  b.addRectangle("floor", {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 10, 10);
  b.addRectangle("lamp", {0.4, 0.4, 0.5}, {0, 0.2, 0}, {0.2, 0, 0}, 2, 2);
  b.addRectangle("blocker", {0.45, 0.45, 0.3}, {0, 0.1, 0}, {0.1, 0, 0});
  return b;
}
}  // namespace

TEST(FormFactors, ConstructStorage) {
  test::MeshBuilder b = floorAndLamp();  // 105 patches: dense double needs 88200 bytes
  const int n = b.mesh().size();
  RayScene scene(b.mesh());
  FormFactorSettings s;
  FormFactorResult dense = computeFormFactors(b.mesh(), scene, s);
  EXPECT_EQ(storageName(dense.matrix), "dense-double");
  EXPECT_EQ(dense.plan.bytes, 88200u);

  s.memoryBudget = 80000;  // too small for dense, enough for CSR of the facing pairs
  std::string logged;
  FormFactorResult sparse =
      computeFormFactors(b.mesh(), scene, s, [&](const std::string& m) { logged += m; });
  EXPECT_EQ(storageName(sparse.matrix), "csr-double");
  EXPECT_NE(logged.find("csr-double"), std::string::npos);
  s.precision = FormFactorPrecision::Float;
  s.memoryBudget = std::size_t(8) << 30;
  FormFactorResult single = computeFormFactors(b.mesh(), scene, s);
  EXPECT_EQ(storageName(single.matrix), "dense-float");
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      double f = formFactorAt(dense.matrix, i, j);
      EXPECT_EQ(formFactorAt(sparse.matrix, i, j), f);
      EXPECT_NEAR(formFactorAt(single.matrix, i, j), f, 1e-7 * f);
    }
  EXPECT_EQ(sparse.diagnostics.nonZeros, dense.diagnostics.nonZeros);
}

TEST(FormFactors, ConstructBadInput) {
  test::MeshBuilder b = test::cubeInterior(2);
  RayScene scene(b.mesh());
  FormFactorSettings s;
  s.samples = 0;
  try {
    computeFormFactors(b.mesh(), scene, s);
    ADD_FAILURE() << "K = 0 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("--ff-samples"), std::string::npos);
  }
  s.samples = 4;
  s.memoryBudget = 100;
  try {
    computeFormFactors(b.mesh(), scene, s);
    ADD_FAILURE() << "impossible budget accepted";
  } catch (const MemoryBudgetError& e) {
    std::string m = e.what();
    for (const char* option : {"--memory-budget", "--max-area", "--patches", "--ff-storage float"})
      EXPECT_NE(m.find(option), std::string::npos) << option << " missing from: " << m;
  }
}

TEST(FormFactors, ConstructOnePatch) {
  test::MeshBuilder b;
  b.addRectangle("lonely", {0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  RayScene scene(b.mesh());
  for (const std::string& method : formFactorMethodNames()) {
    FormFactorSettings s;
    s.method = method;
    FormFactorResult r = computeFormFactors(b.mesh(), scene, s);
    EXPECT_EQ(matrixSize(r.matrix), 1);
    EXPECT_EQ(formFactorAt(r.matrix, 0, 0), 0.0);
    EXPECT_EQ(r.diagnostics.rowSumMax, 0.0);
  }
}

// Coincident patches (same square, opposite orientation) and an overlapping coplanar one:
// reported, with finite F (0 between them: neither front sees the other).
TEST(FormFactors, ConstructCoincidentPatches) {
  test::MeshBuilder b;
  b.addRectangle("up", {0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  b.addRectangle("down", {0, 0, 0}, {0, 1, 0}, {1, 0, 0});
  b.addRectangle("shifted", {0.5, 0.5, 0}, {1, 0, 0}, {0, 1, 0});
  b.addRectangle("roof", {0, 0, 1}, {0, 1, 0}, {1, 0, 0});
  RayScene scene(b.mesh());
  for (const std::string& method : formFactorMethodNames()) {
    FormFactorSettings s;
    s.method = method;
    FormFactorResult r = computeFormFactors(b.mesh(), scene, s);
    forEachNonZero(r.matrix, [&](int, int, double f) { EXPECT_TRUE(std::isfinite(f)); });
    if (method != "hemisphere") {  // hemisphere sees only what its rays hit
      EXPECT_EQ(r.diagnostics.overlappingPairs, 3) << method;
      EXPECT_FALSE(r.diagnostics.warnings.empty());
    }
    EXPECT_EQ(formFactorAt(r.matrix, 0, 1), 0.0);
  }
}

// Same seed, same F, whatever the number of threads; another seed changes sampled entries.
TEST(FormFactors, ExactDeterministic) {
  test::MeshBuilder b = test::cubeInterior(2);
  b.addRectangle("blocker", {0.3, 0.3, 0.5}, {0.4, 0, 0}, {0, 0.4, 0});
  RayScene scene(b.mesh());
  for (const std::string& method : formFactorMethodNames()) {
    FormFactorSettings s;
    s.method = method;
    FormFactorResult parallel = computeFormFactors(b.mesh(), scene, s);
    tbb::task_arena one(1);
    FormFactorResult serial = one.execute([&] { return computeFormFactors(b.mesh(), scene, s); });
    s.seed = 99;
    FormFactorResult other = computeFormFactors(b.mesh(), scene, s);
    int differ = 0;
    for (int i = 0; i < b.mesh().size(); ++i)
      for (int j = 0; j < b.mesh().size(); ++j) {
        EXPECT_EQ(formFactorAt(parallel.matrix, i, j), formFactorAt(serial.matrix, i, j));
        differ += formFactorAt(parallel.matrix, i, j) != formFactorAt(other.matrix, i, j);
      }
    EXPECT_GT(differ, 0) << method;
  }
}

// Reciprocity: exact by construction for the pairwise methods; for hemisphere only when
// asked (--ff-enforce reciprocity), and never silently.
TEST(FormFactors, ExactReciprocity) {
  test::MeshBuilder b = test::cubeInterior(2);
  RayScene scene(b.mesh());
  FormFactorSettings s;
  s.method = "hemisphere";
  s.samples = 256;
  FormFactorResult raw = computeFormFactors(b.mesh(), scene, s);
  EXPECT_GT(raw.diagnostics.maxRelativeReciprocityError, 1e-3);
  EXPECT_FALSE(raw.diagnostics.reciprocityEnforced);
  s.enforceReciprocity = true;
  FormFactorResult fixed = computeFormFactors(b.mesh(), scene, s);
  EXPECT_LT(fixed.diagnostics.maxRelativeReciprocityError, 1e-12);
  EXPECT_EQ(fixed.diagnostics.maxRelativeReciprocityErrorBeforeEnforcement,
            raw.diagnostics.maxRelativeReciprocityError);
  // The CSR path symmetrizes while assembling: same F as the dense path.
  test::MeshBuilder open = floorAndLamp();
  RayScene openScene(open.mesh());
  FormFactorResult denseFixed = computeFormFactors(open.mesh(), openScene, s);
  s.memoryBudget = 80000;
  FormFactorResult sparse = computeFormFactors(open.mesh(), openScene, s);
  EXPECT_EQ(storageName(sparse.matrix), "csr-double");
  for (int i = 0; i < open.mesh().size(); ++i)
    for (int j = 0; j < open.mesh().size(); ++j)
      EXPECT_NEAR(formFactorAt(sparse.matrix, i, j), formFactorAt(denseFixed.matrix, i, j), 1e-15);
  // Closure survives enforcement in a closed cube only approximately; the row sums say so.
  EXPECT_NEAR(raw.diagnostics.rowSumMin, 1.0, 1e-12);
  EXPECT_GT(fixed.diagnostics.maxDeviationFromOne, 0.0);
}

TEST(FormFactors, ConstructDiagnosticsJson) {
  test::MeshBuilder b = test::cubeInterior(2);
  b.addRectangle("blocker", {0.3, 0.3, 0.5}, {0.4, 0, 0}, {0, 0.4, 0});
  RayScene scene(b.mesh());
  FormFactorResult r = computeFormFactors(b.mesh(), scene, FormFactorSettings{});
  nlohmann::json j = toJson(r.diagnostics);
  EXPECT_EQ(j["method"], "point-polygon");
  EXPECT_GT(j["rays"]["cast"].get<long long>(), 0);
  EXPECT_GT(j["rays"]["saved"].get<long long>(), 0);
  EXPECT_GT(j["rays"]["per_second"].get<double>(), 0);
  EXPECT_TRUE(j["seconds"].contains("compute"));
  EXPECT_TRUE(j["reciprocity"]["by_construction"].get<bool>());
}

// Row sums of a closed box with a blocker: the visible fractions are estimates, so a row may
// exceed 1 by their noise; the excess must shrink as K grows (it is reported, not clipped).
TEST(FormFactors, StatisticalRowSums) {
  test::MeshBuilder b = test::cubeInterior(2);
  b.addRectangle("blocker", {0.3, 0.3, 0.5}, {0.4, 0, 0}, {0, 0.4, 0});
  RayScene scene(b.mesh());
  double previous = 1;
  for (int K : {16, 256, 1024}) {
    FormFactorSettings s;
    s.samples = K;
    FormFactorResult r = computeFormFactors(b.mesh(), scene, s);
    double excess = std::max(0.0, r.diagnostics.rowSumMax - 1);
    std::printf("[ row sums ] cube + blocker  K=%4d  max %.6f  min %.6f\n", K,
                r.diagnostics.rowSumMax, r.diagnostics.rowSumMin);
    EXPECT_LT(excess, previous);
    previous = excess;
  }
  EXPECT_LT(previous, 2e-3);
}

}  // namespace radkit
