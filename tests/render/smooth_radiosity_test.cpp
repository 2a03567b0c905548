// The crease-aware smooth reconstruction: exact where the solution is piecewise constant per
// face, linear precision inside a surface, jumps kept, and creases respected (the same box
// smoothed with a 180° crease angle, the old vertex average, does blur across the edges).
#include "render/smooth_radiosity.h"

#include <gtest/gtest.h>

#include <cmath>

#include "geometry/ray_scene.h"
#include "geometry/scene_loader.h"
#include "geometry/subdivision.h"
#include "render/radiosity_image.h"
#include "tests/common/test_util.h"

namespace radkit {
namespace {

/// A constant per surface and per face orientation: the blocks' five faces differ.
std::vector<Vec3> constantPerFace(const PatchMesh& mesh) {
  std::vector<Vec3> b;
  for (const Patch& p : mesh.patches) {
    int axis = 0;
    for (int a = 1; a < 3; ++a)
      if (std::fabs(p.normal[a]) > std::fabs(p.normal[axis])) axis = a;
    const int face = 2 * axis + (p.normal[axis] > 0);
    b.push_back(Vec3{1.0 + p.surface, 2.0 + face, 0.5 + 0.25 * face * p.surface});
  }
  return b;
}

/// Pixels (centre samples) whose smooth radiance differs from their patch's flat value.
int pixelsOffTheirFace(const Scene& scene, const PatchMesh& mesh, const std::vector<Vec3>& b,
                       double creaseDeg, int& seen) {
  RayScene rays(mesh);
  ImageSettings s;
  s.width = s.height = 96;
  s.samplesPerAxis = 1;  // the pixel centre: each pixel sees one patch
  s.smooth = true;
  s.smoothing.creaseAngleDeg = creaseDeg;
  s.smoothing.relativeError = 1e9;  // no jump test: creases alone must keep the faces apart
  const RadianceImage img = renderRadiosity(mesh, rays, *scene.camera, b,
                                            std::vector<bool>(scene.surfaces.size(), true), s);
  int off = 0;
  seen = 0;
  for (std::size_t k = 0; k < img.radiance.size(); ++k) {
    if (img.patch[k] < 0) continue;
    ++seen;
    if (!(img.radiance[k] == b[img.patch[k]] / M_PI)) ++off;
  }
  return off;
}

TEST(SmoothRadiosity, BoxFacesKeepTheirConstants) {
  Scene scene = loadScene(test::dataPath("cornell-box.json"));
  PatchMesh mesh = subdivide(scene, {0, 800});
  const std::vector<Vec3> b = constantPerFace(mesh);
  int seen = 0;
  EXPECT_EQ(pixelsOffTheirFace(scene, mesh, b, 30, seen), 0);
  EXPECT_GT(seen, 96 * 96 / 2);
  // Averaging across the blocks' 90° edges (what --smooth did before) changes pixels there.
  EXPECT_GT(pixelsOffTheirFace(scene, mesh, b, 180, seen), 100);
}

/// An n × n grid of unit quads in the plane z = 0, one surface.
PatchMesh grid(int n) {
  PatchMesh m;
  for (int y = 0; y <= n; ++y)
    for (int x = 0; x <= n; ++x) m.vertices.push_back(Vec3{double(x), double(y), 0});
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      Patch p;
      p.vertex = {y * (n + 1) + x, y * (n + 1) + x + 1, (y + 1) * (n + 1) + x + 1,
                  (y + 1) * (n + 1) + x};
      p.vertexCount = 4;
      p.surface = 0;
      computePatchGeometry(m.vertices, p);
      m.patches.push_back(p);
    }
  m.surfaceBegin = {0, n * n};
  return m;
}

TEST(SmoothRadiosity, CornerValuesForTheViewerKeepCreasesSurfacesAndJumps) {
  // Square A (z = 0) shares an edge with the coplanar square B and another with C, folded up
  // by 90°. A's corners on B's edge average A and B (equal areas) while they are one
  // surface and agree; its corners on the crease keep A's value.
  const std::vector<Vec3> points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                    {2, 0, 0}, {2, 1, 0}, {0, 1, 1}, {0, 0, 1}};
  const std::vector<std::vector<int>> polygons = {{0, 1, 2, 3}, {1, 4, 5, 2}, {0, 3, 6, 7}};
  auto cornersOfA = [&](std::vector<int> surface, std::vector<double> b) {
    const std::vector<double> c = smoothCornerValues(points, polygons, surface, b);
    EXPECT_EQ(c.size(), 12u);
    return std::vector<double>(c.begin(), c.begin() + 4);
  };
  const std::vector<double> blended = cornersOfA({0, 0, 0}, {1, 1.1, 1.05});
  EXPECT_NEAR(blended[0], 1, 1e-15);  // on the crease with C
  EXPECT_NEAR(blended[1], 1.05, 1e-15);
  EXPECT_NEAR(blended[2], 1.05, 1e-15);
  EXPECT_NEAR(blended[3], 1, 1e-15);
  // B on another surface, or B far brighter than the error explains: A stays flat.
  for (const std::vector<double>& c :
       {cornersOfA({0, 1, 0}, {1, 1.1, 1.05}), cornersOfA({0, 0, 0}, {1, 5, 1.05})})
    for (double v : c) EXPECT_NEAR(v, 1, 1e-15);
  // Colours follow the same rule (the grey overload is the Vec3 one's x).
  const std::vector<Vec3> colour = smoothCornerValues(
      points, polygons, {0, 0, 0}, {Vec3{1, 1, 1}, Vec3{1.1, 1.1, 1.1}, Vec3{1.05, 1.05, 1.05}});
  EXPECT_NEAR(colour[1].y, 1.05, 1e-15);
  EXPECT_NEAR(colour[0].y, 1, 1e-15);
}

