#include <gtest/gtest.h>

#include "analytic_systems.h"

namespace radkit {
using namespace radkit::test;

namespace {
void expectInvalid(const RadiositySystem& s, const std::string& fragment) {
  try {
    s.validate();
    ADD_FAILURE() << "accepted; expected an error mentioning " << fragment;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}
}  // namespace

TEST(RadiositySystem, Construct) {
  Problem p = tenPatchSphere();
  EXPECT_NO_THROW(p.system.validate());
  EXPECT_EQ(p.system.size(), 10);
  EXPECT_EQ(p.system.emissionNorm(), 1.0);

  RadiositySystem none;
  EXPECT_THROW(none.matrix(), std::logic_error);
  expectInvalid(none, "no form-factor matrix");

  Problem q = tenPatchSphere();
  q.system.area.pop_back();
  expectInvalid(q.system, "10 x 10 for 9 areas");
  q = tenPatchSphere();
  q.system.area[4] = 0.0;
  expectInvalid(q.system, "area[patch 4]");
  q = tenPatchSphere();
  q.system.reflectance[2][7] = 1.0;
  expectInvalid(q.system, "reflectance[blue][patch 7] = 1");
  q = tenPatchSphere();
  q.system.reflectance[0][1] = -0.1;
  expectInvalid(q.system, "reflectance[red][patch 1]");
  q = tenPatchSphere();
  q.system.emission[1][0] = -1.0;
  expectInvalid(q.system, "emission[green][patch 0]");
  q = tenPatchSphere();
  q.system.emission[1].resize(3);
  expectInvalid(q.system, "emission channel green has 3 entries");
}

TEST(RadiositySystem, ExactResidual) {
  Problem p = makeProblem(platesFormFactors(), {1.0, 1.0}, grey({0.5, 0.5}), grey({1.0, 0.0}));
  const Channels exact = grey({4.0 / 3.0, 2.0 / 3.0});
  EXPECT_LT(maxAbs(residualVector(p.system, exact)), 1e-15);
  const Channels r = residualVector(p.system, p.system.emission);  // B = E: r = ρFE
  EXPECT_EQ(r[0], (std::vector<double>{0.0, 0.5}));
  EXPECT_EQ(residualMeasure(p.system, r, p.system.emission, ResidualNorm::Relative), 0.5);
  EXPECT_EQ(residualMeasure(p.system, r, p.system.emission, ResidualNorm::PerPatch), 1.0);
  EXPECT_EQ(residualPower(p.system, r), 1.5);
}

}  // namespace radkit
