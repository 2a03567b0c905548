#include <gtest/gtest.h>

#include "analytic_systems.h"
#include "solvers/convergence.h"

namespace radkit {
using namespace radkit::test;

TEST(Convergence, ExactMilestones) {
  const SolveResult r = runSolver("jacobi", tenPatchSphere().system, 1e-10);
  // Residual after k sweeps is ρĒ ρ^k = 0.07 · 0.7^k (ten-patch sphere, ρ = 0.7, Ē = 0.1):
  // first <= 1e-3 at k = ceil(ln(1e-3/0.07)/ln 0.7) = 12, <= 1e-6 at k = 32, <= 1e-9 at 51.
  const auto m = milestones(r);
  ASSERT_EQ(m.size(), 3u);
  EXPECT_TRUE(m[0].reached && m[1].reached && m[2].reached);
  EXPECT_EQ(m[2].iterations, 51);
  EXPECT_EQ(m[2].sweeps, 51.0);
  EXPECT_FALSE(milestones(r, {1e-11})[0].reached);
  EXPECT_EQ(m[0].iterations, 12);
  EXPECT_EQ(m[1].iterations, 32);
}

}  // namespace radkit
