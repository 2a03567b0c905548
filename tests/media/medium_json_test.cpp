// Volume scene files (media/medium_json.h): the shipped data/clouds/ files read back as written,
// a homogeneous slab from a file against Beer-Lambert, every refusal naming the file and the
// key, and `radkit clouds --scene` against the same run from the command line's defaults.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "geometry/scene_loader.h"
#include "media/medium_json.h"
#include "media/volume_tracer.h"
#include "tests/common/test_util.h"

namespace radkit::media {
namespace {

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(VolumeScene, CumulusFileIsTheCloudsDefaults) {
  const VolumeScene scene = loadVolumeScene(test::dataPath("clouds/cumulus.json"));
  EXPECT_EQ(scene.kind, "cloud-layer");
  const auto* layer = dynamic_cast<const CloudLayer*>(scene.medium.get());
  ASSERT_NE(layer, nullptr);
  const CloudLayerSettings& s = layer->settings();
  const CloudLayerSettings defaults;
  EXPECT_EQ(s.bottom, defaults.bottom);
  EXPECT_EQ(s.top, defaults.top);
  EXPECT_EQ(s.size, defaults.size);
  EXPECT_EQ(s.coverage, defaults.coverage);
  EXPECT_EQ(s.cloudType, defaults.cloudType);
  EXPECT_EQ(s.extinction, defaults.extinction);
  EXPECT_EQ(s.albedo, defaults.albedo);
  EXPECT_EQ(s.shapePeriod, defaults.shapePeriod);
  EXPECT_EQ(s.detailPeriod, defaults.detailPeriod);
  EXPECT_EQ(s.detailErosion, defaults.detailErosion);
  EXPECT_EQ(s.weatherPeriod, defaults.weatherPeriod);
  EXPECT_EQ(s.shapeSize, defaults.shapeSize);
  EXPECT_EQ(s.detailSize, defaults.detailSize);
  EXPECT_EQ(s.seed, defaults.seed);
  EXPECT_EQ(layer->phase().name(), "henyey-greenstein");
  EXPECT_DOUBLE_EQ(layer->phase().meanCosine(), 0.86);
  ASSERT_TRUE(scene.sunElevationDeg && scene.sunAzimuthDeg);
  EXPECT_EQ(*scene.sunElevationDeg, 40);
  EXPECT_EQ(*scene.sunAzimuthDeg, 150);
  ASSERT_TRUE(scene.camera);
  EXPECT_EQ(scene.camera->fovDeg, 70);
  const Vec3 f = normalize(scene.camera->lookAt - scene.camera->position);
  EXPECT_NEAR(std::asin(f.z) * 180 / M_PI, 25, 1e-12);
  EXPECT_EQ(scene.groundAlbedo, 0);
}

TEST(VolumeScene, StratusFileGivesLowFlatCloud) {
  const VolumeScene scene = loadVolumeScene(test::dataPath("clouds/stratus.json"));
  const auto* layer = dynamic_cast<const CloudLayer*>(scene.medium.get());
  ASSERT_NE(layer, nullptr);
  const CloudLayerSettings& s = layer->settings();
  EXPECT_EQ(s.cloudType, 0);
  EXPECT_EQ(s.extinction, 0.05);  // OPAC stratus: 0.04-0.06 per metre
  EXPECT_EQ(s.bottom, 500);
  EXPECT_EQ(s.top, 1500);
  EXPECT_EQ(s.coverage, 0.9);
  EXPECT_EQ(s.shapePeriod, CloudLayerSettings().shapePeriod);  // omitted keys: defaults
  EXPECT_DOUBLE_EQ(layer->phase().meanCosine(), 0.86);
  EXPECT_EQ(scene.groundAlbedo, 0.2);
}

TEST(VolumeScene, SlabFileIsAHomogeneousBox) {
  const VolumeScene scene = loadVolumeScene(test::dataPath("clouds/slab.json"));
  EXPECT_EQ(scene.kind, "homogeneous-box");
  const Medium& m = *scene.medium;
  ASSERT_NE(dynamic_cast<const HomogeneousBox*>(&m), nullptr);
  EXPECT_EQ(m.extinction({0, 0, 1050}), 0.01);
  EXPECT_EQ(m.extinction({9999, -9999, 1001}), 0.01);
  EXPECT_EQ(m.extinction({0, 0, 999}), 0);
  EXPECT_EQ(m.extinction({0, 0, 1101}), 0);
  EXPECT_EQ(m.extinction({10001, 0, 1050}), 0);
  EXPECT_EQ(m.albedo(), 0.9);
  EXPECT_EQ(m.phase().name(), "isotropic");
  EXPECT_EQ(m.phase().meanCosine(), 0);
  EXPECT_EQ(m.bounds().lo.z, 1000);
  EXPECT_EQ(m.bounds().hi.z, 1100);
}

TEST(VolumeScene, StatisticalSlabFromAFileFollowsBeerLambert) {
  // Straight up through the 100 m slab: T = exp(−σ_t d) = e^{−1}. Ratio tracking's estimates
  // here are 0 or 1 (σ_t equals the majorant), so their spread gives the standard error.
  const VolumeScene scene = loadVolumeScene(test::dataPath("clouds/slab.json"));
  Rng rng(5, 0, 0);
  const int n = 200000;
  double sum = 0, sum2 = 0;
  for (int i = 0; i < n; ++i) {
    const double t = ratioTrack(*scene.medium, {0, 0, 1.7}, {0, 0, 1}, INFINITY, rng);
    sum += t, sum2 += t * t;
  }
  const double mean = sum / n, se = std::sqrt((sum2 / n - mean * mean) / (n - 1));
  const double exact = std::exp(-0.01 * 100);
  EXPECT_GT(se, 0);
  EXPECT_NEAR(mean, exact, 4 * se) << "ratio tracking " << mean << " ± " << se;
}

TEST(VolumeScene, PhaseObjectParametersReachTheRegistry) {
  const nlohmann::json j = nlohmann::json::parse(R"({"type": "homogeneous-box",
      "min": [0, 0, 0], "max": [1, 1, 1], "extinction": 1,
      "phase": {"name": "double-henyey-greenstein", "g1": 0.8, "g2": -0.3, "w": 0.75}})");
  std::string kind, name, params;
  const auto m = parseMedium(j, "inline.json", &kind, &name, &params);
  EXPECT_EQ(kind, "homogeneous-box");
  EXPECT_EQ(name, "double-henyey-greenstein");
  EXPECT_NEAR(m->phase().meanCosine(), 0.75 * 0.8 + 0.25 * -0.3, 1e-15);
  EXPECT_EQ(m->albedo(), 1);  // the box's default
}

/// The InputError loading `text` from a file called `name` raises ("" when none).
std::string refusal(const test::TempDir& dir, const std::string& name, const std::string& text) {
  const std::string path = dir.file(name, text);
  try {
    loadVolumeScene(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(VolumeScene, RefusesBadInputNamingTheFileAndTheKey) {
  test::TempDir dir;
  const std::string box = R"("type": "homogeneous-box", "min": [0, 0, 0], "max": [1, 1, 1])";
  struct Case {
    const char* name;
    std::string text, key;
    bool fix = true;  ///< the message says how to fix it (the JSON parser's does not)
  };
  const Case cases[] = {
      {"type.json", R"({"medium": {"type": "fog"}})", "fog"},
      {"unknown-key.json", R"({"medium": {"type": "cloud-layer", "colour": 1}})", "colour"},
      {"unknown-top.json", R"({"medium": {"type": "cloud-layer"}, "lights": 1})", "lights"},
      {"coverage.json", R"({"medium": {"type": "cloud-layer", "coverage": 1.5}})", "coverage"},
      {"extinction.json", R"({"medium": {"type": "cloud-layer", "extinction": -0.1}})",
       "extinction"},
      {"box-extinction.json", "{\"medium\": {" + box + ", \"extinction\": -1}}", "extinction"},
      {"top.json", R"({"medium": {"type": "cloud-layer", "bottom": 2000, "top": 2000}})", "top"},
      {"max.json",
       R"({"medium": {"type": "homogeneous-box", "min": [0, 0, 0], "max": [1, 0, 1],
           "extinction": 1}})",
       "max"},
      {"shape-size.json", R"({"medium": {"type": "cloud-layer", "shape_size": 12.5}})",
       "shape_size"},
      {"phase-name.json", R"({"medium": {"type": "cloud-layer", "phase": "fog"}})", "phase"},
      {"phase-param.json",
       R"({"medium": {"type": "cloud-layer", "phase": {"name": "henyey-greenstein", "g": 1.5}}})",
       "\"g\""},
      {"phase-key.json",
       R"({"medium": {"type": "cloud-layer", "phase": {"name": "isotropic", "g": 0.5}}})", "g"},
      {"huge.json", R"({"medium": {"type": "cloud-layer", "extinction": 1e400}})", "extinction"},
      {"malformed.json", R"({"medium": {"type": "cloud-layer",)", "malformed JSON", false},
      {"sun.json", R"({"medium": {"type": "cloud-layer"}, "sun": {"elevation": 95}})", "elevation"},
      {"camera.json",
       R"({"medium": {"type": "cloud-layer"}, "camera": {"position": [0, 0, 1],
           "look_at": [0, 0, 1]}})",
       "look_at"},
      {"fov.json",
       R"({"medium": {"type": "cloud-layer"}, "camera": {"look_at": [0, 1, 2], "fov_deg": 180}})",
       "fov_deg"},
      {"no-medium.json", R"({"sun": {"elevation": 10}})", "medium"},
      {"low-camera.json",
       R"({"medium": {"type": "cloud-layer"}, "ground_albedo": 0.2,
           "camera": {"position": [0, 0, -1], "look_at": [0, 1, 0]}})",
       "camera"},
      {"buried-box.json",
       R"({"medium": {"type": "homogeneous-box", "min": [0, 0, -5], "max": [1, 1, 1],
           "extinction": 0.1}, "ground_albedo": 0.2})",
       "reaches below the ground"},
  };
  for (const Case& c : cases) {
    const std::string message = refusal(dir, c.name, c.text);
    ASSERT_FALSE(message.empty()) << c.name << " was accepted";
    EXPECT_NE(message.find(c.name), std::string::npos) << message;
    EXPECT_NE(message.find(c.key), std::string::npos) << c.name << ": " << message;
    if (c.fix) {
      EXPECT_NE(message.find("Fix:"), std::string::npos) << c.name << ": " << message;
    }
  }
  // The unknown key's message lists what is allowed.
  EXPECT_NE(refusal(dir, "k.json", R"({"medium": {"type": "cloud-layer", "colour": 1}})")
                .find("coverage, cloud_type"),
            std::string::npos);
  const std::string missing = dir.path("missing.json");
  try {
    loadVolumeScene(missing);
    ADD_FAILURE() << "a missing file was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(missing), std::string::npos) << e.what();
  }
}