TEST(SmoothRadiosity, ReproducesALinearRampInside) {
  // B = 5 + 0.1x + 0.2y: patch means are the centroid values, vertex means of the four
  // patches around an interior vertex are the vertex values, and mean value coordinates
  // reproduce linear functions, so interior patches return the ramp itself.
  const int n = 8;
  PatchMesh m = grid(n);
  auto ramp = [](const Vec3& x) { return 5 + 0.1 * x.x + 0.2 * x.y; };
  std::vector<Vec3> b;
  for (const Patch& p : m.patches) b.push_back(Vec3{1, 1, 1} * ramp(p.centroid));
  SmoothRadiosity smooth(m, b);
  for (int i = 0; i < m.size(); ++i) {
    const Vec3 c = m.patches[i].centroid;
    if (c.x < 1 || c.y < 1 || c.x > n - 1 || c.y > n - 1)
      continue;  // boundary corners see fewer patches
    for (const Vec3& x : {c, c + Vec3{0.3, -0.4, 0}, c + Vec3{-0.5, 0.5, 0}})
      EXPECT_NEAR(smooth.at(i, x).y, ramp(x), 1e-12) << "patch " << i;
  }
}

TEST(SmoothRadiosity, KeepsJumpsLargerThanTheError) {
  // A shadow edge: B = 1 left of x = 4, 10 right of it. With the default error (10 % of B)
  // the two sides never average, so every point returns its patch's value; with an error
  // large enough to explain the jump they do.
  PatchMesh m = grid(8);
  std::vector<Vec3> b;
  for (const Patch& p : m.patches) b.push_back(Vec3{1, 1, 1} * (p.centroid.x < 4 ? 1.0 : 10.0));
  SmoothRadiosity sharp(m, b);
  SmoothRadiosity blurred(m, b, {}, std::vector<double>(m.size(), 5.0));
  int blurredOff = 0;
  for (int i = 0; i < m.size(); ++i) {
    const Vec3 x = m.vertex(m.patches[i], 1) * 0.9 + m.patches[i].centroid * 0.1;  // near a corner
    EXPECT_EQ(sharp.at(i, x), b[i]);
    blurredOff += !(blurred.at(i, x) == b[i]);
  }
  EXPECT_EQ(blurredOff, 16);  // the two columns beside the edge, whose corners lie on x = 4
}

}  // namespace
}  // namespace radkit
