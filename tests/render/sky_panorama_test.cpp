// sky.pfm's panorama: its layout against the scene's compass and its light against closed
// forms of the horizontal irradiance.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "geometry/scene_loader.h"
#include "render/hdr_io.h"
#include "render/sky_panorama.h"
#include "tests/common/test_util.h"

namespace radkit {
namespace {

/// Irradiance on a plane facing `normal`, summed over the panorama's pixels (cos⁺ dω).
Vec3 panoramaIrradiance(const RadianceImage& p, const SkyModel& sky, const Vec3& normal) {
  Vec3 sum;
  for (int y = 0; y < p.height; ++y) {
    const double top = (0.5 - double(y) / p.height) * M_PI;
    const double bottom = (0.5 - double(y + 1) / p.height) * M_PI;
    const double omega = 2 * M_PI / p.width * (std::sin(top) - std::sin(bottom));
    for (int x = 0; x < p.width; ++x) {
      const Vec3 d = panoramaDirection(sky, (x + 0.5) / p.width, (y + 0.5) / p.height);
      sum += p.radiance[std::size_t(y) * p.width + x] * (std::max(0.0, dot(d, normal)) * omega);
    }
  }
  return sum;
}

SkyDescription zUpSky() {
  SkyDescription d;
  d.up = {0, 0, 1};
  d.north = {0, 1, 0};
  return d;
}

TEST(SkyPanorama, ColumnsFollowTheCompassAndRowsTheElevation) {
  // A y-up scene whose north is −z: east is then +x (east = north × up).
  SkyDescription d;
  d.parameters = Params({{"radiance", 1.0}});
  d.up = {0, 1, 0};
  d.north = {0, 0, -1};
  const SkyModel sky(d);
  auto near = [](const Vec3& a, const Vec3& b) { return length(a - b) < 1e-12; };
  EXPECT_TRUE(near(panoramaDirection(sky, 0.0, 0.5), {0, 0, -1}));   // north on the horizon,
  EXPECT_TRUE(near(panoramaDirection(sky, 1.0, 0.5), {0, 0, -1}));   // at both edges
  EXPECT_TRUE(near(panoramaDirection(sky, 0.25, 0.5), {1, 0, 0}));   // east
  EXPECT_TRUE(near(panoramaDirection(sky, 0.5, 0.5), {0, 0, 1}));    // south
  EXPECT_TRUE(near(panoramaDirection(sky, 0.75, 0.5), {-1, 0, 0}));  // west
  EXPECT_TRUE(near(panoramaDirection(sky, 0.3, 0.0), {0, 1, 0}));    // the zenith: top row
  EXPECT_TRUE(near(panoramaDirection(sky, 0.3, 1.0), {0, -1, 0}));
  const Vec3 up30 = panoramaDirection(sky, 0.25, 1.0 / 3);  // east, 30° up
  EXPECT_NEAR(up30.y, 0.5, 1e-12);
  EXPECT_NEAR(up30.x, std::sqrt(0.75), 1e-12);
}

TEST(SkyPanorama, UniformSkyGivesPiLAndTheSunKeepsItsIrradianceAndPlace) {
  // Uniform sky L: E_h = πL. The sun at elevation 30°, azimuth 120° (clockwise from north),
  // normal irradiance E_n: E_h = E_n sin 30° more, and on a plane facing the sun E_n more.
  SkyDescription d = zUpSky();
  const Vec3 radiance{1, 2, 3};
  d.parameters = Params();
  d.parameters.set("radiance", radiance);
  d.sun = true;
  d.sunElevationDeg = 30;
  d.sunAzimuthDeg = 120;
  d.sunIrradiance = {100, 200, 300};
  const SkyModel sky(d);
  const RadianceImage p = skyPanorama(sky, 512);
  ASSERT_EQ(p.width, 512);
  ASSERT_EQ(p.height, 256);
  // The disc sits in the pixel holding its centre, whose centre is up to half a row (0.35°)
  // off in elevation: sin e moves by cos 30° · that much.
  const Vec3 e = panoramaIrradiance(p, sky, {0, 0, 1});
  const double rowHalf = M_PI / p.height / 2;
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(
        e[c], M_PI * radiance[c] + d.sunIrradiance[c] * 0.5,
        1e-4 * M_PI * radiance[c] + d.sunIrradiance[c] * std::cos(30 * M_PI / 180) * rowHalf);
  // The brightest pixel lies at the sun's bearing and elevation, within a pixel (0.7°).
  std::size_t brightest = 0;
  for (std::size_t i = 0; i < p.radiance.size(); ++i)
    if (p.radiance[i].x > p.radiance[brightest].x) brightest = i;
  const double u = (brightest % p.width + 0.5) / p.width,
               v = (brightest / p.width + 0.5) / p.height;
  EXPECT_NEAR(360 * u, 120, 360.0 / p.width);
  EXPECT_NEAR(90 - 180 * v, 30, 180.0 / p.height);
  // Towards the sun: its normal irradiance plus the sky's half space, πL.
  const Vec3 toSun = sky.sunDirection();
  EXPECT_NEAR(panoramaIrradiance(p, sky, toSun).x, 100 + M_PI, 1e-2 * (100 + M_PI));
}

TEST(SkyPanorama, CieOvercastSkyGivesSevenPiLzOverNineAndItsGroundGlow) {
  // CIE standard overcast sky L(θ) = L_z (1 + 2 cos θ)/3 (Moon and Spencer 1942, CIE S 011):
  // E_h = 7πL_z/9. Below the horizon the ground glows at ρ_g E_h/π, so a downward plane gets
  // ρ_g E_h.
  SkyDescription d = zUpSky();
  d.model = "cie-overcast";
  d.parameters = Params({{"zenith_radiance", 3.0}});
  d.groundReflectance = 0.2;
  const SkyModel sky(d);
  const RadianceImage p = skyPanorama(sky, 1024);
  EXPECT_NEAR(panoramaIrradiance(p, sky, {0, 0, 1}).x, 7 * M_PI * 3 / 9, 1e-4 * 7 * M_PI * 3 / 9);
  EXPECT_NEAR(panoramaIrradiance(p, sky, {0, 0, -1}).x, 0.2 * 7 * M_PI * 3 / 9,
              1e-4 * 7 * M_PI * 3 / 9);
  // No sun: nothing is added anywhere.
  EXPECT_NEAR(p.radiance[0].x, 3.0, 1e-4);  // the top row sits within 0.18° of the zenith
}

// `radkit run` under a sky, dense and hierarchical, writes the scene's sky as sky.pfm and the
// frame that places it in report.json; a run without a sky writes neither.
TEST(SkyPanorama, RunWritesTheScenesSkyForTheViewer) {
  test::TempDir dir;
  const std::string scene = test::dataPath("street-canyon-sunny.json");
  const Scene loaded = loadScene(scene);
  const RadianceImage expected = skyPanorama(SkyModel(*loaded.sky));
  for (const std::string method : {" --patches 200", " --method hierarchical"}) {
    const std::string out = dir.path(method.find("hier") == std::string::npos ? "dense" : "hier");
    const test::RunResult r =
        test::runRadkit("run " + scene + " --no-render" + method + " --out " + out, 600);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const RadianceImage written = readPfm(out + "/sky.pfm");
    ASSERT_EQ(written.width, kSkyPanoramaWidth);
    ASSERT_EQ(written.height, kSkyPanoramaWidth / 2);
    double worst = 0;  // PFM holds floats
    for (std::size_t i = 0; i < written.radiance.size(); ++i)
      worst = std::max(worst, length(written.radiance[i] - expected.radiance[i]) /
                                  std::max(1e-30, length(expected.radiance[i])));
    EXPECT_LT(worst, 1e-6) << method;
    nlohmann::json report;
    std::ifstream(out + "/report.json") >> report;
    const nlohmann::json& p = report.at("sky_panorama");
    EXPECT_EQ(p.at("file"), "sky.pfm");
    EXPECT_EQ(p.at("up"), nlohmann::json::array({0.0, 0.0, 1.0})) << method;
    EXPECT_EQ(p.at("north"), nlohmann::json::array({0.0, 1.0, 0.0})) << method;
    EXPECT_EQ(p.at("east"), nlohmann::json::array({1.0, 0.0, 0.0})) << method;
  }
  const test::RunResult r =
      test::runRadkit("run " + test::dataPath("parallel-squares.json") +
                          " --patches 50 --no-render --out " + dir.path("none"),
                      300);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir.path("none") + "/sky.pfm"));
}

}  // namespace
}  // namespace radkit
