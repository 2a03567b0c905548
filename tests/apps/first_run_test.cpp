// What a first-time user meets beyond the shipped defaults: each form-factor method's own K
// and the noise warning, the two-pass modes on a scene without glossy materials, load
// warnings in every report, and a study that stays within its budget.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/common/read_json.h"
#include "tests/common/test_util.h"

namespace radkit {
namespace {

using nlohmann::json;
using test::dataPath;
using test::readJson;
using test::runRadkit;

bool mentions(const json& lines, const std::string& text) {
  for (const json& l : lines)
    if (l.get<std::string>().find(text) != std::string::npos) return true;
  return false;
}

// hemisphere spends K rays per patch, not per pair: at the per-pair default of 16 its image
// was a patchwork with no word. It now has its own default and says when K is too small.
TEST(FirstRun, HemisphereHasItsOwnSamplesAndWarnsWhenNoisy) {
  test::TempDir dir;
  const std::string scene = "'" + dataPath("cornell-box.json") + "' --patches 150 --no-render";
  auto r = runRadkit("run " + scene + " --ff hemisphere --ff-samples 16 --out '" + dir.path("k16") +
                     "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const json noisy = readJson(dir.path("k16/report.json"));
  EXPECT_TRUE(mentions(noisy["warnings"], "hemisphere form factors are noisy"))
      << noisy["warnings"];
  EXPECT_TRUE(mentions(noisy["warnings"], "Fix: --ff-samples"));
  EXPECT_GT(noisy["form_factors"]["gathered_light_noise"].get<double>(), 0.05);

  r = runRadkit("run " + scene + " --ff hemisphere --out '" + dir.path("default") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const json quiet = readJson(dir.path("default/report.json"));
  EXPECT_NE(quiet["form_factors"]["description"].get<std::string>().find("K=16384"),
            std::string::npos)
      << quiet["form_factors"]["description"];
  EXPECT_FALSE(mentions(quiet["warnings"], "noisy")) << quiet["warnings"];
  EXPECT_LT(quiet["form_factors"]["gathered_light_noise"].get<double>(), 0.05);

  // point-polygon keeps its own default: no gathered-light noise is reported for it.
  r = runRadkit("run " + scene + " --out '" + dir.path("pp") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const json pp = readJson(dir.path("pp/report.json"));
  EXPECT_FALSE(pp["form_factors"].contains("gathered_light_noise"));
  EXPECT_NE(pp["form_factors"]["description"].get<std::string>().find("K=16"), std::string::npos);
}

// The Cornell box is all Lambertian: phong and cook-torrance give one image, and say so, in
// the console and in --report with the loader's warnings (the box's non-planar wall).
TEST(FirstRun, TwoPassModesSayWhenNoMaterialIsGlossy) {
  test::TempDir dir;
  const std::string common = " --size 8x8 --spp 1 --patches 60";
  auto r = runRadkit("render '" + dataPath("cornell-box.json") + "' --shading path-trace" + common +
                     " --out '" + dir.path("ref.pfm") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  r = runRadkit("render '" + dataPath("cornell-box.json") + "' --shading phong" + common +
                " --out '" + dir.path("p.pfm") + "' --reference '" + dir.path("ref.pfm") +
                "' --report '" + dir.path("p.json") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("no surface has a glossy"), std::string::npos) << r.output;
  const json report = readJson(dir.path("p.json"));
  EXPECT_TRUE(mentions(report["warnings"], "no surface has a glossy"));
  EXPECT_TRUE(mentions(report["load"]["warnings"], "not planar")) << report["load"];

  r = runRadkit("render '" + dataPath("cornell-box-glossy.json") + "' --shading cook-torrance" +
                common + " --out '" + dir.path("g.pfm") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(r.output.find("no surface has a glossy"), std::string::npos) << r.output;
}

TEST(FirstRun, PhotonsReportHasTheLoadWarnings) {
  test::TempDir dir;
  auto r = runRadkit("photons '" + dataPath("cornell-box.json") +
                     "' --photons 20000 --gather 4 --size 16x16 --bench-rays 1000 --patches 60 "
                     "--out '" +
                     dir.path("ph") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const json report = readJson(dir.path("ph/report.json"));
  ASSERT_TRUE(report.contains("load"));
  EXPECT_TRUE(mentions(report["load"]["warnings"], "not planar")) << report["load"];
}

// The planner's decisions are in study.csv: a configuration ran exactly when its estimate (plus
// the reference still to come) fitted the budget left, and the hierarchical ladder's budget is
// what the whole study left of --max-seconds, not a fifth kept aside however late it is.
TEST(FirstRun, StudyRunsOnlyWhatFitsTheBudgetLeft) {
  test::TempDir dir;
  const double budget = 8;
  auto r = runRadkit("study --max-seconds " + std::to_string(budget) +
                     " --knob-patches 250 --epsilons 1e-3,3e-4,1e-4 --out '" + dir.path("s") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  double spent = 0;  // seconds of the sweep rows and the reference that ran before the ladder
  int weighed = 0, hierarchical = 0;
  for (auto& row : test::readCsv(dir.path("s/study.csv"))) {
    SCOPED_TRACE(row["knob"] + " " + row["config"]);
    if (row["knob"] == "reference") spent += std::stod(row["total_s"]);
    if (row["needed_s"].empty()) continue;
    ++weighed;
    const double needed = std::stod(row["needed_s"]), left = std::stod(row["left_s"]);
    EXPECT_EQ(row["status"] == "ran", needed <= left && left > 0);
    EXPECT_LE(left, budget);
    if (row["knob"] == "hierarchical") {
      ++hierarchical;
      EXPECT_LE(left, budget - spent + 1e-9);
    } else if (row["status"] == "ran") {
      spent += std::stod(row["total_s"]);
    }
  }
  EXPECT_GT(weighed, 5);
  EXPECT_EQ(hierarchical, 3);
}

}  // namespace
}  // namespace radkit
