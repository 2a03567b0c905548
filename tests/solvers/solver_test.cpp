#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>

#include "analytic_systems.h"
#include "solvers/convergence.h"

namespace radkit {
using namespace radkit::test;

TEST(SolverRegistry, ParameterErrorsNameTheSolverAndTheKeys) {
  try {
    makeSolver("sor", Params::parse("omega=1.5, power_iteration=10"));
    ADD_FAILURE();
  } catch (const ParamError& e) {
    EXPECT_NE(std::string(e.what()).find("solver \"sor\": gives \"power_iteration\""),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("sor reads omega, power_iterations"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(makeSolver("sor", Params::parse("power_iterations=2.5")), ParamError);
  EXPECT_THROW(makeSolver("cg", Params::parse("replace_every=-1")), ParamError);
  EXPECT_THROW(makeSolver("sor", Params::parse("omega=fast")), ParamError);
  // Every entry builds from its example, and the registry lists what the help shows.
  for (const auto& entry : solverRegistry().entries())
    EXPECT_NO_THROW(makeSolver(entry.name, Params::parse(entry.example))) << entry.name;
  EXPECT_EQ(solverNames(), solverRegistry().names());
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

namespace {

/// Jacobi that updates B only every `period`-th step, reporting `sweepsPerStep` per step (0: a
/// solver whose sweeps() never advances); period 0 never updates B at all.
class LazyJacobi final : public Solver {
 public:
  LazyJacobi(int period, double sweepsPerStep) : m_period(period), m_sweepsPerStep(sweepsPerStep) {}
  std::string name() const override { return "lazy"; }
  std::string describe() const override { return "Jacobi updating B every few steps"; }
  void start(const RadiositySystem& system, const SolverSettings& settings) override {
    m_system = &system, m_norm = settings.norm, m_steps = 0;
    m_b = system.emission;
    measure();
  }
  void step() override {
    ++m_steps;
    if (m_period == 0 || m_steps % m_period != 0) return;
    Channels fb;
    multiply(m_system->matrix(), m_b, fb);
    for (int c = 0; c < 3; ++c)
      for (int i = 0; i < m_system->size(); ++i)
        m_b[c][i] = m_system->emission[c][i] + m_system->reflectance[c][i] * fb[c][i];
    measure();
  }
  const Channels& radiosity() const override { return m_b; }
  double residual() const override { return m_residual; }
  double unshotPower() const override { return 0.0; }
  double sweeps() const override { return m_sweepsPerStep * double(m_steps); }

 private:
  void measure() {
    m_residual = residualMeasure(*m_system, residualVector(*m_system, m_b), m_b, m_norm);
  }
  int m_period;
  double m_sweepsPerStep;
  const RadiositySystem* m_system = nullptr;
  ResidualNorm m_norm = ResidualNorm::Relative;
  Channels m_b;
  double m_residual = 0.0;
  long m_steps = 0;
};

}  // namespace

// A step that leaves B and the residual as they were (a Python step() that never updates B)
// used to repeat to the iteration limit: above the rounding floor nothing stopped it. It now
// stops as stagnated once a whole sweep (or n steps) changed nothing.
TEST(Solve, StepsThatChangeNothingStopAsStagnated) {
  const Problem p = cubeOneEmitter(0.5);
  SolverSettings settings;
  settings.tolerance = 1e-9;
  settings.maxIterations = 1000000;
  LazyJacobi idle(0, 1.0);
  SolveResult r = solve(idle, p.system, settings);
  EXPECT_EQ(r.exit, "stagnated") << r.reason;
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.iterations, 2);
  EXPECT_EQ(
      r.reason.rfind(
          "stagnated: B, the residual 0.1 and the unshot power have not changed since iteration 1",
          0),
      0u)
      << r.reason;
  // sweeps() that never advances: n = 6 unchanged steps are enough.
  LazyJacobi stuck(0, 0.0);
  r = solve(stuck, p.system, settings);
  EXPECT_EQ(r.exit, "stagnated") << r.reason;
  EXPECT_EQ(r.iterations, 1 + 6);
  // A solver that idles for part of a sweep between updates is left to converge.
  for (const auto& [period, sweepsPerStep] : {std::pair<int, double>{2, 0.5}, {4, 0.25}}) {
    LazyJacobi slow(period, sweepsPerStep);
    r = solve(slow, p.system, settings);
    EXPECT_TRUE(r.converged) << period << ": " << r.reason;
  }
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

// Two infinite parallel plates (F12 = F21 = 1, docs/oracles.md), plate 1 emitting 1, both at
// reflectance rho: every method's rate is known in closed form. Jacobi iterates ρF, whose
// eigenvalues are ±ρ, and from B = E the residual is exactly ρ^(k+1) after k sweeps: spectral
// radius ρ. Gauss-Seidel: B1 = E1 + ρB2 then B2 = ρB1 leaves residual ρ^(2k), radius ρ² per
// sweep. Southwell: each shot hands ρ of the unshot radiosity to the other plate, and a shot is
// one row of two, half a sweep: radius ρ² per sweep too.
Problem plates(double rho) {
  return makeProblem(platesFormFactors(), {1.0, 1.0}, grey({rho, rho}), grey({1.0, 0.0}));
}

const std::map<std::string, int> kPlateRadiusPower{
    {"jacobi", 1}, {"gauss-seidel", 2}, {"southwell", 2}};

// At ρ = 0.999999 reaching 1e-6 takes 13.8 M Jacobi sweeps (6.9 M for the others), far beyond
// a budget of 10⁶ iterations. Each method used to sweep silently to that limit; it now stops as
// soon as its rate is stable (three windows of kRateWindowSweeps, the first never trusted),
// with a prediction that matches the closed form log(tol/r)/log(radius) within 1 %.
TEST(Solve, ExactNearSingularStopsWhenPredictedOverBudget) {
  const double rho = 0.999999, tol = 1e-6;
  const Problem p = plates(rho);
  for (const auto& [name, power] : kPlateRadiusPower) {
    const double radius = std::pow(rho, power);
    const SolveResult r = runSolver(name, p.system, tol, ResidualNorm::Relative, 1000000);
    EXPECT_EQ(r.exit, "predicted_over_budget") << name << ": " << r.reason;
    EXPECT_FALSE(r.converged) << name;
    EXPECT_EQ(r.history.back().sweeps, 3 * kRateWindowSweeps) << name;
    EXPECT_NEAR(r.spectralRadius, radius, 1e-9) << name;
    const double analytic = std::log(tol / r.residual) / std::log(radius);
    EXPECT_GT(analytic, 1e6) << name;
    EXPECT_NEAR(r.predictedSweeps / analytic, 1.0, 0.01) << name << ": " << r.predictedSweeps;
    EXPECT_EQ(r.reason.rfind("predicted over budget: at estimated spectral radius", 0), 0u)
        << r.reason;
    for (const char* part : {"--max-iterations 1000000 leaves", "Fix: raise --max-iterations"})
      EXPECT_NE(r.reason.find(part), std::string::npos) << name << ": " << r.reason;
    // A valid partial solution: more light than emitted, all of it finite.
    EXPECT_TRUE(allFinite(r.radiosity)) << name;
    EXPECT_GT(r.radiosity[0][1], 0.0) << name;
  }
}

// No false positives. The plates at ρ = 0.99 reach 1e-6 after ceil(ln 1e-6 / ln 0.99) - 1 =
// 1374 Jacobi sweeps, 688 Gauss-Seidel sweeps and 1375 Southwell shots: given exactly that many
// iterations every method converges (the prediction is checked every window up to the end).
// Given a few too few it does not; once the need exceeds kPredictionMargin times what is left,
// the prediction may stop it before the limit, and is then right.
TEST(Solve, ExactPredictionNeverStopsARunThatFitsItsBudget) {
  const Problem p = plates(0.99);
  const std::map<std::string, long> needed{
      {"jacobi", 1374}, {"gauss-seidel", 688}, {"southwell", 1375}};
  for (const auto& [name, iterations] : needed) {
    SolveResult r = runSolver(name, p.system, 1e-6, ResidualNorm::Relative, iterations);
    EXPECT_EQ(r.exit, "converged") << name << ": " << r.reason;
    EXPECT_EQ(r.iterations, iterations) << name;
    for (const long shorter : {iterations - 1, iterations * 8 / 11}) {
      r = runSolver(name, p.system, 1e-6, ResidualNorm::Relative, shorter);
      EXPECT_FALSE(r.converged) << name;
      EXPECT_TRUE(r.exit == "max_iterations" || r.exit == "predicted_over_budget")
          << name << ": " << r.reason;
      // Not before its rate was stable, and with the sweeps it really still needed (to 1 %).
      if (r.exit == "predicted_over_budget") {
        EXPECT_GE(r.history.back().sweeps, 3 * kRateWindowSweeps) << name;
        const double sweepsPerStep = r.history.back().sweeps / double(r.iterations);
        EXPECT_NEAR(r.predictedSweeps / (double(iterations - r.iterations) * sweepsPerStep), 1.0,
                    0.01)
            << name << ": " << r.reason;
      }
    }
  }
  // The well-conditioned systems of the other tests, every solver, default limits.
  for (const std::string& name : solverNames()) {
    for (const Problem& q : {cubeOneEmitter(0.9), cubeOneEmitter(0.99), randomReciprocal(40, 21)})
      EXPECT_EQ(runSolver(name, q.system, 1e-10).exit, "converged") << name;
  }
}

// The rules of the prediction on a synthetic residual r_k = 0.999^k (a sweep per 0.01 s).
TEST(Solve, ExactPredictionNeedsAStableRateAndCountsTheTimeLeft) {
  const double rate = 0.999, tol = 1e-6;
  ConvergenceMonitor m;
  m.windowResidual = 1.0;
  double r = 1.0;
  for (int k = 1; k <= 149; ++k) {
    r *= rate;
    m.update(r, k, 0.01 * k);
    EXPECT_FALSE(m.overBudget(r, tol, 1, INFINITY)) << "sweep " << k << ": window not stable";
  }
  r *= rate;
  m.update(r, 150, 1.5);
  const double analytic = std::log(tol / r) / std::log(rate);  // 13 659 sweeps
  EXPECT_NEAR(m.sweepsToTolerance(r, tol), analytic, 1e-6 * analytic);
  // The iteration budget: stopped only beyond kPredictionMargin times what is left.
  EXPECT_FALSE(m.overBudget(r, tol, analytic / kPredictionMargin + 1, INFINITY));
  EXPECT_TRUE(m.overBudget(r, tol, analytic / kPredictionMargin - 1, INFINITY));
  EXPECT_FALSE(m.timeBound);
  // The time budget at 0.01 s per sweep: 10 s leave 1000 sweeps.
  EXPECT_TRUE(m.overBudget(r, tol, 1e9, 10.0));
  EXPECT_TRUE(m.timeBound);
  EXPECT_NEAR(m.affordable, 1000.0, 1e-6);
  EXPECT_FALSE(m.overBudget(r, tol, 1e9, 0.01 * analytic));
  EXPECT_NE(m.overBudgetText(r, tol, SolverSettings{}, 150).find("--max-seconds"),
            std::string::npos);

  // A rate that changes between windows (here halving its speed) predicts nothing; neither does
  // a rising residual (Gauss-Seidel and Southwell at ρ near 1 can rise and then converge).
  for (const double second : {std::sqrt(rate), 1.0001}) {
    ConvergenceMonitor n;
    n.windowResidual = r = 1.0;
    for (int k = 1; k <= 200; ++k) {
      r *= k <= 150 ? rate : second;
      n.update(r, k, 0.01 * k);
    }
    EXPECT_TRUE(std::isnan(n.sweepsToTolerance(r, tol))) << second;
    EXPECT_FALSE(n.overBudget(r, tol, 1, INFINITY)) << second;
  }
  // restart() (a new hierarchical round): three windows again, the first without a rate.
  r = 0.5;
  m.restart(150, 1.5);
  for (int k = 151; k <= 299; ++k) m.update(r *= rate, k, 0.01 * k);
  EXPECT_TRUE(std::isnan(m.sweepsToTolerance(r, tol)));
  m.update(r *= rate, 300, 3.0);
  EXPECT_FALSE(std::isnan(m.sweepsToTolerance(r, tol)));
}

}  // namespace radkit
