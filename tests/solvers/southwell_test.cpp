#include <gtest/gtest.h>

#include <cstring>

#include "analytic_systems.h"

namespace radkit {
using namespace radkit::test;

TEST(SouthwellSolver, Construct) {
  auto solver = makeSolver("southwell");
  EXPECT_EQ(solver->name(), "southwell");
  Problem p = tenPatchSphere();
  solver->start(p.system, SolverSettings{});
  EXPECT_EQ(solver->radiosity(), p.system.emission);  // progressive refinement starts at B = E
  EXPECT_DOUBLE_EQ(solver->unshotPower(), 3.0);       // A·ΔB summed over channels
}

TEST(SouthwellSolver, ExactSphere) {
  const SolveResult r = runSolver("southwell", tenPatchSphere().system, 1e-13);
  ASSERT_TRUE(r.converged) << r.reason;
  EXPECT_NEAR(r.radiosity[0][0], 1.2333333333333333, 1e-12);
  EXPECT_NEAR(r.radiosity[1][5], 0.2333333333333333, 1e-12);
  EXPECT_LE(r.checkedResidual, r.residual);  // ‖ΔB‖ bounds the true residual of B
}

// Each shot removes A_i ΔB_i and hands on at most ρ_max of it: the unshot power never grows.
TEST(SouthwellSolver, ExactUnshotPowerNeverGrows) {
  for (unsigned seed : {1u, 2u}) {
    Problem p = randomReciprocal(60, seed);
    auto solver = makeSolver("southwell");
    solver->start(p.system, SolverSettings{});
    double previous = solver->unshotPower();
    for (int k = 0; k < 5000; ++k) {
      solver->step();
      ASSERT_LE(solver->unshotPower(), previous) << "shot " << k;
      previous = solver->unshotPower();
    }
  }
}

// The ambient term is display-only: B converges to the direct solution with or without asking
// for it, and it falls to zero with the unshot power.
TEST(SouthwellSolver, ExactAmbientNeverFedBack) {
  Problem p = cubeOneEmitter(0.8);
  auto solver = makeSolver("southwell");
  solver->start(p.system, SolverSettings{});
  solver->step();
  const Channels before = solver->radiosity();
  const Rgb ambient = solver->ambient();
  EXPECT_GT(ambient[0], 0.0);
  EXPECT_EQ(solver->radiosity(), before);
  // After the first shot ΔB is the light of one bounce, ρ F_0j on each face j != 0.
  const double unshot = 0.8 * (kCubeOpposite + 4 * kCubeAdjacent);
  EXPECT_NEAR(ambient[0], unshot / 6.0 / (1.0 - 0.8), 1e-12);
  const SolveResult r = runSolver("southwell", p.system, 1e-13);
  EXPECT_LT(relativeError(r.radiosity, directSolve(p.system)), 1e-12);
  EXPECT_LT(r.ambient[0], 1e-12);
}

TEST(SouthwellSolver, ExactHighReflectanceConverges) {
  for (double rho : {0.999, 0.9999}) {
    Problem p = cubeOneEmitter(rho, Storage::CsrDouble);
    const SolveResult r = runSolver("southwell", p.system, 1e-9);
    ASSERT_TRUE(r.converged) << r.reason;
    EXPECT_LT(relativeError(r.radiosity, directSolve(p.system)), 1e-9 / (1 - rho));
    EXPECT_NEAR(r.history.back().sweeps, r.iterations / 6.0, 1e-6);  // 5 of 6 entries per row
  }
}

TEST(SouthwellSolver, ExactSameInputsSameBits) {
  Problem p = randomReciprocal(300, 5);
  const SolveResult a = runSolver("southwell", p.system, 1e-10);
  const SolveResult b = runSolver("southwell", p.system, 1e-10);
  for (int c = 0; c < 3; ++c)
    EXPECT_EQ(0, std::memcmp(a.radiosity[c].data(), b.radiosity[c].data(), 300 * sizeof(double)));
}

}  // namespace radkit
