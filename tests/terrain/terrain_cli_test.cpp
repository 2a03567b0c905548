// `radkit terrain` and `radkit sky` end to end: the files they promise, a terrain run through
// hierarchical radiosity under its sky, and refusals that leave nothing behind.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "tests/common/test_util.h"

namespace radkit {
namespace {

namespace fs = std::filesystem;

nlohmann::json readJson(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

TEST(TerrainCli, GeneratesASceneThatRadiosityRunsUnderItsSky) {
  test::TempDir dir;
  const std::string out = dir.path("land");
  test::RunResult r = test::runRadkit(
      "terrain --resolution 33 --seed 4 --sky cie-overcast --sky-samples 16 --format ply "
      "--image --image-width 32 --image-height 16 --out " +
          out,
      300);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (const char* f : {"terrain.json", "heightmap.png", "report.json", "landscape-march.pfm",
                        "landscape-embree.png", "landscape-difference.png"})
    EXPECT_TRUE(fs::exists(out + "/" + f)) << f;
  const nlohmann::json report = readJson(out + "/report.json");
  EXPECT_EQ(report["triangles"].get<int>(), 2 * 32 * 32);
  EXPECT_EQ(report["landscape"]["hit_mismatch_pixels"].get<double>(), 0.0);
  // The same seed gives the same meshes, byte for byte.
  ASSERT_EQ(test::runRadkit("terrain --resolution 33 --seed 4 --sky cie-overcast --format ply "
                            "--sky-samples 16 --out " +
                                dir.path("again"),
                            300)
                .exitCode,
            0);
  for (const char* part : {"terrain-grass.ply", "terrain-rock.ply", "terrain-snow.ply"}) {
    if (!fs::exists(out + "/" + part)) continue;
    std::ifstream a(out + "/" + part), b(dir.path("again") + "/" + part);
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(a), {}),
              std::string(std::istreambuf_iterator<char>(b), {}))
        << part;
  }
  r = test::runRadkit(
      "run " + out + "/terrain.json --method hierarchical --no-render --out " + dir.path("run"),
      300);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const auto rows = test::readCsv(dir.path("run") + "/surfaces.csv");
  ASSERT_FALSE(rows.empty());
  for (const auto& row : rows) {
    const double svf = std::stod(row.at("sky_view_factor"));
    EXPECT_GT(svf, 0.3) << row.at("surface");  // a terrain sees most of its sky
    EXPECT_LE(svf, 1.0);
    EXPECT_GT(std::stod(row.at("illuminance_lux")), 0);
  }
  const nlohmann::json run = readJson(dir.path("run") + "/report.json");
  EXPECT_EQ(run["daylight"]["sky"], "cie-overcast");
}

TEST(TerrainCli, RefusesBadOptionsAndWritesNothing) {
  test::TempDir dir;
  for (const char* bad : {"--resolution 1", "--type perlin", "--lacunarity nan", "--format stl"}) {
    const test::RunResult r =
        test::runRadkit(std::string("terrain ") + bad + " --out " + dir.path("x"), 60);
    EXPECT_NE(r.exitCode, 0) << bad;
    EXPECT_FALSE(fs::exists(dir.path("x"))) << bad;
  }
}

TEST(SkyCli, WritesImagesAndRefusesBadSuns) {
  test::TempDir dir;
  const std::string out = dir.path("sky");
  test::RunResult r =
      test::runRadkit("sky --size 24 --elevation 20 --projection all --exr --out " + out, 300);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (const char* p : {"fisheye", "panorama", "camera"}) {
    EXPECT_TRUE(fs::exists(out + "/sky-" + std::string(p) + ".pfm")) << p;
    EXPECT_TRUE(fs::exists(out + "/sky-" + std::string(p) + ".png")) << p;
    EXPECT_TRUE(fs::exists(out + "/sky-" + std::string(p) + ".exr")) << p;
  }
  EXPECT_TRUE(fs::exists(out + "/report.json"));
  r = test::runRadkit("sky --elevation 95 --out " + dir.path("bad"), 60);
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.output.find("elevation"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir.path("bad")));
}

}  // namespace
}  // namespace radkit
