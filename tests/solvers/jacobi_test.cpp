#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <cstring>

#include "analytic_systems.h"

namespace radkit {
using namespace radkit::test;

TEST(JacobiSolver, Construct) {
  auto solver = makeSolver("jacobi");
  EXPECT_EQ(solver->name(), "jacobi");
  EXPECT_FALSE(solver->describe().empty());
  Problem p = tenPatchSphere();
  p.system.reflectance[1][3] = 1.0;  // invalid: start() validates
  EXPECT_THROW(solver->start(p.system, SolverSettings{}), std::invalid_argument);
}

TEST(JacobiSolver, ExactParallelPlates) {
  Problem p = makeProblem(platesFormFactors(), {1.0, 1.0}, grey({0.5, 0.5}), grey({1.0, 0.0}));
  const SolveResult r = runSolver("jacobi", p.system, 1e-14);
  ASSERT_TRUE(r.converged) << r.reason;
  EXPECT_NEAR(r.radiosity[0][0], 4.0 / 3.0, 1e-13);
  EXPECT_NEAR(r.radiosity[2][1], 2.0 / 3.0, 1e-13);
}

// Sphere interior: ρF has rank one, so from B = E the residual shrinks by exactly ρ per sweep.
// r = G − B is a difference of numbers near ‖B‖∞ = 1.23, so each residual carries an absolute
// rounding error of a few ulp(‖B‖∞); the ratio is checked to that accuracy.
TEST(JacobiSolver, ExactSphereResidualRatioIsRho) {
  Problem p = tenPatchSphere();
  const SolveResult r = runSolver("jacobi", p.system, 1e-13);
  ASSERT_TRUE(r.converged) << r.reason;
  EXPECT_NEAR(r.radiosity[0][0], 1.2333333333333333, 1e-12);
  for (int i = 1; i < 10; ++i) EXPECT_NEAR(r.radiosity[1][i], 0.2333333333333333, 1e-12);
  ASSERT_GT(r.history.size(), 30u);
  for (std::size_t k = 1; k < r.history.size(); ++k) {
    const double rounding = 8 * DBL_EPSILON * 1.24 / r.history[k - 1].residual;
    EXPECT_NEAR(r.history[k].residual / r.history[k - 1].residual, 0.7, 1e-14 + rounding)
        << "sweep " << k;
  }
}

TEST(JacobiSolver, ExactZeroReflectanceIsEmission) {
  Problem p = makeProblem(cubeFormFactors(), std::vector<double>(6, 1.0),
                          grey(std::vector<double>(6, 0.0)), grey({1, 2, 3, 0, 0, 5}));
  const SolveResult r = runSolver("jacobi", p.system, 1e-12);
  EXPECT_TRUE(r.converged);
  EXPECT_LE(r.iterations, 1);
  EXPECT_EQ(r.radiosity, p.system.emission);
}

TEST(JacobiSolver, ExactEnergyBalance) {
  Problem p = cubeOneEmitter(0.8);
  const SolveResult r = runSolver("jacobi", p.system, 1e-13);
  double power = 0.0;
  for (int i = 0; i < 6; ++i) power += r.radiosity[0][i];
  EXPECT_NEAR(power, 1.0 / (1.0 - 0.8), 1e-10);
}

// Iterations to 1e-6 grow like log(tol/r_0)/log(ρ) ≈ ln(r_0/tol)/(1 − ρ), r_0 the residual of
// B = E (the error ratio tends to exactly ρ in a closed box with uniform ρ). The ratio of counts
// for 0.999 and 0.99 is then ln(0.99)/ln(0.999) = 10.045; 0.9999 vs 0.999: 10.0045. The 5% band
// allows for the transient before the ratio settles at ρ.
TEST(JacobiSolver, ExactIterationsGrowLikeInverseOneMinusRho) {
  const double tol = 1e-6;
  long counts[3];
  const double rhos[3] = {0.99, 0.999, 0.9999};
  for (int k = 0; k < 3; ++k) {
    Problem p = cubeOneEmitter(rhos[k]);
    const SolveResult r = runSolver("jacobi", p.system, tol);
    ASSERT_TRUE(r.converged) << r.reason;
    counts[k] = r.iterations;
    const double predicted = std::log(tol / r.history[0].residual) / std::log(rhos[k]);
    EXPECT_NEAR(r.iterations / predicted, 1.0, 0.05) << "rho " << rhos[k];
  }
  for (int k = 0; k < 2; ++k) {
    const double predicted = std::log(rhos[k]) / std::log(rhos[k + 1]);
    EXPECT_NEAR(double(counts[k + 1]) / counts[k] / predicted, 1.0, 0.05)
        << counts[k] << " -> " << counts[k + 1];
  }
}

TEST(JacobiSolver, ExactSameInputsSameBits) {
  Problem p = randomReciprocal(400, 7);  // 160000 entries: rows run in parallel
  const SolveResult a = runSolver("jacobi", p.system, 1e-12);
  const SolveResult b = runSolver("jacobi", p.system, 1e-12);
  for (int c = 0; c < 3; ++c)
    EXPECT_EQ(0, std::memcmp(a.radiosity[c].data(), b.radiosity[c].data(), 400 * sizeof(double)));
}

}  // namespace radkit
