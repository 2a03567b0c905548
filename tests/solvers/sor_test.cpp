#include <gtest/gtest.h>

#include <cmath>

#include "analytic_systems.h"

namespace radkit {
using namespace radkit::test;

TEST(SorSolver, Construct) {
  EXPECT_EQ(makeSolver("sor")->name(), "sor");
  EXPECT_NO_THROW(makeSolver("sor", SolverParams({{"omega", 1.1}})));
  EXPECT_THROW(makeSolver("sor", SolverParams({{"omega", 2.0}})), std::invalid_argument);
  EXPECT_THROW(makeSolver("sor", SolverParams({{"omega", -1.0}})), std::invalid_argument);
  EXPECT_THROW(makeSolver("sor", SolverParams({{"omgea", 1.1}})), std::invalid_argument);
}

TEST(SorSolver, ExactParallelPlatesGivenOmega) {
  Problem p = makeProblem(platesFormFactors(), {1.0, 1.0}, grey({0.5, 0.5}), grey({1.0, 0.0}));
  const SolveResult r = runSolver("sor", p.system, 1e-14, ResidualNorm::Relative, 10000,
                                  SolverParams({{"omega", 1.1}}));
  ASSERT_TRUE(r.converged) << r.reason;
  EXPECT_NEAR(r.radiosity[0][0], 4.0 / 3.0, 1e-13);
  EXPECT_NE(r.description.find("1.1"), std::string::npos);
}

// Closed box with uniform ρ: the spectral radius of ρF is exactly ρ, so the estimate gives
// Young's ω = 2 / (1 + sqrt(1 − ρ²)).
TEST(SorSolver, ExactEstimatedOmegaOnClosedBox) {
  const double rho = 0.9;
  Problem p = cubeOneEmitter(rho);
  auto solver = makeSolver("sor");
  solver->start(p.system, SolverSettings{});
  const double expected = 2.0 / (1.0 + std::sqrt(1.0 - rho * rho));
  EXPECT_NE(solver->describe().find(std::to_string(expected).substr(0, 5)), std::string::npos)
      << solver->describe() << " expected omega " << expected;
  const SolveResult r = runSolver("sor", p.system, 1e-12);
  ASSERT_TRUE(r.converged) << r.reason;
  EXPECT_LT(relativeError(r.radiosity, directSolve(p.system)), 1e-10);
}

TEST(SorSolver, ExactHighReflectanceConverges) {
  for (double rho : {0.999, 0.9999}) {
    Problem p = cubeOneEmitter(rho);
    const SolveResult r = runSolver("sor", p.system, 1e-9);
    ASSERT_TRUE(r.converged) << r.reason;
    EXPECT_LT(relativeError(r.radiosity, directSolve(p.system)), 1e-9 / (1 - rho));
  }
}

}  // namespace radkit
