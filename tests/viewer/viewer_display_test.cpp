// Headless screenshots and picking. These need X: they skip without a display, and the
// `viewer_screenshots` ctest entry runs them under xvfb-run with RADKIT_REQUIRE_DISPLAY=1.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>

#include "geometry/scene_loader.h"
#include "geometry/subdivision.h"
#include "output/run_files.h"
#include "render/camera.h"
#include "render/hdr_io.h"
#include "render/sky_panorama.h"
#include "tests/common/open_box.h"
#include "tests/common/test_util.h"
#include "tests/viewer/test_run.h"
#include "util/canvas.h"
#include "viewer/viewer.h"

namespace radkit::viewer {
namespace {

class ViewerDisplay : public ::testing::Test {
 protected:
  void SetUp() override {
    const char* display = std::getenv("DISPLAY");
    if (!display || !*display) {
      if (std::getenv("RADKIT_REQUIRE_DISPLAY"))
        FAIL() << "RADKIT_REQUIRE_DISPLAY is set but DISPLAY is not";
      GTEST_SKIP() << "no X display (ctest runs these under xvfb-run as viewer_screenshots)";
    }
    test::writeTestRun(folder());
  }
  std::string folder() const { return m_dir.path(""); }

  /// Renders `mode` at w × h and reads the PNG back.
  Canvas shot(const std::string& mode, int w, int h, bool smooth = false, double exposure = 0) {
    ViewerOptions o;
    o.exposure = exposure;
    o.runFolder = folder();
    o.screenshot = m_dir.path(mode.substr(0, mode.find(':')) + (smooth ? "-smooth" : "") + ".png");
    o.mode = mode;
    o.width = w;
    o.height = h;
    o.smooth = smooth;
    const auto start = std::chrono::steady_clock::now();
    EXPECT_EQ(runViewer(o), 0);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_LT(seconds, 5.0) << mode << " took " << seconds << " s";
    EXPECT_FALSE(std::filesystem::exists(o.screenshot + ".tmp"));
    return readPng(o.screenshot);
  }

  radkit::test::TempDir m_dir;
};

struct ImageStats {
  std::size_t distinctColours = 0;
  double differentFromCorner = 0;  ///< fraction of pixels unlike the top-left... background pixel
};

ImageStats stats(const Canvas& c) {
  std::set<int> colours;
  const Rgb8 bg = c.at(c.width() - 1, c.height() - 1);
  std::size_t different = 0;
  for (int y = 0; y < c.height(); ++y)
    for (int x = 0; x < c.width(); ++x) {
      const Rgb8 p = c.at(x, y);
      colours.insert(p.r << 16 | p.g << 8 | p.b);
      different += std::abs(p.r - bg.r) + std::abs(p.g - bg.g) + std::abs(p.b - bg.b) > 24;
    }
  return {colours.size(), double(different) / (double(c.width()) * c.height())};
}

/// Mean colour over a square of side 2r around (x, y).
Vec3 meanColour(const Canvas& c, double x, double y, int r = 4) {
  Vec3 sum;
  int n = 0;
  for (int j = int(y) - r; j <= int(y) + r; ++j)
    for (int i = int(x) - r; i <= int(x) + r; ++i, ++n)
      sum += Vec3{double(c.at(i, j).r), double(c.at(i, j).g), double(c.at(i, j).b)};
  return sum / n;
}

TEST_F(ViewerDisplay, EveryModeFillsAnImageOfTheRequestedSize) {
  const int w = 333, h = 222;  // odd sizes: exactly these, not a power of two or the screen
  for (const std::string mode :
       {"radiosity", "false-colour", "formfactors-row:0", "matrix", "convergence"}) {
    const Canvas c = shot(mode, w, h);
    ASSERT_EQ(c.width(), w) << mode;
    ASSERT_EQ(c.height(), h) << mode;
    const ImageStats s = stats(c);
    EXPECT_GT(s.distinctColours, 20u) << mode;  // text, colour bar, patches: not a flat fill
    EXPECT_GT(s.differentFromCorner, 0.05) << mode;
  }
}

/// A hierarchical run has no formfactors.mtx; the matrix mode shows its links.png instead,
/// whole and with its aspect (here a magenta left half and a yellow right half).
TEST_F(ViewerDisplay, MatrixOfAHierarchicalRunShowsItsLinksImage) {
  std::filesystem::remove(m_dir.path("formfactors.mtx"));
  Canvas links(200, 100, {255, 0, 255});
  links.fill(100, 0, 200, 100, {255, 255, 0});
  writePng(m_dir.path("links.png"), links);
  const int w = 400, h = 300;
  const Canvas c = shot("matrix", w, h);
  // The image is 2:1, scaled to the width (400 × 200) below the title, centred vertically.
  const Vec3 left = meanColour(c, w * 0.25, h * 0.55), right = meanColour(c, w * 0.75, h * 0.55);
  EXPECT_GT(left.x, 200);
  EXPECT_LT(left.y, 60);
  EXPECT_GT(left.z, 200);
  EXPECT_GT(right.x, 200);
  EXPECT_GT(right.y, 200);
  EXPECT_LT(right.z, 60);
  ViewerOptions o;
  o.runFolder = folder();
  o.screenshot = m_dir.path("none.png");
  o.mode = "matrix";
  // A links.png that is not a PNG is refused by name, with nothing written.
  { std::ofstream(m_dir.path("links.png")) << "not an image\n"; }
  try {
    runViewer(o);
    FAIL() << "a links.png that is not a PNG should be refused";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("links.png: not a PNG image"), std::string::npos)
        << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(o.screenshot));
  // Without either file the mode is refused, naming what is missing.
  std::filesystem::remove(m_dir.path("links.png"));
  try {
    runViewer(o);
    FAIL() << "matrix mode without formfactors.mtx or links.png should be refused";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("formfactors.mtx"), std::string::npos) << e.what();
  }
}

