// radkit render and radkit brdf end to end: files written, JSON printed, bad input refused.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <algorithm>

#include <nlohmann/json.hpp>

#include "render/hdr_io.h"
#include "tests/common/test_util.h"
#include "util/canvas.h"

namespace radkit {
namespace {

TEST(RenderCommand, WritesPngAndPfm) {
  test::TempDir dir;
  test::RunResult r = test::runRadkit("render --shading path-trace --spp 2 --size 24x16 --out " +
                                      dir.path("a.png"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  Canvas png = readPng(dir.path("a.png"));
  EXPECT_EQ(png.width(), 24);
  EXPECT_EQ(png.height(), 16);
  r = test::runRadkit("render --shading path-trace --spp 1 --size 8x8 --tonemap filmic --out " +
                      dir.path("b.pfm"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  RadianceImage hdr = readPfm(dir.path("b.pfm"));
  EXPECT_EQ(hdr.width, 8);
  r = test::runRadkit("render --shading cook-torrance --patches 60 --spp 1 --size 8x8 --out " +
                      dir.path("c.png"));
  EXPECT_EQ(r.exitCode, 0) << r.output;
  r = test::runRadkit("render --shading photon-map --patches 60 --photons 2000 --size 8x8 --out " +
                      dir.path("d.png"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(readPng(dir.path("d.png")).width(), 8);
}

TEST(RenderCommand, DaylightScenesRenderInEveryMode) {
  // The path tracer lights a sky scene (its image was black before it knew the sky; the
  // closed forms are in daylight_path_test.cpp and photon/tracer_test.cpp), and so do the
  // modes over the radiosity solution and photon mapping.
  test::TempDir dir;
  const std::string scene = "'" + test::dataPath("street-canyon.json") + "'";
  test::RunResult r = test::runRadkit(
      "render " + scene + " --shading path-trace --spp 2 --size 16x12 --out " + dir.path("pt.pfm"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const RadianceImage img = readPfm(dir.path("pt.pfm"));
  // Nearly every pixel sees the street, a wall or the sky, all lit; below the horizon, past
  // the street's end, the ground is black.
  std::size_t lit = 0;
  for (const Vec3& v : img.radiance) lit += v.y > 0;
  EXPECT_GT(lit, img.radiance.size() * 9 / 10);
  for (const char* mode : {"final-gather", "phong", "photon-map"}) {
    r = test::runRadkit("render " + scene + " --shading " + mode +
                        " --patches 200 --spp 1 --photons 20000 --gather-rays 4 --size 8x8 --out " +
                        dir.path(std::string(mode) + ".pfm"));
    ASSERT_EQ(r.exitCode, 0) << mode << ": " << r.output;
    std::size_t modeLit = 0;
    for (const Vec3& v : readPfm(dir.path(std::string(mode) + ".pfm")).radiance) modeLit += v.y > 0;
    EXPECT_GT(modeLit, 8u * 8u * 9 / 10) << mode;
  }
  r = test::runRadkit("photons " + scene + " --photons 20000 --out " + dir.path("photons"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  std::ifstream in(dir.path("photons") + "/report.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  EXPECT_GT(report["photons"]["sky_and_sun_power"][1].get<double>(), 0.0);
}

TEST(RenderCommand, ComparesWithReferenceRenders) {
  // Two independent path-traced references, then a final gather measured against them.
  test::TempDir dir;
  for (const char* seed : {"1", "2"}) {
    test::RunResult r = test::runRadkit(std::string("render --spp 4 --size 16x16 --seed ") + seed +
                                        " --out " + dir.path(std::string("ref") + seed + ".pfm"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
  }
  test::RunResult r = test::runRadkit(
      "render --shading final-gather --patches 60 --spp 2 --sampler stratified --size 16x16"
      " --reference " +
      dir.path("ref1.pfm") + " --reference " + dir.path("ref2.pfm") + " --report " +
      dir.path("r.json") + " --out " + dir.path("fg.pfm"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("rmse all"), std::string::npos) << r.output;
  std::ifstream in(dir.path("r.json"));
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["shading"], "final-gather");
  EXPECT_EQ(j["regions"][0]["region"], "all");
  EXPECT_EQ(j["regions"][0]["pixels"], 256);
  EXPECT_GT(j["regions"][0]["reference_noise"].get<double>(), 0);
  r = test::runRadkit(
      "render --shading radiosity --smooth --crease-angle 45 --smooth-error 0.2 --patches 60 "
      "--size 16x16"
      " --reference " +
      dir.path("ref1.pfm") + " --out " + dir.path("s.pfm"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("its own noise is not subtracted"), std::string::npos) << r.output;
  r = test::runRadkit("render --spp 1 --size 8x8 --reference " + dir.path("ref1.pfm") + " --out " +
                      dir.path("x.pfm"));
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.output.find("--size"), std::string::npos) << r.output;
}

TEST(RenderCommand, RefusesBadInput) {
  test::TempDir dir;
  test::RunResult r = test::runRadkit("render --size 12by4 --out " + dir.path("a.png"));
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.output.find("WIDTHxHEIGHT"), std::string::npos) << r.output;
  EXPECT_NE(test::runRadkit("render --shading toon --out " + dir.path("a.png")).exitCode, 0);
  std::string dark = dir.file("dark.json", R"({"materials": {"m": {"reflectance": [0.5,0.5,0.5]}},
    "surfaces": [{"name": "a", "material": "m", "polygon": [[0,0,0],[1,0,0],[1,1,0]]}]})");
  r = test::runRadkit("render '" + dark + "' --shading photon-map --size 8x8 --out " +
                      dir.path("e.png"));
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.output.find("no surface emits"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir.path("a.png")) ||
               std::filesystem::exists(dir.path("e.png")));
}

TEST(BrdfCommand, PrintsAlbedo) {
  test::RunResult r = test::runRadkit("brdf --model cook-torrance --alpha 1 --mu 1");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  nlohmann::json j = nlohmann::json::parse(r.output);
  EXPECT_NEAR(j["E"].get<double>(), 0.307, 1e-3);  // docs/oracles.md
  EXPECT_LT(j["E_avg"].get<double>(), 1);
  r = test::runRadkit(
      "brdf --model cook-torrance --alpha 0.6 --mu 0.3 --g separable --compensated");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  j = nlohmann::json::parse(r.output);
  EXPECT_NEAR(j["E"].get<double>(), 1, 3e-3);
  EXPECT_NEAR(j["E_avg"].get<double>(), 1, 3e-3);
  r = test::runRadkit("brdf --table");
  ASSERT_EQ(r.exitCode, 0);
  EXPECT_EQ(r.output.rfind("alpha,mu,E\n", 0), 0u);
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1 + 10 * 20);
}

TEST(BrdfCommand, RefusesBadInput) {
  for (const char* args :
       {"brdf --alpha 0 --mu 0.5", "brdf --alpha 1.5 --mu 0.5", "brdf --alpha 0.5 --mu 0",
        "brdf --alpha 0.5 --mu 1.01", "brdf --model phong", "brdf --g beckmann"}) {
    test::RunResult r = test::runRadkit(args);
    EXPECT_NE(r.exitCode, 0) << args;
    EXPECT_FALSE(r.output.empty()) << args;
  }
}

}  // namespace
}  // namespace radkit
