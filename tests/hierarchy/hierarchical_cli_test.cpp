// `radkit run --method hierarchical` end to end: every output of a dense run plus links.png,
// and bad options refused before any work with a message that names the option and the fix.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <fstream>
#include <nlohmann/json.hpp>

#include "tests/common/test_util.h"

namespace radkit::test {
namespace {

TEST(HierarchicalCli, CornellBoxWritesEveryOutput) {
  TempDir dir;
  std::string out = dir.path("run");
  RunResult r = runRadkit("run " + dataPath("cornell-box.json") +
                          " --method hierarchical --image-size 64 --out " + out);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (const char* f : {"patches.csv", "surfaces.csv", "radiosity.vtp", "convergence.csv",
                        "convergence.png", "report.json", "render.png", "links.png"})
    EXPECT_TRUE(std::filesystem::exists(out + "/" + f)) << f;
  nlohmann::json report = nlohmann::json::parse(std::ifstream(out + "/report.json"));
  EXPECT_EQ(report["method"], "hierarchical");
  const auto& h = report["hierarchy"];
  EXPECT_EQ(h["input_faces"], 24);
  EXPECT_GT(h["links"].get<long long>(), 0);
  long long kinds = 0;
  for (auto& [name, count] : h["links_by_kind"].items()) kinds += count.get<long long>();
  EXPECT_EQ(kinds, h["links"].get<long long>());
  EXPECT_EQ(report["mesh"]["patches"], h["leaves"]);
  EXPECT_TRUE(report["solvers"][0]["converged"].get<bool>());
  // Leaves are patches: one row each in patches.csv.
  EXPECT_EQ(static_cast<long long>(readCsv(out + "/patches.csv").size()),
            h["leaves"].get<long long>());
  // The escape estimate makes the balance an independent check: within a few standard errors.
  double se = report["escape_estimate"]["escaped_standard_error_W"][1];
  double emitted = report["energy_balance"]["emitted_W"][1],
         absorbed = report["energy_balance"]["absorbed_W"][1],
         escaped = report["energy_balance"]["escaped_W"][1];
  EXPECT_LT(std::fabs(emitted - absorbed - escaped), 4 * se + 0.01 * emitted);
}

TEST(HierarchicalCli, DenseOnlyOptionsAndBadValuesAreRefused) {
  TempDir dir;
  std::string out = dir.path("run");
  // Each refusal names the option it refuses (and, for dense-only ones, what to use instead).
  auto refuses = [&](const std::string& options, std::initializer_list<const char*> named) {
    RunResult r = runRadkit("run " + dataPath("cornell-box.json") + " --method hierarchical " +
                            options + " --out " + out);
    EXPECT_NE(r.exitCode, 0) << options;
    for (const char* name : named)
      EXPECT_NE(r.output.find(name), std::string::npos) << options << ": " << r.output;
  };
  refuses("--patches 100", {"--patches", "--epsilon"});
  refuses("--epsilon 0", {"--epsilon"});
  refuses("--min-area 1e12", {"--min-area"});
  refuses("--memory-budget 1MiB", {"--memory-budget"});
  refuses("--gather sideways", {"--gather"});
  EXPECT_FALSE(std::filesystem::exists(out)) << "no partial output";
}

/// The study puts the hierarchy's ε ladder on the same error axes as the uniform meshes,
/// measured against the same reference.
TEST(HierarchicalCli, StudyMeasuresTheEpsilonLadder) {
  TempDir dir;
  // The ladder gets what the mesh rungs and the reference leave of the wall-clock budget, so
  // how much of it runs depends on the machine's load (under the suite's heaviest start a
  // 20 s study once left it nothing). A ladder the planner skipped for want of time (its
  // needed_s above its left_s) is asked for once more with three times the budget.
  std::vector<std::map<std::string, std::string>> ladder;
  for (int budget : {20, 60}) {
    std::string out = dir.path("study" + std::to_string(budget));
    RunResult r = runRadkit("study " + dataPath("cube-one-emitter.json") + " --max-seconds " +
                            std::to_string(budget) + " --knob-patches 250 --epsilons 1e-2 1e-3 --out " +
                            out);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    ladder.clear();
    bool skippedForTime = false;
    for (const auto& row : readCsv(out + "/study.csv")) {
      if (row.at("knob") != "hierarchical") continue;
      ladder.push_back(row);
      if (row.at("status") != "ran")
        skippedForTime |= std::stod(row.at("needed_s")) > std::stod(row.at("left_s"));
    }
    if (!skippedForTime) break;
  }
  int ran = 0;
  std::vector<double> errors;
  for (const auto& row : ladder) {
    EXPECT_EQ(row.at("status"), "ran");
    double e = std::stod(row.at("surface_error"));
    EXPECT_TRUE(std::isfinite(e) && e >= 0);
    errors.push_back(e);
    ++ran;
  }
  ASSERT_EQ(ran, 2);
  EXPECT_LT(errors[1], errors[0]) << "a smaller epsilon is closer to the reference";
}

}  // namespace
}  // namespace radkit::test