TEST_F(ViewerDisplay, RadiosityShowsRedLeftGreenRightAndBackground) {
  const int w = 320, h = 240;
  const Canvas c = shot("radiosity", w, h);
  double x, y;
  test::projectToPixel({-0.5, -0.25, 0}, w, h, x, y);
  const Vec3 left = meanColour(c, x, y);
  test::projectToPixel({0.5, -0.25, 0}, w, h, x, y);
  const Vec3 right = meanColour(c, x, y);
  test::projectToPixel({0, -0.9, 0}, w, h, x, y);
  const Vec3 below = meanColour(c, x, y);
  EXPECT_GT(left.x, 2 * left.y) << "left wall should be red";
  EXPECT_GT(right.y, 2 * right.x) << "right wall should be green";
  EXPECT_LT(below.x + below.y + below.z, 3 * 60) << "below the walls is dark background";
  // Patch 0 (B_r 0.9) is brighter than patch 1 (B_r 0.6) in flat shading.
  test::projectToPixel({-0.5, 0.25, 0}, w, h, x, y);
  EXPECT_GT(left.x, meanColour(c, x, y).x + 10);
}

TEST_F(ViewerDisplay, SmoothShadingBlendsAcrossTheSharedEdge) {
  const int w = 320, h = 240;
  const Canvas flat = shot("radiosity", w, h), smooth = shot("radiosity", w, h, true);
  double x, yLow, yHigh;
  test::projectToPixel({-0.5, -0.02, 0}, w, h, x, yLow);  // just below the shared edge y = 0
  test::projectToPixel({-0.5, 0.02, 0}, w, h, x, yHigh);
  const double flatJump = meanColour(flat, x, yLow, 1).x - meanColour(flat, x, yHigh, 1).x;
  const double smoothJump = meanColour(smooth, x, yLow, 1).x - meanColour(smooth, x, yHigh, 1).x;
  EXPECT_GT(flatJump, 10);
  EXPECT_LT(std::abs(smoothJump), flatJump / 2);
}

TEST_F(ViewerDisplay, PickReturnsThePatchUnderThePixel) {
  const int w = 320, h = 240;
  double x, y;
  test::projectToPixel({-0.5, -0.25, 0}, w, h, x, y);
  EXPECT_EQ(pickPatchAt(folder(), w, h, int(x), int(y)), 0);
  test::projectToPixel({-0.5, 0.25, 0}, w, h, x, y);
  EXPECT_EQ(pickPatchAt(folder(), w, h, int(x), int(y)), 1);
  test::projectToPixel({0.5, 0.25, 0}, w, h, x, y);
  EXPECT_EQ(pickPatchAt(folder(), w, h, int(x), int(y)), 2);
  test::projectToPixel({0, 0, 0}, w, h, x, y);  // the gap between the walls
  EXPECT_EQ(pickPatchAt(folder(), w, h, int(x), int(y)), -1);
  EXPECT_EQ(pickPatchAt(folder(), w, h, 2, 2), -1);
}

// A patch seen from behind is neither drawn nor picked: its radiosity leaves its front only.
TEST_F(ViewerDisplay, BackOfAPatchIsNotDrawnOrPicked) {
  test::writeTestRun(folder(), true);
  const int w = 320, h = 240;
  const Canvas c = shot("radiosity", w, h);
  double x, y;
  test::projectToPixel({0.5, -0.25, 0}, w, h, x, y);
  const Vec3 right = meanColour(c, x, y);
  EXPECT_LT(right.x + right.y + right.z, 3 * 60) << "the right patch's back shows the background";
  EXPECT_EQ(pickPatchAt(folder(), w, h, int(x), int(y)), -1);
  test::projectToPixel({-0.5, -0.25, 0}, w, h, x, y);
  EXPECT_GT(meanColour(c, x, y).x, 100) << "the left wall still faces the camera";
  EXPECT_EQ(pickPatchAt(folder(), w, h, int(x), int(y)), 0);
}

