#include "render/radiosity_image.h"

#include <gtest/gtest.h>

#include "geometry/ray_scene.h"
#include "geometry/scene_loader.h"
#include "geometry/subdivision.h"
#include "tests/common/test_util.h"

namespace radkit {
namespace {

TEST(PinholeCamera, CornellBoxHandedness) {
  Scene scene = loadScene(test::dataPath("cornell-box.json"));
  PinholeCamera cam(*scene.camera, 512, 512);
  Vec3 centre = cam.direction(256, 256);
  EXPECT_NEAR(centre.z, 1.0, 1e-12);
  // docs/oracles.md (Cornell box): looking along +z with +y up, +x is the viewer's left.
  EXPECT_GT(cam.direction(0, 256).x, 0);
  EXPECT_GT(cam.direction(256, 0).y, 0);
  // The full vertical field of view is 39.3077°.
  double half = std::acos(dot(cam.direction(256, 0), centre)) * 180 / M_PI;
  EXPECT_NEAR(2 * half, 39.3077, 1e-9);
}

TEST(PinholeCamera, ProjectInvertsDirection) {
  Camera c;
  c.position = {1, 2, 3};
  c.lookAt = {0, 0, 0};
  c.up = {0, 0, 1};
  c.fovDeg = 50;
  PinholeCamera cam(c, 640, 480);
  for (double x : {0.5, 100.25, 320.0, 639.5})
    for (double y : {0.5, 240.0, 479.5}) {
      double px, py;
      ASSERT_TRUE(cam.project(c.position + cam.direction(x, y) * 7.0, px, py));
      EXPECT_NEAR(px, x, 1e-9);
      EXPECT_NEAR(py, y, 1e-9);
    }
  double px, py;
  EXPECT_FALSE(cam.project(c.position * 2.0, px, py));  // behind the camera
}

TEST(ToneMap, SrgbCurve) {
  // IEC 61966-2-1: linear segment below 0.0031308, then 1.055 v^(1/2.4) - 0.055.
  EXPECT_DOUBLE_EQ(srgbEncode(0), 0);
  EXPECT_NEAR(srgbEncode(0.0031308), 0.04045, 1e-6);
  EXPECT_NEAR(srgbEncode(0.5), 1.055 * std::pow(0.5, 1 / 2.4) - 0.055, 1e-15);
  EXPECT_DOUBLE_EQ(srgbEncode(1), 1);
  EXPECT_DOUBLE_EQ(srgbEncode(7), 1);  // clamped
}

TEST(RadiosityImage, FurnaceIsUniform) {
  // Inside a closed cube of uniform B every ray hits a patch whose radiance is B/π, flat or
  // smooth alike (vertex means of a constant are the constant).
  Scene scene = loadScene(test::dataPath("furnace.json"));
  PatchMesh mesh = subdivide(scene, {0.05, 0});
  RayScene rays(mesh);
  std::vector<Vec3> b(mesh.size(), Vec3{2, 2, 2});
  Camera cam;
  cam.position = {0.5, 0.5, 0.5};
  cam.lookAt = {0.5, 1, 0.6};
  cam.up = {0, 0, 1};
  cam.fovDeg = 100;
  for (bool smooth : {false, true}) {
    ImageSettings s;
    s.width = s.height = 48;
    s.smooth = smooth;
    RadianceImage img = renderRadiosity(mesh, rays, cam, b, std::vector<bool>(6, false), s);
    for (std::size_t k = 0; k < img.radiance.size(); ++k) {
      ASSERT_GE(img.patch[k], 0);
      ASSERT_NEAR(img.radiance[k].y, 2 / M_PI, 1e-12);
    }
  }
}

TEST(Picking, ReturnsThePatchUnderThePixel) {
  Scene scene = loadScene(test::dataPath("cornell-box.json"));
  PatchMesh mesh = subdivide(scene, {0, 200});
  RayScene rays(mesh);
  const int w = 512, h = 512;
  PinholeCamera cam(*scene.camera, w, h);
  int checked = 0;
  for (int i = 0; i < mesh.size(); ++i) {
    const Patch& p = mesh.patches[i];
    double x, y;
    if (dot(p.normal, p.centroid - scene.camera->position) >= 0) continue;  // faces away
    if (!cam.project(p.centroid, x, y) || x < 0 || y < 0 || x >= w || y >= h) continue;
    if (rays.occluded(scene.camera->position, p.centroid)) continue;  // hidden
    // The pixel containing the centroid's image sees this patch unless the centroid lies
    // within a pixel of the patch's outline; patches here span tens of pixels.
    auto picked = pickPatch(rays, *scene.camera, w, h, int(x), int(y));
    ASSERT_TRUE(picked.has_value()) << i;
    EXPECT_EQ(*picked, i);
    ++checked;
  }
  EXPECT_GT(checked, 40);
  Camera away = *scene.camera;
  away.lookAt = away.position - Vec3{0, 0, 1};  // turned around: the box is behind it
  EXPECT_FALSE(pickPatch(rays, away, w, h, 256, 256).has_value());
}

}  // namespace
}  // namespace radkit
