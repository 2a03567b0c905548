// Hostile option values (issue 20, points 5 and 8): NaN, infinity and values out of range are
// refused at parse time with the option's name, a non-zero exit and no output, instead of a
// solver that never stops, a limit silently ignored or an allocation that ends in bad_alloc.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "tests/common/test_util.h"

namespace radkit {
namespace {

namespace fs = std::filesystem;

struct OptionCase {
  const char* name;
  std::string args;                      ///< after "COMMAND SCENE"
  std::vector<std::string> mustMention;
  std::string command = "mesh";
};

void PrintTo(const OptionCase& c, std::ostream* os) { *os << c.name; }

class HostileOption : public ::testing::TestWithParam<OptionCase> {};

TEST_P(HostileOption, RefusedBeforeAnyWork) {
  const OptionCase& c = GetParam();
  test::TempDir dir;
  const test::RunResult r = test::runRadkitWithin(
      120, c.command + " '" + test::dataPath("furnace.json") + "' " + c.args + " --out '" + dir.path("o") + "'");
  EXPECT_NE(r.exitCode, 0) << r.output;
  EXPECT_NE(r.exitCode, 124) << "timed out";
  for (const std::string& word : c.mustMention)
    EXPECT_NE(r.output.find(word), std::string::npos) << "missing '" << word << "' in:\n" << r.output;
  EXPECT_FALSE(fs::exists(dir.path("o")));
  EXPECT_EQ(r.output.find("bad_alloc"), std::string::npos) << r.output;
}

INSTANTIATE_TEST_SUITE_P(
    Options, HostileOption,
    ::testing::Values(
        OptionCase{"MaxAreaNan", "--max-area nan", {"--max-area", "'nan' is not a finite number"}},
        OptionCase{"MaxAreaInf", "--max-area inf", {"--max-area", "'inf' is not a finite number"}},
        OptionCase{"MaxAreaTiny", "--max-area 1e-300", {"--max-area 1e-300", "more than 10000000 patches"}},
        OptionCase{"MaxAreaSmall", "--max-area 1e-12", {"--max-area 1e-12", "more than 10000000 patches"}},
        OptionCase{"MaxAreaTinyInRun", "--max-area 1e-300", {"furnace.json", "--max-area 1e-300"}, "run"},
        OptionCase{"PatchesBillion", "--patches 1000000000", {"--patches", "1000000000"}},
        OptionCase{"TolNan", "--tol nan", {"--tol", "'nan' is not a finite number"}, "run"},
        OptionCase{"TolInf", "--tol inf", {"--tol"}, "run"},
        OptionCase{"MaxSecondsNan", "--max-seconds nan", {"--max-seconds"}, "run"},
        OptionCase{"AdaptiveTolNan", "--adaptive --adaptive-tol nan", {"--adaptive-tol"}, "run"},
        OptionCase{"MemoryBudgetHuge", "--memory-budget 1e30GiB", {"--memory-budget", "larger than"}, "formfactors"}),
    [](const ::testing::TestParamInfo<OptionCase>& param) { return std::string(param.param.name); });

TEST(HostileOptionCli, ExposureNanRefusedByRender) {
  test::TempDir dir;
  const test::RunResult r = test::runRadkitWithin(
      120, "render '" + test::dataPath("furnace.json") + "' --exposure nan --out '" + dir.path("i.png") + "'");
  EXPECT_NE(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("--exposure"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir.path("i.png")));
}

// Point 9: report.json says how each solver stopped, with its spectral-radius estimate.
TEST(HostileOptionCli, ReportSaysMaxIterationsExit) {
  test::TempDir dir;
  const test::RunResult r = test::runRadkitWithin(
      300, "run '" + test::dataPath("furnace.json") + "' --patches 24 --no-render --solvers jacobi "
           "--max-iterations 20 --tol 1e-12 --out '" + dir.path("o") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  std::ifstream in(dir.path("o/report.json"));
  const nlohmann::json solver = nlohmann::json::parse(in)["solvers"][0];
  EXPECT_EQ(solver["exit_reason"], "max_iterations") << solver.dump();
  ASSERT_TRUE(solver["spectral_radius_estimate"].is_number()) << solver.dump();
  EXPECT_GT(solver["spectral_radius_estimate"].get<double>(), 0.0);
  EXPECT_LT(solver["spectral_radius_estimate"].get<double>(), 1.0);
}

}  // namespace
}  // namespace radkit
