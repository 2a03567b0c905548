// The automatic camera (one for every image and the viewer), --camera, and render of an OBJ.
#include "render/camera.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "geometry/scene_loader.h"
#include "geometry/subdivision.h"
#include "render/hdr_io.h"
#include "tests/common/open_box.h"

namespace radkit {
namespace {

TEST(AutomaticCamera, LooksIntoAnOpenBoxThroughItsOpenSide) {
  test::TempDir dir;
  const Scene plus = loadScene(test::writeOpenBoxObj(dir, true, "plus"));
  const Camera c = automaticCamera(plus);
  EXPECT_GT(c.position.z, 1) << "the box opens toward +z";
  EXPECT_LT(c.lookAt.z, c.position.z);
  EXPECT_EQ(c.up.y, 1);
  // The patches of the same scene (the viewer's and render.png's input) agree.
  const Camera m = automaticCamera(subdivide(plus, {0, 200}));
  EXPECT_GT(m.position.z, 1);

  const Scene minus = loadScene(test::writeOpenBoxObj(dir, false, "minus"));
  EXPECT_LT(automaticCamera(minus).position.z, -1) << "the box opens toward -z";
}

TEST(AutomaticCamera, SeesAnOpenBoxUnmirrored) {
  // From the open side, with +y up, the red wall (x = 0) of the +z box is on the image's left.
  test::TempDir dir;
  const Scene scene = loadScene(test::writeOpenBoxObj(dir, true));
  const PinholeCamera cam(automaticCamera(scene), 64, 64);
  double x, y;
  ASSERT_TRUE(cam.project({0, 0.5, 0.5}, x, y));
  EXPECT_LT(x, 32);
  ASSERT_TRUE(cam.project({1, 0.5, 0.5}, x, y));
  EXPECT_GT(x, 32);
}

TEST(AutomaticCamera, ClosedModelFromItsFrontFacingSide) {
  // One outward-facing square at y = 0 (a floor seen from above) and nothing else: only the +y
  // side sees a front face.
  std::vector<Triangle> t{{Vec3{0, 0, 0}, Vec3{0, 0, 1}, Vec3{1, 0, 1}},
                          {Vec3{0, 0, 0}, Vec3{1, 0, 1}, Vec3{1, 0, 0}}};
  const Camera c = automaticCamera(t);
  EXPECT_GT(c.position.y, 0.5);
  EXPECT_GT(length(cross(c.lookAt - c.position, c.up)), 0) << "up must not be the view direction";
}

/// Two triangles of the quad a, b, c, d (counter-clockwise seen from its front).
void quad(std::vector<Triangle>& t, std::vector<char>& emitting, Vec3 a, Vec3 b, Vec3 c, Vec3 d,
          bool emits = false) {
  t.push_back({a, b, c});
  t.push_back({a, c, d});
  emitting.push_back(emits), emitting.push_back(emits);
}

/// A closed 4 × 3 × 5 room (y up) of inward-facing walls with a lamp under its ceiling.
std::vector<Triangle> closedRoom(std::vector<char>& emitting) {
  std::vector<Triangle> t;
  quad(t, emitting, {0, 0, 0}, {0, 0, 5}, {4, 0, 5}, {4, 0, 0});  // floor, facing +y
  quad(t, emitting, {0, 3, 0}, {4, 3, 0}, {4, 3, 5}, {0, 3, 5});  // ceiling, -y
  quad(t, emitting, {0, 0, 0}, {0, 3, 0}, {0, 3, 5}, {0, 0, 5});  // +x
  quad(t, emitting, {4, 0, 0}, {4, 0, 5}, {4, 3, 5}, {4, 3, 0});  // -x
  quad(t, emitting, {0, 0, 0}, {4, 0, 0}, {4, 3, 0}, {0, 3, 0});  // +z
  quad(t, emitting, {0, 0, 5}, {0, 3, 5}, {4, 3, 5}, {4, 0, 5});  // -z
  quad(t, emitting, {1.5, 2.9, 2}, {2.5, 2.9, 2}, {2.5, 2.9, 3}, {1.5, 2.9, 3}, true);
  return t;
}

TEST(AutomaticCamera, GoesInsideAClosedRoom) {
  // From outside every side shows the backs of walls: the old camera drew a black picture.
  std::vector<char> emitting;
  const std::vector<Triangle> room = closedRoom(emitting);
  const Camera c = automaticCamera(room, &emitting);
  for (int k = 0; k < 3; ++k) {
    EXPECT_GT(c.position[k], 0) << k;
    EXPECT_LT(c.position[k], k == 0 ? 4 : k == 1 ? 3 : 5) << k;
  }
  // Along the longer horizontal axis (z, 5 m), from its near end toward the far wall.
  EXPECT_LT(c.position.z, 0.5);
  EXPECT_NEAR(c.lookAt.z, 5, 1e-12);
}

TEST(AutomaticCamera, DoesNotLookIntoTheLampUnderWhichAModelStands) {
  // A unit cube under a large lamp facing down: from below the lamp filled the view and won.
  std::vector<Triangle> t;
  std::vector<char> emitting;
  quad(t, emitting, {0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1});            // bottom, facing -y
  quad(t, emitting, {0, 1, 0}, {0, 1, 1}, {1, 1, 1}, {1, 1, 0});            // top, +y
  quad(t, emitting, {0, 0, 0}, {0, 0, 1}, {0, 1, 1}, {0, 1, 0});            // -x
  quad(t, emitting, {1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1});            // +x
  quad(t, emitting, {0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0});            // -z
  quad(t, emitting, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1});            // +z
  quad(t, emitting, {-3, 3, -3}, {4, 3, -3}, {4, 3, 4}, {-3, 3, 4}, true);  // lamp, facing -y
  EXPECT_LT(automaticCamera(t).position.y, 0) << "without the lamp flags: from below";
  const Camera c = automaticCamera(t, &emitting);
  EXPECT_GE(c.position.y, 0) << "seen from below, into the lamp";
}

TEST(ParseCamera, GivesEveryPartAndRefusesNonsense) {
  const Camera c = parseCamera("--camera", "0,1,4,0,1,0,1,0,0,30");
  EXPECT_EQ(c.position.z, 4);
  EXPECT_EQ(c.lookAt.y, 1);
  EXPECT_EQ(c.up.x, 1);
  EXPECT_EQ(c.fovDeg, 30);
  EXPECT_EQ(parseCamera("--camera", "0,1,4,0,1,0").up.y, 1);
  for (const char* bad : {"0,1,4", "0,1,4,0,1,x", "0,1,4,0,1,4", "0,1,4,0,1,0,0,0,1,180",
                          "0,5,0,0,0,0", "1,2,3,4,5,6,7"}) {
    try {
      parseCamera("--camera", bad);
      ADD_FAILURE() << bad << " was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("Fix:"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("--camera"), std::string::npos) << e.what();
    }
  }
}

TEST(RenderCamera, OpenBoxObjIsNotBlack) {
  // CornellBox-Original.obj's shape: open toward +z. The old camera sat on -z and saw the backs.
  test::TempDir dir;
  const std::string obj = test::writeOpenBoxObj(dir, true);
  const std::string common = " --shading radiosity --patches 60 --size 16x16 --out ";
  test::RunResult r = test::runRadkit("render '" + obj + "'" + common + dir.path("auto.pfm"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_GT(readPfm(dir.path("auto.pfm")).meanRadiance(), 0.01);
  // --camera replaces the automatic one: from behind the back wall, nothing faces it.
  r = test::runRadkit("render '" + obj + "' --camera 0.5,0.5,-3,0.5,0.5,0" + common +
                      dir.path("behind.pfm"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(readPfm(dir.path("behind.pfm")).meanRadiance(), 0);
  r = test::runRadkit("render '" + obj + "' --camera 0,0,1" + common + dir.path("bad.pfm"));
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.output.find("Fix:"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir.path("bad.pfm")));
}

}  // namespace
}  // namespace radkit
