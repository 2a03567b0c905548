// Properties every registered solver must have, on every storage.
#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <cstring>
#include <iostream>

#include <tbb/task_arena.h>

#include "analytic_systems.h"

namespace radkit {
using namespace radkit::test;

TEST(Registry, Construct) {
  const std::vector<std::string> expected = {"jacobi", "gauss-seidel", "sor", "southwell", "cg"};
  EXPECT_EQ(solverNames(), expected);
  EXPECT_EQ(solverHelp().size(), expected.size());
  for (const std::string& name : expected) EXPECT_EQ(makeSolver(name)->name(), name);
  try {
    makeSolver("gauss-jordan");
    FAIL() << "unknown name accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("jacobi, gauss-seidel, sor, southwell, cg"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(makeSolver("jacobi", Params({{"omega", 1.0}})), std::invalid_argument);
}

// Same inputs, same bits, whatever the thread count: rows are summed by one thread in a fixed
// order and reductions sum fixed chunks in order.
TEST(Registry, ExactSameBitsForOneAndTwoThreads) {
  Problem p = randomReciprocal(400, 23);
  for (const std::string& name : solverNames()) {
    SolveResult one, two;
    tbb::task_arena(1).execute([&] { one = runSolver(name, p.system, 1e-11); });
    tbb::task_arena(2).execute([&] { two = runSolver(name, p.system, 1e-11); });
    EXPECT_EQ(one.iterations, two.iterations) << name;
    for (int c = 0; c < 3; ++c)
      EXPECT_EQ(0,
                std::memcmp(one.radiosity[c].data(), two.radiosity[c].data(), 400 * sizeof(double)))
          << name;
  }
}

// Furnace: uniform ρ and E in a closed enclosure give B = E/(1 − ρ). Float storage rounds each
// F_ij by at most ε_f/2 relative, so a row sum moves by at most ε_f/2 and B by ρ ε_f/(2(1 − ρ)).
TEST(Registry, ExactFurnaceEveryStorage) {
  const double rho = 0.8, tol = 1e-12;
  const std::vector<double> area = {0.3, 1.0, 2.5, 0.7, 4.0, 1.1, 0.05};
  for (Storage s : kAllStorages) {
    const bool isFloat = s == Storage::DenseFloat || s == Storage::CsrFloat;
    const double bound = 2 * tol / (1 - rho) + (isFloat ? rho * FLT_EPSILON / (1 - rho) : 1e-14);
    std::vector<Problem> problems;
    problems.push_back(makeProblem(cubeFormFactors(), std::vector<double>(6, 1.0),
                                   grey(std::vector<double>(6, rho)),
                                   grey(std::vector<double>(6, 1.0)), s));
    problems.push_back(makeProblem(sphereFormFactors(area), area, grey(std::vector<double>(7, rho)),
                                   grey(std::vector<double>(7, 1.0)), s));
    for (const Problem& p : problems)
      for (const std::string& name : solverNames()) {
        const SolveResult r = runSolver(name, p.system, tol);
        ASSERT_TRUE(r.converged) << name << " " << r.reason;
        for (int c = 0; c < 3; ++c)
          for (double b : r.radiosity[c])
            EXPECT_NEAR(b * (1 - rho), 1.0, bound) << name << " " << storageLabel(s);
      }
  }
}

TEST(Registry, ExactEnergyBalanceClosedEnclosure) {
  const std::vector<double> area = {0.3, 1.0, 2.5, 0.7, 4.0, 1.1};
  const std::vector<double> e = {0.0, 2.0, 0.0, 0.5, 0.0, 1.0};
  const double rho = 0.6;
  Problem p =
      makeProblem(sphereFormFactors(area), area, grey(std::vector<double>(6, rho)), grey(e));
  double emitted = 0.0;
  for (int i = 0; i < 6; ++i) emitted += area[i] * e[i];
  for (const std::string& name : solverNames()) {
    const SolveResult r = runSolver(name, p.system, 1e-13);
    double power = 0.0;
    for (int i = 0; i < 6; ++i) power += area[i] * r.radiosity[1][i];
    EXPECT_NEAR(power / (emitted / (1 - rho)), 1.0, 1e-11) << name;
  }
}

TEST(Registry, ExactAllSolversAgreeWithDirectSolve) {
  for (unsigned seed : {1u, 2u, 3u})
    for (Storage s : {Storage::DenseDouble, Storage::CsrDouble}) {
      Problem p = randomReciprocal(40, seed, s);
      const Channels direct = directSolve(p.system);
      for (const std::string& name : solverNames()) {
        const SolveResult r = runSolver(name, p.system, 1e-13);
        ASSERT_TRUE(r.converged) << name << ": " << r.reason;
        EXPECT_LT(relativeError(r.radiosity, direct), 1e-10) << name << " seed " << seed;
        EXPECT_LT(r.checkedResidual, 1e-12) << name;
      }
    }
}

// Two enclosures in one scene (block-diagonal F), lit at 1e20 and at 1e-20 W/m². The per-patch
// norm holds both to the tolerance relative to their own radiosity. The ∞-norm relative to ‖E‖∞
// would accept the 1e-20 enclosure before it has received any light; the sweeping methods and
// CG happen to treat it anyway, Southwell (which shoots by power) does not.
TEST(Registry, ExactEmissionSpanning40Decades) {
  const int m = 5;
  std::vector<double> f(4 * m * m, 0.0), area(2 * m, 1.0), e(2 * m, 0.0), expected(2 * m);
  for (int b = 0; b < 2; ++b)
    for (int i = 0; i < m; ++i)
      for (int j = 0; j < m; ++j) f[(b * m + i) * 2 * m + b * m + j] = 1.0 / m;
  e[0] = 1e20;
  e[1] = 1e-20;  // same enclosure as the 1e20 emitter: invisible next to it, still exact
  e[m] = 1e-20;
  const double rho = 0.7;
  for (int b = 0; b < 2; ++b) {
    double eBar = 0.0;
    for (int i = 0; i < m; ++i) eBar += e[b * m + i] / m;
    for (int i = 0; i < m; ++i) expected[b * m + i] = e[b * m + i] + rho * eBar / (1 - rho);
  }
  Problem p = makeProblem(f, area, grey(std::vector<double>(2 * m, rho)), grey(e));
  for (const std::string& name : solverNames()) {
    const SolveResult r = runSolver(name, p.system, 1e-12, ResidualNorm::PerPatch);
    ASSERT_TRUE(r.converged) << name << ": " << r.reason;
    for (int i = 0; i < 2 * m; ++i)
      EXPECT_NEAR(r.radiosity[0][i] / expected[i], 1.0, 1e-10) << name << " patch " << i;
  }
  Channels unlit = grey(expected);
  for (int i = m; i < 2 * m; ++i) unlit[0][i] = unlit[1][i] = unlit[2][i] = e[i];
  const Channels r = residualVector(p.system, unlit);
  EXPECT_LT(residualMeasure(p.system, r, unlit, ResidualNorm::Relative), 1e-12);
  EXPECT_GT(residualMeasure(p.system, r, unlit, ResidualNorm::PerPatch), 0.5);
  const SolveResult loose = runSolver("southwell", p.system, 1e-12, ResidualNorm::Relative);
  EXPECT_GT(std::fabs(loose.radiosity[0][m + 1] / expected[m + 1] - 1.0), 0.5);
}

TEST(Registry, ExactAreaRatio1e8) {
  const std::vector<double> area = {1e-8, 1.0, 2.0, 0.5, 1.0};
  const std::vector<double> e = {1.0, 0.0, 0.0, 0.0, 0.0};
  const std::vector<double> rho = {0.5, 0.7, 0.3, 0.9, 0.6};
  Problem p = makeProblem(sphereFormFactors(area), area, grey(rho), grey(e));
  double total = 0, rhoBar = 0, eBar = 0;
  for (int i = 0; i < 5; ++i) total += area[i];
  for (int i = 0; i < 5; ++i) {
    rhoBar += area[i] * rho[i] / total;
    eBar += area[i] * e[i] / total;
  }
  for (const std::string& name : solverNames()) {
    const SolveResult r = runSolver(name, p.system, 1e-13, ResidualNorm::PerPatch);
    ASSERT_TRUE(r.converged) << name << ": " << r.reason;
    for (int i = 0; i < 5; ++i)
      EXPECT_NEAR(r.radiosity[2][i] / (e[i] + rho[i] * eBar / (1 - rhoBar)), 1.0, 1e-11)
          << name << " patch " << i;
  }
}

// Accuracy floor of each storage: solve to 1e-14 and compare with the long-double solution of
// the double-precision system. Measured figures are printed for docs/solvers.md.
TEST(Registry, ExactFloatAndDoubleAccuracyFloors) {
  for (double rho : {0.5, 0.9, 0.99}) {
    std::vector<double> area(40);
    for (int i = 0; i < 40; ++i) area[i] = 0.1 + 0.05 * ((i * 7919) % 40);
    std::vector<double> e(40, 0.0);
    e[3] = 1.0;
    e[17] = 0.25;
    const Channels direct = directSolve(
        makeProblem(sphereFormFactors(area), area, grey(std::vector<double>(40, rho)), grey(e))
            .system);
    for (Storage s : kAllStorages) {
      Problem p = makeProblem(sphereFormFactors(area), area, grey(std::vector<double>(40, rho)),
                              grey(e), s);
      const SolveResult r = runSolver("gauss-seidel", p.system, 1e-14);
      const double err = relativeError(r.radiosity, direct);
      const bool isFloat = s == Storage::DenseFloat || s == Storage::CsrFloat;
      std::cout << "[ floor    ] rho " << rho << " " << storageLabel(s) << " relative error " << err
                << "\n";
      EXPECT_LT(err, isFloat ? FLT_EPSILON / (1 - rho) : 1e-13 / (1 - rho)) << storageLabel(s);
    }
  }
}

}  // namespace radkit
