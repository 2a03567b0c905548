#include <gtest/gtest.h>

#include <cmath>

#include "analytic_systems.h"

namespace radkit {
using namespace radkit::test;

TEST(SorSolver, Construct) {
  EXPECT_EQ(makeSolver("sor")->name(), "sor");
  EXPECT_NO_THROW(makeSolver("sor", Params({{"omega", 1.1}})));
  EXPECT_THROW(makeSolver("sor", Params({{"omega", 2.0}})), std::invalid_argument);
  EXPECT_THROW(makeSolver("sor", Params({{"omega", -1.0}})), std::invalid_argument);
  EXPECT_THROW(makeSolver("sor", Params({{"omgea", 1.1}})), std::invalid_argument);
}

TEST(SorSolver, ExactParallelPlatesGivenOmega) {
  Problem p = makeProblem(platesFormFactors(), {1.0, 1.0}, grey({0.5, 0.5}), grey({1.0, 0.0}));
  const SolveResult r =
      runSolver("sor", p.system, 1e-14, ResidualNorm::Relative, 10000, Params({{"omega", 1.1}}));
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

// The sweep takes the residual's left-of-diagonal sum from the previous sweep; at every step the
// reported residual must still be that of the reported radiosity, recomputed here in long double
// from F's entries. 300 patches: three row blocks and parallel off-block sums; ω = 1.4 so the
// carried sum is of relaxed values; dense and CSR take different row kernels.
TEST(SorSolver, ExactResidualAtEveryStep) {
  for (Storage s : {Storage::DenseDouble, Storage::CsrFloat}) {
    Problem p = randomReciprocal(300, 5, s);
    const int n = p.system.size();
    auto solver = makeSolver("sor", Params({{"omega", 1.4}}));
    SolverSettings settings;
    settings.norm = ResidualNorm::Relative;
    solver->start(p.system, settings);
    for (int step = 0; step < 12; ++step) {
      const Channels& b = solver->radiosity();
      long double worst = 0;
      for (int c = 0; c < 3; ++c)
        for (int i = 0; i < n; ++i) {
          long double fb = 0;
          for (int j = 0; j < n; ++j)
            fb += std::visit([&](const auto& m) { return (long double)m(i, j); }, *p.f) * b[c][j];
          const long double r = p.system.emission[c][i] + p.system.reflectance[c][i] * fb - b[c][i];
          worst = std::max(worst, std::fabs(r));
        }
      const double expected = double(worst) / p.system.emissionNorm();
      EXPECT_NEAR(solver->residual(), expected, 1e-13 * std::max(1.0, expected))
          << storageLabel(s) << " step " << step;
      solver->step();
    }
  }
}

}  // namespace radkit