TEST(CloudsCli, SceneFileOfTheDefaultsGivesTheDefaultImages) {
  test::TempDir dir;
  // Seed 1 is the file's noise seed: without --scene, --seed seeds the noise as well.
  const std::string size = "--width 16 --height 8 --samples 2 --seed 1 ";
  const test::RunResult a =
      test::runRadkit("clouds " + size + "--scene '" + test::dataPath("clouds/cumulus.json") +
                          "' --out " + dir.path("file"),
                      600);
  ASSERT_EQ(a.exitCode, 0) << a.output;
  const test::RunResult b = test::runRadkit("clouds " + size + "--out " + dir.path("cli"), 600);
  ASSERT_EQ(b.exitCode, 0) << b.output;
  for (const char* f : {"clouds-reference.pfm", "clouds-realtime.pfm"}) {
    const std::string x = slurp(dir.path("file") + "/" + f), y = slurp(dir.path("cli") + "/" + f);
    ASSERT_FALSE(x.empty()) << f;
    EXPECT_TRUE(x == y) << f << " differs";
  }
  std::ifstream fa(dir.path("file") + "/report.json"), fb(dir.path("cli") + "/report.json");
  const nlohmann::json ra = nlohmann::json::parse(fa), rb = nlohmann::json::parse(fb);
  EXPECT_EQ(ra["settings"]["medium"], "cloud-layer");
  EXPECT_NE(ra["settings"]["scene"].get<std::string>().find("cumulus.json"), std::string::npos);
  EXPECT_TRUE(rb["settings"]["scene"].is_null());
  ASSERT_EQ(ra["realtime"].size(), rb["realtime"].size());
  for (std::size_t i = 0; i < ra["realtime"].size(); ++i)
    for (const char* k : {"relative_rmse", "relative_bias"})
      EXPECT_EQ(ra["realtime"][i][k], rb["realtime"][i][k]) << i << " " << k;
  for (const char* k : {"sun_irradiance_W_m2", "phase_mean_cosine", "fov_deg", "coverage"})
    EXPECT_EQ(ra["settings"][k], rb["settings"][k]) << k;
  // The file's camera is reported by its direction's elevation, 25° to rounding.
  EXPECT_NEAR(ra["settings"]["camera_elevation_deg"].get<double>(), 25, 1e-12);
}

