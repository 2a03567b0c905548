// Presets: the contract the command line relies on (names, errors, which fields change, and
// that explicit options applied afterwards win).
#include <gtest/gtest.h>

#include <stdexcept>

#include "radiosity/presets.h"

namespace radkit {

TEST(Presets, ConstructNamesInOrderOfCost) {
  EXPECT_EQ(presetNames(), (std::vector<std::string>{"draft", "balanced", "reference", "large"}));
  PipelineSettings previous;
  previous.mesh.targetPatches = 0;
  previous.stopping.tolerance = 1;
  for (const std::string& name : presetNames()) {
    if (presetIsHierarchical(name)) continue;
    PipelineSettings s;
    applyPreset(name, s);
    EXPECT_GT(s.mesh.targetPatches, previous.mesh.targetPatches) << name;
    EXPECT_LT(s.stopping.tolerance, previous.stopping.tolerance) << name;
    EXPECT_NE(describePreset(name).find(name), std::string::npos);
    previous = s;
  }
}

TEST(Presets, ConstructUnknownNameListsTheKnownOnes) {
  PipelineSettings s;
  try {
    applyPreset("fast", s);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    std::string m = e.what();
    for (const std::string& name : presetNames()) EXPECT_NE(m.find(name), std::string::npos) << m;
    EXPECT_NE(m.find("fast"), std::string::npos) << m;
  }
  EXPECT_THROW(describePreset(""), std::invalid_argument);
}

// The hierarchical preset picks a method and leaves every dense setting as it was.
TEST(Presets, ConstructLargeIsHierarchicalAndChangesNoDenseSetting) {
  EXPECT_TRUE(presetIsHierarchical("large"));
  for (const char* dense : {"draft", "balanced", "reference"})
    EXPECT_FALSE(presetIsHierarchical(dense));
  EXPECT_THROW(presetIsHierarchical("fast"), std::invalid_argument);
  PipelineSettings s, before;
  s.mesh.targetPatches = before.mesh.targetPatches = 123;
  applyPreset("large", s);
  EXPECT_EQ(s.mesh.targetPatches, 123);
  EXPECT_EQ(s.mesh.maxArea, before.mesh.maxArea);
  EXPECT_EQ(s.formFactors.method, before.formFactors.method);
  EXPECT_EQ(s.formFactors.samples, before.formFactors.samples);
  EXPECT_EQ(s.stopping.tolerance, before.stopping.tolerance);
  EXPECT_NE(describePreset("large").find("hierarchical"), std::string::npos);
}

// A preset changes only its fields; values set after it (explicit options) stay.
TEST(Presets, ConstructLeavesOtherSettingsAndYieldsToExplicitOnes) {
  PipelineSettings s;
  s.mesh.maxArea = 5;
  s.formFactors.seed = 42;
  s.formFactors.memoryBudget = 1234;
  s.solvers = {{"sor", "omega=1.2"}};
  s.stopping.maxIterations = 7;
  applyPreset("draft", s);
  EXPECT_EQ(s.mesh.maxArea, 0);  // the preset's patch count replaces an earlier area limit
  EXPECT_EQ(s.formFactors.seed, 42u);
  EXPECT_EQ(s.formFactors.memoryBudget, 1234u);
  EXPECT_EQ(s.solvers.front().name, "sor");
  EXPECT_EQ(s.stopping.maxIterations, 7);
  s.formFactors.samples = 99;  // the user's --ff-samples, applied after the preset
  EXPECT_EQ(s.formFactors.samples, 99);
}

}  // namespace radkit
