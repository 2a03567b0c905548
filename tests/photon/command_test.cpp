// `radkit photons` end to end: the files it writes, what they hold, determinism, and bad input
// failing with a clear message and no output.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "tests/common/test_util.h"
#include "util/canvas.h"

namespace radkit {
namespace {

namespace fs = std::filesystem;
using test::dataPath;
using test::runRadkit;

std::string readText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Rows of a CSV file keyed by its first column.
std::map<std::string, std::map<std::string, std::string>> readCsvByKey(const std::string& path) {
  std::map<std::string, std::map<std::string, std::string>> rows;
  std::ifstream in(path);
  std::string header;
  std::getline(in, header);
  const std::string key = header.substr(0, header.find(','));
  for (auto& row : test::readCsv(path)) rows[row[key]] = row;
  return rows;
}

const std::string kQuick =
    " --photons 100000 --gather 8 --size 64x64 --bench-rays 10000 --max-area 0.05";

TEST(PhotonsCommand, ConstructWritesEveryFile) {
  test::TempDir dir;
  const std::string out = dir.path("spot");
  auto r =
      runRadkit("photons '" + dataPath("mirror-spot.json") + "'" + kQuick + " --out '" + out + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (const char* f : {"patches.csv", "surfaces.csv", "photonmap.png", "caustics.png",
                        "comparison.csv", "difference.png", "report.json"})
    EXPECT_TRUE(fs::exists(out + "/" + f)) << f;
  EXPECT_EQ(
      readText(out + "/patches.csv").rfind("id,surface,area_m2,cx_m,cy_m,cz_m,nx,ny,nz,rho_r", 0),
      0u);
  EXPECT_EQ(
      readText(out + "/surfaces.csv").rfind("surface,area_m2,b_r_W_m2,b_g_W_m2,b_b_W_m2\n", 0), 0u);
  nlohmann::json report = nlohmann::json::parse(readText(out + "/report.json"));
  EXPECT_EQ(report["photons"]["emitted"], 100000);
  EXPECT_GT(report["photons"]["caustic"].get<double>(), 0);
  EXPECT_NEAR(report["photons"]["emitted_power"][0].get<double>(),
              report["photons"]["total_power"][0].get<double>(), 1e-9);
  for (const char* rate : {"photons_per_second", "embree_closest_hit_rays_per_second",
                           "kd_build_photons_per_second", "kd_queries_per_second"})
    EXPECT_GT(report["rates"][rate].get<double>(), 0) << rate;
  EXPECT_GT(report["memory"]["photon_map_bytes"].get<double>(), 0);
  // The target gets about twice the light radiosity gives it (the mirror's spot): far beyond
  // its standard error.
  auto rows = readCsvByKey(out + "/comparison.csv");
  ASSERT_TRUE(rows.count("target"));
  EXPECT_GT(std::stod(rows["target"]["z_r"]), 5);
  EXPECT_GT(std::stod(rows["target"]["rel_diff_r"]), 0.5);
  Canvas image = readPng(out + "/photonmap.png");
  EXPECT_EQ(image.width(), 64);
}

TEST(PhotonsCommand, ExactSameOutputForSameSeed) {
  test::TempDir dir;
  const std::string args =
      "photons '" + dataPath("cornell-box-specular.json") +
      "' --photons 20000 --gather 4 --size 32x32 --bench-rays 0 --no-radiosity --patches 200";
  ASSERT_EQ(runRadkit(args + " --out '" + dir.path("a") + "'").exitCode, 0);
  ASSERT_EQ(runRadkit(args + " --out '" + dir.path("b") + "'").exitCode, 0);
  EXPECT_EQ(readText(dir.path("a/patches.csv")), readText(dir.path("b/patches.csv")));
  EXPECT_FALSE(fs::exists(dir.path("a/comparison.csv")));
  ASSERT_EQ(runRadkit(args + " --seed 2 --out '" + dir.path("c") + "'").exitCode, 0);
  EXPECT_NE(readText(dir.path("a/patches.csv")), readText(dir.path("c/patches.csv")));
}

TEST(PhotonsCommand, ExactCompareReadsRunFolder) {
  test::TempDir dir;
  fs::create_directories(dir.path("run"));
  dir.file("run/surfaces.csv",
           "surface,area_m2,b_r_W_m2,b_g_W_m2,b_b_W_m2\nlamp,0.0001,10000,10000,10000\nmirror,0.04,"
           "0,0,0\ntarget,0."
           "01,0.25,0.25,0.25\n"
           "wall,2.39,0,0,0\n");
  auto r = runRadkit("photons '" + dataPath("mirror-spot.json") + "'" + kQuick + " --compare '" +
                     dir.path("run") + "' --out '" + dir.path("out") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  auto rows = readCsvByKey(dir.path("out/comparison.csv"));
  EXPECT_EQ(std::stod(rows["target"]["radiosity_b_g_W_m2"]), 0.25);
  EXPECT_EQ(std::stod(rows["mirror"]["rel_diff_r"]), 0);  // zero reference: reported as 0
}

TEST(PhotonsCommand, ConstructBadInputFailsWithoutOutput) {
  test::TempDir dir;
  const std::string spot = " '" + dataPath("mirror-spot.json") + "'" + kQuick;
  struct Case {
    std::string args, expect;
  } cases[] = {
      {spot + " --compare '" + dir.path("nowhere") + "'", "--compare"},
      {spot + " --photons 0", "--photons"},
      {spot + " --k 1", "--k"},
      {spot + " --filter box", "--filter"},
      {" '" + dir.file("dark.json", R"({"materials": {"g": {"reflectance": [0.5,0.5,0.5]}},
        "surfaces": [{"name": "a", "material": "g", "polygon": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]]}]})") +
           "' --photons 10",
       "emission"},
  };
  fs::create_directories(dir.path("other"));
  dir.file("other/surfaces.csv",
           "surface,area_m2,b_r_W_m2,b_g_W_m2,b_b_W_m2\nfloor,1,0.1,0.1,0.1\n");
  for (const Case& c : cases) {
    auto r = runRadkit("photons" + c.args + " --out '" + dir.path("out") + "'");
    EXPECT_NE(r.exitCode, 0) << c.args;
    EXPECT_NE(r.output.find(c.expect), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir.path("out"))) << c.args;
  }
  auto r = runRadkit("photons" + spot + " --compare '" + dir.path("other") + "' --out '" +
                     dir.path("out") + "'");
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.output.find("Fix:"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir.path("out")));
}

}  // namespace
}  // namespace radkit
