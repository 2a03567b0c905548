#include <gtest/gtest.h>

#include <cstring>

#include "analytic_systems.h"

namespace radkit {
using namespace radkit::test;

TEST(ConjugateGradientSolver, Construct) {
  EXPECT_EQ(makeSolver("cg")->name(), "cg");
  EXPECT_NO_THROW(makeSolver("cg", Params({{"replace_every", 0}})));
  EXPECT_THROW(makeSolver("cg", Params({{"replace_every", -1}})), std::invalid_argument);
}

TEST(ConjugateGradientSolver, ExactSphereUnequalAreas) {
  const std::vector<double> area = {0.3, 1.0, 2.5, 0.7, 4.0, 1.1};
  Problem p = makeProblem(sphereFormFactors(area), area, grey({0.7, 0.5, 0.2, 0.9, 0.6, 0.4}),
                          grey({1.0, 0, 0, 0, 0.5, 0}));
  const SolveResult r = runSolver("cg", p.system, 1e-13);
  ASSERT_TRUE(r.converged) << r.reason;
  // B_i = E_i + ρ_i Ē / (1 − ρ̄) with area-weighted means (docs/oracles.md, Closed-form radiosity).
  double total = 0, rhoBar = 0, eBar = 0;
  for (int i = 0; i < 6; ++i) total += area[i];
  for (int i = 0; i < 6; ++i) {
    rhoBar += area[i] * p.system.reflectance[0][i] / total;
    eBar += area[i] * p.system.emission[0][i] / total;
  }
  for (int i = 0; i < 6; ++i)
    EXPECT_NEAR(r.radiosity[0][i],
                p.system.emission[0][i] + p.system.reflectance[0][i] * eBar / (1 - rhoBar), 1e-12);
}

// ρ = 0 patches are eliminated: B_i = E_i exactly there, the rest matches the direct solve.
TEST(ConjugateGradientSolver, ExactZeroReflectancePatchesEliminated) {
  Problem p = randomReciprocal(50, 13);
  const SolveResult r = runSolver("cg", p.system, 1e-13);
  ASSERT_TRUE(r.converged) << r.reason;
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < 50; ++i)
      if (p.system.reflectance[c][i] == 0.0) {
        EXPECT_EQ(r.radiosity[c][i], p.system.emission[c][i]);
      }
  EXPECT_LT(relativeError(r.radiosity, directSolve(p.system)), 1e-11);
  EXPECT_LT(r.iterations, 50);
}

// The preconditioned spectrum lies in [1 − ρ, 1 + ρ]: CG needs far fewer steps than Jacobi.
TEST(ConjugateGradientSolver, ExactHighReflectanceConverges) {
  for (double rho : {0.999, 0.9999}) {
    Problem p = cubeOneEmitter(rho);
    const SolveResult r = runSolver("cg", p.system, 1e-9);
    ASSERT_TRUE(r.converged) << r.reason;
    EXPECT_LE(r.iterations, 12);
    EXPECT_LT(relativeError(r.radiosity, directSolve(p.system)), 1e-9 / (1 - rho));
  }
}

TEST(ConjugateGradientSolver, ExactSameInputsSameBits) {
  Problem p = randomReciprocal(400, 17);
  const SolveResult a = runSolver("cg", p.system, 1e-12);
  const SolveResult b = runSolver("cg", p.system, 1e-12);
  for (int c = 0; c < 3; ++c)
    EXPECT_EQ(0, std::memcmp(a.radiosity[c].data(), b.radiosity[c].data(), 400 * sizeof(double)));
}

}  // namespace radkit
