#include <gtest/gtest.h>

#include <set>

#include "analytic_systems.h"
#include "solvers/convergence.h"

namespace radkit {
using namespace radkit::test;

TEST(SolverParams, Construct) {
  SolverParams p = SolverParams::parse("omega=1.5,power_iterations=10");
  EXPECT_EQ(p.get("omega", 0.0), 1.5);
  EXPECT_EQ(p.get("missing", 7.0), 7.0);
  EXPECT_THROW(p.rejectUnused("sor"), std::invalid_argument);  // power_iterations unread
  EXPECT_EQ(p.get("power_iterations", 30), 10.0);
  EXPECT_NO_THROW(p.rejectUnused("sor"));
  EXPECT_THROW(SolverParams::parse("omega"), std::invalid_argument);
  EXPECT_THROW(SolverParams::parse("omega=fast"), std::invalid_argument);
  EXPECT_THROW(SolverParams::parse("omega=1.5x"), std::invalid_argument);
  EXPECT_NO_THROW(SolverParams::parse(""));
}

TEST(Solve, ExactMaxIterationsSaysNotConvergedAndWhy) {
  Problem p = randomReciprocal(40, 21);  // CG solves the 6-face box in 3 steps: too easy
  for (const std::string& name : solverNames()) {
    const SolveResult r = runSolver(name, p.system, 1e-12, ResidualNorm::Relative, 3);
    EXPECT_FALSE(r.converged) << name;
    EXPECT_EQ(r.iterations, 3) << name;
    EXPECT_EQ(r.history.size(), 4u) << name;  // iteration 0 and three steps
    EXPECT_NE(r.reason.find("not converged: maximum iterations (3)"), std::string::npos)
        << r.reason;
  }
}

TEST(Solve, ExactDivergenceIsReportedNotConverged) {
  // Two plates whose F rows sum to 1.5 (non-physical, as noisy form factors can be): ρF has
  // spectral radius 0.9 × 1.5 = 1.35 > 1, so iterating B ← E + ρFB diverges. Every solver
  // must stop and say so, never call a non-finite or exploding B converged.
  Problem p = makeProblem({0.0, 1.5, 1.5, 0.0}, {1.0, 1.0}, grey({0.9, 0.9}), grey({1.0, 0.0}));
  for (const char* name : {"jacobi", "gauss-seidel", "sor", "southwell"}) {
    const SolveResult r = runSolver(name, p.system, 1e-9, ResidualNorm::Relative, 100000);
    EXPECT_FALSE(r.converged) << name;
    EXPECT_EQ(r.reason.rfind("diverged", 0), 0u) << name << ": " << r.reason;
    EXPECT_LT(r.iterations, 1000) << name;  // caught by the residual's growth, not by overflow
  }
}

TEST(Solve, ExactTimeLimitSaysNotConverged) {
  Problem p = cubeOneEmitter(0.99);
  SolverSettings settings;
  settings.tolerance = 1e-12;
  settings.maxSeconds = 0.0;
  auto solver = makeSolver("jacobi");
  const SolveResult r = solve(*solver, p.system, settings);
  EXPECT_FALSE(r.converged);
  EXPECT_NE(r.reason.find("time limit"), std::string::npos) << r.reason;
}

TEST(Solve, ExactZeroEmissionIsExact) {
  Problem p = cubeOneEmitter(0.5);
  p.system.emission = makeChannels(6, 0.0);
  for (const std::string& name : solverNames()) {
    const SolveResult r = runSolver(name, p.system, 1e-9);
    EXPECT_TRUE(r.converged) << name;
    EXPECT_EQ(r.iterations, 0) << name;
    EXPECT_EQ(maxAbs(r.radiosity), 0.0) << name;
    EXPECT_NE(r.reason.find("B = 0 is exact"), std::string::npos) << r.reason;
  }
}

TEST(Solve, ExactHistoryIsMonotoneInTimeAndIteration) {
  const SolveResult r = runSolver("gauss-seidel", cubeOneEmitter(0.9).system, 1e-10);
  for (std::size_t k = 1; k < r.history.size(); ++k) {
    EXPECT_EQ(r.history[k].iteration, long(k));
    EXPECT_GE(r.history[k].seconds, r.history[k - 1].seconds);
  }
  EXPECT_EQ(r.history.back().residual, r.residual);
}

// report.json's exit_reason: one token per way a run can stop.
TEST(Solve, ExactExitReasons) {
  Problem p = randomReciprocal(40, 21);
  EXPECT_EQ(runSolver("jacobi", p.system, 1e-12, ResidualNorm::Relative, 3).exit, "max_iterations");
  EXPECT_EQ(runSolver("jacobi", p.system, 1e-6).exit, "converged");
  Problem bad = makeProblem({0.0, 1.5, 1.5, 0.0}, {1.0, 1.0}, grey({0.9, 0.9}), grey({1.0, 0.0}));
  EXPECT_EQ(runSolver("jacobi", bad.system, 1e-9).exit, "diverged");
}

// A tolerance below the rounding floor used to run to the iteration limit (10 million here);
// a residual with no new low for kStagnationSweeps sweeps now stops the run and says so.
TEST(Solve, ExactStagnationStopsAndSaysWhy) {
  Problem p = cubeOneEmitter(0.5);
  int stagnated = 0;
  for (const std::string& name : solverNames()) {
    const SolveResult r = runSolver(name, p.system, 1e-300);
    EXPECT_LT(r.iterations, 1000000) << name;
    if (r.converged) continue;  // some reach (near) the exact fixed point: nothing to stagnate
    EXPECT_EQ(r.exit, "stagnated") << name << ": " << r.reason;
    EXPECT_EQ(r.reason.rfind("stagnated: no residual below", 0), 0u) << r.reason;
    ++stagnated;
  }
  EXPECT_GT(stagnated, 0) << "no solver stagnated: the test shows nothing";
}

// The residual's reduction per sweep tends to ρ for Jacobi in a closed box of uniform ρ.
TEST(Solve, ExactSpectralRadiusEstimate) {
  const SolveResult r = runSolver("jacobi", cubeOneEmitter(0.9).system, 1e-12);
  ASSERT_GT(r.iterations, 2 * kRateWindowSweeps);
  EXPECT_NEAR(r.spectralRadius, 0.9, 1e-6);
}

// A long run keeps a bounded, logarithmically spaced history: every row up to 1000, then 900
// per decade of iterations, the first row of each residual decade, and the last row.
TEST(Solve, ExactHistoryIsDecimatedLogarithmically) {
  const SolveResult r = runSolver("jacobi", cubeOneEmitter(0.9999).system, 1e-9);
  ASSERT_TRUE(r.converged) << r.reason;
  ASSERT_GT(r.iterations, 100000);
  EXPECT_LT(r.history.size(), 1000u + 900u * 3 + 20u) << r.iterations << " iterations";
  for (std::size_t k = 0; k < 1000; ++k) EXPECT_EQ(r.history[k].iteration, long(k));
  for (std::size_t k = 1; k < r.history.size(); ++k)
    EXPECT_GT(r.history[k].iteration, r.history[k - 1].iteration);
  EXPECT_EQ(r.history.back().iteration, r.iterations);
  EXPECT_EQ(r.history.back().residual, r.residual);
  // Milestones at powers of ten stay exact: one iteration earlier the residual was above.
  const Milestone m = milestones(r, {1e-6})[0];
  ASSERT_TRUE(m.reached);
  ASSERT_GT(m.iterations, 1000);
  const SolveResult before = runSolver("jacobi", cubeOneEmitter(0.9999).system, 1e-9,
                                       ResidualNorm::Relative, m.iterations - 1);
  EXPECT_GT(before.residual, 1e-6);
}

// Point 9 of issue 20: a closed box at ρ = 0.999999 (ρF has spectral radius 0.999999) made
// Jacobi keep 7.2 M history rows and Southwell run past 90 M steps without a word. With the
// default iteration limit every solver now stops with an exit reason and a bounded history.
TEST(Solve, ExactNearSingularClosedBoxStopsWithAReason) {
  const Problem p = cubeOneEmitter(0.999999);
  const std::set<std::string> exits{"converged", "max_iterations", "stagnated", "time_limit"};
  for (const std::string& name : solverNames()) {
    SolverSettings settings;  // default tolerance and iteration limit
    auto solver = makeSolver(name);
    const SolveResult r = solve(*solver, p.system, settings);
    EXPECT_TRUE(exits.count(r.exit)) << name << ": '" << r.exit << "', " << r.reason;
    EXPECT_FALSE(r.reason.empty()) << name;
    EXPECT_LE(r.iterations, settings.maxIterations) << name;
    // 1000 rows, 900 per further decade of iterations (at most 6 up to 1e8), the residual's
    // decades and the last row.
    EXPECT_LT(r.history.size(), 1000u + 900u * 6 + 40u)
        << name << ": " << r.iterations << " iterations";
    if (r.iterations > 2 * kRateWindowSweeps && name == "jacobi") {
      EXPECT_NEAR(r.spectralRadius, 0.999999, 1e-6);
    }
  }
}

}  // namespace radkit
