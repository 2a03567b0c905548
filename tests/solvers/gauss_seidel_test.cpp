#include <gtest/gtest.h>

#include <cstring>

#include "analytic_systems.h"

namespace radkit {
using namespace radkit::test;

TEST(GaussSeidelSolver, Construct) {
  EXPECT_EQ(makeSolver("gauss-seidel")->name(), "gauss-seidel");
  EXPECT_THROW(makeSolver("gauss-seidel", Params({{"omega", 1.2}})), std::invalid_argument);
}

TEST(GaussSeidelSolver, ExactParallelPlates) {
  Problem p = makeProblem(platesFormFactors(), {1.0, 1.0}, grey({0.5, 0.5}), grey({1.0, 0.0}));
  const SolveResult r = runSolver("gauss-seidel", p.system, 1e-14);
  ASSERT_TRUE(r.converged) << r.reason;
  EXPECT_NEAR(r.radiosity[0][0], 4.0 / 3.0, 1e-13);
  EXPECT_NEAR(r.radiosity[1][1], 2.0 / 3.0, 1e-13);
}

TEST(GaussSeidelSolver, ExactSphere) {
  const SolveResult r = runSolver("gauss-seidel", tenPatchSphere().system, 1e-13);
  EXPECT_NEAR(r.radiosity[0][0], 1.2333333333333333, 1e-12);
  EXPECT_NEAR(r.radiosity[2][9], 0.2333333333333333, 1e-12);
}

// The residual reported is exact: it matches the driver's independent recomputation.
TEST(GaussSeidelSolver, ExactResidualIsTrueResidual) {
  Problem p = randomReciprocal(300, 3);  // three row blocks, parallel off-block sums
  const SolveResult r = runSolver("gauss-seidel", p.system, 1e-8);
  EXPECT_NEAR(r.residual, r.checkedResidual, 1e-14);
  EXPECT_LT(relativeError(r.radiosity, directSolve(p.system)), 1e-7);
}

TEST(GaussSeidelSolver, ExactFewerSweepsThanJacobi) {
  for (double rho : {0.5, 0.9, 0.99}) {
    Problem p = cubeOneEmitter(rho);
    const SolveResult gs = runSolver("gauss-seidel", p.system, 1e-9);
    const SolveResult jacobi = runSolver("jacobi", p.system, 1e-9);
    EXPECT_LT(gs.iterations, jacobi.iterations) << "rho " << rho;
  }
}

TEST(GaussSeidelSolver, ExactSameInputsSameBits) {
  Problem p = randomReciprocal(400, 11);
  const SolveResult a = runSolver("gauss-seidel", p.system, 1e-12);
  const SolveResult b = runSolver("gauss-seidel", p.system, 1e-12);
  for (int c = 0; c < 3; ++c)
    EXPECT_EQ(0, std::memcmp(a.radiosity[c].data(), b.radiosity[c].data(), 400 * sizeof(double)));
}

}  // namespace radkit
