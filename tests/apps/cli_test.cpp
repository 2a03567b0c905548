// End-to-end through the radkit binary: what a student runs, checked against oracles from
// docs/oracles.md (view factors, closed-form radiosity) and against the scene's layout.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "tests/common/read_json.h"
#include "tests/common/test_util.h"
#include "util/canvas.h"

namespace radkit {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::dataPath;
using test::readCsv;
using test::readJson;
using test::runRadkit;

double surfaceFactor(const std::string& csv, const std::string& from, const std::string& to) {
  for (auto& row : readCsv(csv))
    if (row["from"] == from && row["to"] == to) return std::stod(row["F"]);
  ADD_FAILURE() << "no " << from << " -> " << to << " in " << csv;
  return NAN;
}

TEST(FormFactorsCli, HowellParallelAndPerpendicularSquares) {
  test::TempDir dir;
  // Howell C-11 (X = Y = 1) and C-14 (W = H = 1), docs/oracles.md.
  auto r = runRadkit("formfactors '" + dataPath("parallel-squares.json") +
                     "' --max-area 0.05 --out '" + dir.path("p") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NEAR(surfaceFactor(dir.path("p/surface_formfactors.csv"), "lower", "upper"),
              0.19982489569838746, 1e-4);
  for (const char* f : {"formfactors.bin", "formfactors.png", "patches.csv", "report.json"})
    EXPECT_TRUE(fs::exists(dir.path(std::string("p/") + f))) << f;
  EXPECT_FALSE(fs::exists(dir.path("p/formfactors.mtx")))
      << "the text matrix is written only when asked";
  r = runRadkit("formfactors '" + dataPath("perpendicular-squares.json") +
                "' --max-area 0.05 --write-matrix --out '" + dir.path("q") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NEAR(surfaceFactor(dir.path("q/surface_formfactors.csv"), "floor", "wall"),
              0.20004377607540316, 1e-4);
  std::ifstream mtx(dir.path("q/formfactors.mtx"));
  std::string banner;
  std::getline(mtx, banner);
  EXPECT_EQ(banner, "%%MatrixMarket matrix coordinate real general");
}

TEST(FormFactorsCli, CornellBoxReciprocityAndRowSums) {
  test::TempDir dir;
  // Without the blocks nothing inside the box can block a pair: F is the exact contour
  // integral, so rows sum to at most 1 up to quadrature error, and reciprocity is exact.
  auto r = runRadkit("formfactors '" + dataPath("cornell-box-empty.json") +
                     "' --patches 300 --out '" + dir.path("e") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  json ff = readJson(dir.path("e/report.json"))["form_factors"];
  EXPECT_LE(ff["row_sum"]["max"].get<double>(), 1 + 1e-5);
  EXPECT_GT(ff["row_sum"]["min"].get<double>(), 0.5);  // the open front lets the rest escape
  EXPECT_LE(ff["reciprocity"]["max_relative_error"].get<double>(), 1e-12);
  // With the blocks, visibility is estimated from K rays: rows may exceed 1 by that noise only.
  r = runRadkit("formfactors '" + dataPath("cornell-box.json") + "' --patches 300 --out '" +
                dir.path("b") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  ff = readJson(dir.path("b/report.json"))["form_factors"];
  EXPECT_LE(ff["row_sum"]["max"].get<double>(), 1.01);
  EXPECT_LE(ff["reciprocity"]["max_relative_error"].get<double>(), 1e-12);
  EXPECT_GT(ff["rays"]["saved"].get<long long>(), 0);
}

std::string fileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// --threads caps the parallel loops (report.json says how many ran) and changes no bit of F.
// --ff-pair-levels 0 gives every pair the adaptive contour: another F, as close as both rules'
// tolerances (1e-6 relative and absolute per pair) allow.
TEST(FormFactorsCli, ThreadsAndPairLevels) {
  test::TempDir dir;
  const std::string scene = "formfactors '" + dataPath("cornell-box.json") + "' --patches 300 ";
  for (const char* t : {"1", "2"}) {
    auto r = runRadkit(scene + "--threads " + t + " --out '" + dir.path(t) + "'");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(readJson(dir.path(std::string(t) + "/report.json"))["form_factors"]["threads"],
              std::stoi(t));
  }
  EXPECT_EQ(fileBytes(dir.path("1/formfactors.bin")), fileBytes(dir.path("2/formfactors.bin")));
  auto r = runRadkit(scene + "--ff-pair-levels 0 --out '" + dir.path("a") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  json selected = readJson(dir.path("1/report.json"))["form_factors"]["pairs"]["by_rule"];
  json adaptive = readJson(dir.path("a/report.json"))["form_factors"]["pairs"]["by_rule"];
  EXPECT_GT(
      selected["tensor_level_3"].get<long long>() + selected["tensor_level_4"].get<long long>(), 0);
  EXPECT_EQ(
      adaptive["tensor_level_3"].get<long long>() + adaptive["tensor_level_4"].get<long long>(), 0);
  for (auto& row : readCsv(dir.path("a/surface_formfactors.csv")))
    EXPECT_NEAR(surfaceFactor(dir.path("1/surface_formfactors.csv"), row["from"], row["to"]),
                std::stod(row["F"]), 2e-6)
        << row["from"] << " -> " << row["to"];
  r = runRadkit(scene + "--threads 0 --out '" + dir.path("z") + "'");
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("--threads"), std::string::npos) << r.output;
}

TEST(FormFactorsCli, BadInput) {
  test::TempDir dir;
  auto r = runRadkit("formfactors '" + dataPath("furnace.json") + "' --ff-samples 0 --out '" +
                     dir.path("a") + "'");
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.output.find("--ff-samples"), std::string::npos) << r.output;
  r = runRadkit("formfactors '" + dataPath("cornell-box.json") +
                "' --patches 5000 --memory-budget 1KiB --out '" + dir.path("b") + "'");
  EXPECT_NE(r.exitCode, 0);
  for (const char* option : {"--memory-budget", "--ff-storage float"})
    EXPECT_NE(r.output.find(option), std::string::npos) << r.output;
  r = runRadkit("formfactors '" + dataPath("furnace.json") + "' --ff nonsense --out '" +
                dir.path("c") + "'");
  EXPECT_NE(r.exitCode, 0);
  for (const char* name : {"a", "b", "c"}) EXPECT_FALSE(fs::exists(dir.path(name))) << name;
  // One patch: nothing to see, F = 0, and the run still completes.
  std::string one = dir.file(
      "one.json", R"({"materials": {"m": {"reflectance": [0.5,0.5,0.5], "emission": [1,1,1]}},
    "surfaces": [{"name": "only", "material": "m", "polygon": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]]}]})");
  r = runRadkit("run '" + one + "' --max-area 10 --no-render --out '" + dir.path("d") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NEAR(std::stod(readCsv(dir.path("d/surfaces.csv"))[0]["b_r_W_m2"]), 1.0, 1e-12);  // B = E
}

TEST(SolversCli, FurnaceEverySolver) {
  test::TempDir dir;
  // Furnace: B = E/(1 - rho) = 2 on every patch for every solver (docs/oracles.md).
  auto r = runRadkit("solvers '" + dataPath("furnace.json") + "' --max-area 0.05 --out '" +
                     dir.path("f") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  json report = readJson(dir.path("f/report.json"));
  ASSERT_EQ(report["solvers"].size(), 5u);
  for (const json& s : report["solvers"]) {
    std::string name = s["solver"];
    SCOPED_TRACE(name);
    EXPECT_TRUE(s["converged"].get<bool>()) << s["reason"];
    for (const json& m : s["milestones"]) EXPECT_TRUE(m["reached"].get<bool>());
    // Cube form factors are exact to ~1e-6 in row sums, which bounds B's error by ~2e-6·B/(1-rho).
    for (auto& row : readCsv(dir.path("f/solution-" + name + ".csv")))
      EXPECT_NEAR(std::stod(row["b_g_W_m2"]), 2.0, 1e-4);
  }
  EXPECT_TRUE(fs::exists(dir.path("f/convergence.png")));
  auto rows = readCsv(dir.path("f/convergence.csv"));
  ASSERT_FALSE(rows.empty());
  EXPECT_EQ(rows.front().size(), 6u);
}

TEST(RunCli, CornellBoxEveryOutput) {
  test::TempDir dir;
  auto r =
      runRadkit("run '" + dataPath("cornell-box.json") +
                "' --patches 400 --photometric --size 128x128 --out '" + dir.path("run") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("energy balance"), std::string::npos);
  for (const char* f : {"patches.csv", "surfaces.csv", "surface_formfactors.csv", "radiosity.vtp",
                        "convergence.csv", "convergence.png", "report.json", "render.png",
                        "formfactors.png", "formfactors.bin"})
    EXPECT_TRUE(fs::exists(dir.path(std::string("run/") + f))) << f;
  EXPECT_FALSE(fs::exists(dir.path("run/formfactors.mtx")));
  for (auto& row : readCsv(dir.path("run/patches.csv")))
    for (const char* c : {"b_r_W_m2", "b_g_W_m2", "b_b_W_m2"}) {
      double b = std::stod(row[c]);
      ASSERT_TRUE(std::isfinite(b) && b >= 0) << row["id"];
    }
  json report = readJson(dir.path("run/report.json"));
  // Light leaves through the open front, so the balance is emitted = absorbed + escaped.
  EXPECT_LT(report["energy_balance"]["relative_imbalance"].get<double>(), 1e-3);
  auto surfaces = readCsv(dir.path("run/surfaces.csv"));
  ASSERT_EQ(surfaces.size(), 8u);
  for (auto& s : surfaces) EXPECT_GT(std::stod(s["illuminance_lux"]), 0) << s["surface"];
}

TEST(RunCli, CornellBoxRenderLayout) {
  test::TempDir dir;
  auto r = runRadkit("run '" + dataPath("cornell-box.json") +
                     "' --patches 800 --size 128x128 --out '" + dir.path("run") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  Canvas img = readPng(dir.path("run/render.png"));
  ASSERT_EQ(img.width(), 128);
  // Mean colour of a region given as fractions of the image.
  // Mean linear colour of a region given as fractions of the image (sRGB decoded).
  auto linear = [](int v) {
    double c = v / 255.0;
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
  };
  auto mean = [&](double x0, double y0, double x1, double y1) {
    double s[3] = {0, 0, 0};
    int n = 0;
    for (int y = int(y0 * img.height()); y < int(y1 * img.height()); ++y)
      for (int x = int(x0 * img.width()); x < int(x1 * img.width()); ++x, ++n) {
        Rgb8 c = img.at(x, y);
        s[0] += linear(c.r), s[1] += linear(c.g), s[2] += linear(c.b);
      }
    return std::array<double, 3>{s[0] / n, s[1] / n, s[2] / n};
  };
  // Direct light alone gives the walls ρ·E: red 0.63·17 : 0.065·12 (ratio 13.7), green
  // 0.45·12 : 0.14·17 (ratio 2.3); interreflection from the white walls pulls both down.
  auto left = mean(0.03, 0.3, 0.15, 0.6), right = mean(0.85, 0.3, 0.97, 0.6);
  EXPECT_GT(left[0], 4 * left[1]) << "red wall on the viewer's left";
  EXPECT_GT(right[1], 1.5 * right[0]) << "green wall on the viewer's right";
  // Ceiling beside the light against the ceiling's far corners.
  auto y = [](std::array<double, 3> c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; };
  double nearLight = y(mean(0.3, 0.16, 0.4, 0.19));
  double corner = y(mean(0.18, 0.01, 0.24, 0.05));
  EXPECT_GT(nearLight, corner * 1.1);
}

TEST(RunCli, PresetAndExplicitOptions) {
  test::TempDir dir;
  // The draft preset fixes the mesh at about 1000 patches; an explicit --patches wins over it.
  auto r = runRadkit("run --preset draft --no-render --out '" + dir.path("a") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  json a = readJson(dir.path("a/report.json"));
  EXPECT_EQ(a["preset"]["name"], "draft");
  EXPECT_NEAR(a["mesh"]["patches"].get<double>(), 1000, 50);
  r = runRadkit("run --preset draft --patches 200 --no-render --out '" + dir.path("b") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NEAR(readJson(dir.path("b/report.json"))["mesh"]["patches"].get<double>(), 200, 20);
  EXPECT_NE(runRadkit("run --preset turbo --out '" + dir.path("c") + "'").exitCode, 0);
  EXPECT_FALSE(fs::exists(dir.path("c")));
}

// The large preset runs the hierarchical method; a disagreeing --method, a dense-only option or
// another command with it is refused before anything is written.
TEST(RunCli, LargePresetRunsHierarchical) {
  test::TempDir dir;
  auto r = runRadkit("run --preset large --no-render --out '" + dir.path("a") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  json a = readJson(dir.path("a/report.json"));
  EXPECT_EQ(a["method"], "hierarchical");
  EXPECT_EQ(a["preset"]["name"], "large");
  EXPECT_GT(a["hierarchy"]["links"].get<double>(), 0);
  r = runRadkit("run --preset large --method dense --out '" + dir.path("b") + "'");
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.output.find("--method dense"), std::string::npos) << r.output;
  r = runRadkit("run --preset large --patches 200 --out '" + dir.path("c") + "'");
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.output.find("--patches"), std::string::npos) << r.output;
  r = runRadkit("formfactors '" + dataPath("cornell-box.json") + "' --preset large --out '" +
                dir.path("d") + "'");
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.output.find("only `radkit run`"), std::string::npos) << r.output;
  for (const char* d : {"b", "c", "d"}) EXPECT_FALSE(fs::exists(dir.path(d))) << d;
}

TEST(RunCli, AdaptiveStaysInBudgetAndBalancesEnergy) {
  test::TempDir dir;
  auto r = runRadkit("run '" + dataPath("cube-one-emitter.json") +
                     "' --adaptive --patches 24 --adaptive-max-patches 150 "
                     "--tol 1e-9 --no-render --out '" +
                     dir.path("a") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  json j = readJson(dir.path("a/report.json"));
  ASSERT_GE(j["adaptive"]["rounds"].size(), 2u);
  EXPECT_LE(j["mesh"]["patches"].get<int>(), 150);
  EXPECT_GT(j["mesh"]["patches"].get<int>(), 24);
  // Closed cube: nothing escapes and emitted = absorbed up to F's row-sum deviation
  // (docs/oracles.md), on a mesh with T-junctions.
  EXPECT_LT(j["energy_balance"]["relative_imbalance"].get<double>(), 1e-4);
  EXPECT_LT(j["energy_balance"]["escaped_W"][1].get<double>(),
            1e-4 * j["energy_balance"]["emitted_W"][1].get<double>());
}

TEST(BenchCli, SolverPrintsOneJsonObject) {
  auto r = runRadkit("bench solver --n 256 --repetitions 1 --threads 1");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  json j = json::parse(r.output);
  EXPECT_EQ(j["threads"].get<int>(), 1);
  EXPECT_GT(j["ratio"]["jacobi"].get<double>(), 0);
  EXPECT_GT(j["ratio"]["gauss_seidel"].get<double>(), 0);
  EXPECT_GT(j["reference"]["triad_bytes_per_second"].get<double>(), 0);
}

}  // namespace
}  // namespace radkit