TEST(CloudsCli, SceneFileOverridesAndRefusals) {
  test::TempDir dir;
  // A homogeneous box works for both methods; --sun-elevation given overrides the file's.
  test::RunResult r = test::runRadkit("clouds --width 8 --height 4 --samples 1 --scene '" +
                                          test::dataPath("clouds/slab.json") +
                                          "' --sun-elevation 60 --out " + dir.path("slab"),
                                      600);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  std::ifstream in(dir.path("slab") + "/report.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  EXPECT_EQ(report["settings"]["medium"], "homogeneous-box");
  EXPECT_EQ(report["settings"]["sun_elevation_deg"], 60);
  EXPECT_EQ(report["settings"]["sun_azimuth_deg"], 150);  // the file's
  EXPECT_EQ(report["settings"]["extinction_per_m"], 0.01);
  for (const auto& row : report["realtime"])
    EXPECT_TRUE(std::isfinite(row["relative_rmse"].get<double>()));

  // A bad scene: a message naming the file and the key, exit 1, no output folder.
  const std::string bad =
      dir.file("bad.json", R"({"medium": {"type": "cloud-layer", "coverage": 1.5}})");
  r = test::runRadkit("clouds --width 8 --height 4 --scene '" + bad + "' --out " + dir.path("bad"),
                      60);
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("bad.json"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("coverage"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir.path("bad")));
  // The layer's options describe the medium the file gives: refused together.
  r = test::runRadkit("clouds --width 8 --height 4 --scene '" +
                          test::dataPath("clouds/cumulus.json") + "' --coverage 0.3 --out " +
                          dir.path("both"),
                      60);
  EXPECT_NE(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("--coverage"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir.path("both")));
}

}  // namespace
}  // namespace radkit::media