// A run with no camera (an OBJ): the viewer looks into the open box through its open side,
// as render.png does, and not through the back of the back wall.
TEST_F(ViewerDisplay, RunWithoutCameraIsSeenThroughItsOpenSide) {
  for (bool plusZ : {true, false}) {
    const Scene scene =
        loadScene(radkit::test::writeOpenBoxObj(m_dir, plusZ, plusZ ? "plus" : "minus"));
    const PatchMesh mesh = subdivide(scene, {0, 100});
    const std::vector<Vec3> b(mesh.size(), Vec3{1, 1, 1});
    const std::string run = m_dir.path(plusZ ? "run-plus" : "run-minus");
    std::filesystem::create_directories(run);
    writePatchesVtp(run + "/radiosity.vtp", scene, mesh, &b);
    std::ofstream(run + "/report.json")
        << R"({"command": "run", "scene": {"name": "box", "file": "box.obj", "units": "m",
              "surfaces": ["back", "floor", "ceiling", "left", "right", "light"]}})";
    const int w = 200, h = 200;
    const PinholeCamera cam(automaticCamera(mesh), w, h);
    EXPECT_EQ(cam.origin().z > 1, plusZ);
    for (const auto& [point, surface] : {std::pair<Vec3, int>{{0, 0.5, plusZ ? 0.5 : -0.5}, 3},
                                         std::pair<Vec3, int>{{1, 0.5, plusZ ? 0.5 : -0.5}, 4},
                                         std::pair<Vec3, int>{{0.5, 0.5, 0}, 0}}) {
      double x, y;
      ASSERT_TRUE(cam.project(point, x, y));
      const int picked = pickPatchAt(run, w, h, int(x), int(y));
      ASSERT_GE(picked, 0) << "nothing under " << x << ", " << y;
      EXPECT_EQ(mesh.patches[picked].surface, surface)
          << (plusZ ? "+z" : "-z") << " box, pixel " << x << ", " << y;
    }
  }
}

// A run under a sky: the radiosity view draws sky.pfm behind the patches in the directions
// report.json's frame gives, at the patches' exposure, and the colour-scale views do not.
TEST_F(ViewerDisplay, RadiosityDrawsTheRunsSkyInItsDirections) {
  // The test camera is y-up and looks along −z: make −z north, so east (+x) is on the right.
  SkyDescription frame;
  frame.up = {0, 1, 0};
  frame.north = {0, 0, -1};
  const SkyModel sky(frame);
  // Red in the east, blue in the west, green more than 5° above the horizon.
  RadianceImage p;
  p.width = 256, p.height = 128;
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x < p.width; ++x) {
      const Vec3 d = panoramaDirection(sky, (x + 0.5) / p.width, (y + 0.5) / p.height);
      p.radiance.push_back({d.x > 0 ? 0.8 : 0.05, d.y > std::sin(5 * M_PI / 180) ? 0.8 : 0.05,
                            d.x < 0 ? 0.8 : 0.05});
    }
  writePfm(m_dir.path("sky.pfm"), p);
  std::ofstream(m_dir.path("report.json"))
      << R"({"command": "run", "scene": {"name": "two-walls", "file": "two-walls.json", "units": "m",
            "surfaces": ["left wall", "right wall"],
            "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov_deg": 40}},
            "sky_panorama": {"file": "sky.pfm", "up": [0, 1, 0], "north": [0, 0, -1],
                             "east": [1, 0, 0]}})";
  const int w = 400, h = 300;
  // Exposure 1: a radiance of 0.8 shows as sRGB 231, 0.05 as 63. The points lie outside the
  // walls, 11.5° above or below the horizon and 21° either side of north.
  const Canvas c = shot("radiosity", w, h, false, 1.0);
  const Vec3 upLeft = meanColour(c, w * 0.1, h * 0.2), upRight = meanColour(c, w * 0.9, h * 0.2);
  const Vec3 downLeft = meanColour(c, w * 0.1, h * 0.8);
  const Vec3 downRight = meanColour(c, w * 0.9, h * 0.8);
  auto expectColour = [](const Vec3& got, bool r, bool g, bool b, const char* where) {
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(got[k],
                  (k == 0   ? r
                   : k == 1 ? g
                            : b)
                      ? 231
                      : 63,
                  12)
          << where << " channel " << k;
  };
  expectColour(upLeft, false, true, true, "up, west");
  expectColour(upRight, true, true, false, "up, east");
  expectColour(downLeft, false, false, true, "down, west");
  expectColour(downRight, true, false, false, "down, east");
  // The walls are drawn over the sky, unchanged.
  double x, y;
  test::projectToPixel({-0.5, -0.25, 0}, w, h, x, y);
  EXPECT_GT(meanColour(c, x, y).x, 2 * meanColour(c, x, y).y) << "left wall should be red";
  // False colour keeps the neutral background behind its colour scale.
  const Canvas f = shot("false-colour", w, h);
  const Vec3 plain = meanColour(f, w * 0.1, h * 0.8);
  EXPECT_LT(std::abs(plain.x - plain.z), 10) << "false colour should not draw the sky";
  // A damaged panorama is refused by name before a window opens.
  { std::ofstream(m_dir.path("sky.pfm")) << "PF\n4 4\n-1\n"; }
  try {
    readRunFolder(folder());
    FAIL() << "a truncated sky.pfm should be refused";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("sky.pfm"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace radkit::viewer
