#include "geometry/subdivision.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "geometry/scene_loader.h"
#include "tests/common/test_util.h"

namespace radkit {
namespace {

double faceArea(const Surface& s, const Face& f) {
  Vec3 n;
  for (std::size_t k = 0; k < f.vertices.size(); ++k)
    n += cross(s.vertices[f.vertices[k]], s.vertices[f.vertices[(k + 1) % f.vertices.size()]]);
  return 0.5 * length(n);
}

Vec3 faceNormal(const Surface& s, const Face& f) {
  Vec3 n;
  for (std::size_t k = 0; k < f.vertices.size(); ++k)
    n += cross(s.vertices[f.vertices[k]], s.vertices[f.vertices[(k + 1) % f.vertices.size()]]);
  return normalize(n);
}

/// Distance from p to the (convex, planar) face, 0 when inside it.
double distanceToFace(const Surface& s, const Face& f, const Vec3& p) {
  Vec3 n = faceNormal(s, f);
  double d = std::fabs(dot(p - s.vertices[f.vertices[0]], n));
  for (std::size_t k = 0; k < f.vertices.size(); ++k) {
    Vec3 a = s.vertices[f.vertices[k]], b = s.vertices[f.vertices[(k + 1) % f.vertices.size()]];
    double outside = dot(cross(b - a, p - a), n) / length(b - a);  // < 0 outside edge ab
    if (outside < 0) d = std::max(d, -outside);
  }
  return d;
}

/// Length of patch edges with no opposite twin: only the surface boundary may have them,
/// so with no T-junctions it equals the boundary length of the input faces.
double unmatchedEdgeLength(const PatchMesh& mesh, int surface) {
  std::map<std::pair<int, int>, int> edges;
  for (int i = mesh.surfaceBegin[surface]; i < mesh.surfaceBegin[surface + 1]; ++i) {
    const Patch& p = mesh.patches[i];
    for (int k = 0; k < p.vertexCount; ++k)
      edges[{p.vertex[k], p.vertex[(k + 1) % p.vertexCount]}]++;
  }
  double len = 0;
  for (const auto& [e, count] : edges)
    if (!edges.count({e.second, e.first}))
      len += count * length(mesh.vertices[e.first] - mesh.vertices[e.second]);
  return len;
}

double boundaryLength(const Surface& s) {
  std::map<std::pair<int, int>, int> edges;
  for (const Face& f : s.faces)
    for (std::size_t k = 0; k < f.vertices.size(); ++k)
      edges[{f.vertices[k], f.vertices[(k + 1) % f.vertices.size()]}]++;
  double len = 0;
  for (const auto& [e, count] : edges)
    if (!edges.count({e.second, e.first}))
      len += length(s.vertices[e.first] - s.vertices[e.second]);
  return len;
}

void checkInvariants(const Scene& scene, const PatchMesh& mesh, double maxArea) {
  ASSERT_EQ(mesh.surfaceBegin.size(), scene.surfaces.size() + 1);
  for (std::size_t si = 0; si < scene.surfaces.size(); ++si) {
    const Surface& s = scene.surfaces[si];
    SCOPED_TRACE(s.name);
    double area = 0, patchArea = 0;
    for (const Face& f : s.faces) area += faceArea(s, f);
    for (int i = mesh.surfaceBegin[si]; i < mesh.surfaceBegin[si + 1]; ++i) {
      const Patch& p = mesh.patches[i];
      ASSERT_EQ(p.surface, int(si));
      patchArea += p.area;
      if (maxArea > 0) {
        EXPECT_LE(p.area, maxArea * (1 + 1e-12));
      }
      // The patch lies inside one face of its surface and shares that face's normal.
      double scale = std::sqrt(area);
      bool found = false;
      for (const Face& f : s.faces) {
        if (distanceToFace(s, f, p.centroid) > 1e-9 * scale) continue;
        found = true;
        EXPECT_NEAR(dot(p.normal, faceNormal(s, f)), 1.0, 1e-9);
        for (int k = 0; k < p.vertexCount; ++k)
          EXPECT_LE(distanceToFace(s, f, mesh.vertex(p, k)), 1e-9 * scale);
        break;
      }
      EXPECT_TRUE(found) << "patch " << i << " lies outside its surface";
    }
    EXPECT_NEAR(patchArea, area, 1e-12 * area) << "area not preserved";
    EXPECT_NEAR(unmatchedEdgeLength(mesh, int(si)), boundaryLength(s), 1e-9 * boundaryLength(s))
        << "T-junction";
  }
}

TEST(Subdivision, NoOptionKeepsInputFaces) {
  Scene scene = loadScene(test::dataPath("cornell-box.json"));
  PatchMesh mesh = subdivide(scene, {});
  std::size_t faces = 0, quads = 0;
  for (const Surface& s : scene.surfaces) {
    faces += s.faces.size();
    for (const Face& f : s.faces) quads += f.vertices.size() == 4;
  }
  EXPECT_EQ(std::size_t(mesh.size()), faces);
  int patchQuads = 0;
  for (const Patch& p : mesh.patches) patchQuads += p.isQuad();
  EXPECT_EQ(std::size_t(patchQuads), quads);
  checkInvariants(scene, mesh, 0);
}

TEST(Subdivision, InvariantsOnEveryDataScene) {
  const std::pair<const char*, double> cases[] = {{"cornell-box.json", 2000},
                                                  {"cornell-box.json", 150},
                                                  {"cornell-box-empty.json", 900},
                                                  {"cube-one-emitter.json", 0.01},
                                                  {"furnace.json", 0.003},
                                                  {"parallel-squares.json", 0.02},
                                                  {"perpendicular-squares.json", 0.05},
                                                  {"sphere-interior.json", 0.005}};
  for (const auto& [file, maxArea] : cases) {
    SCOPED_TRACE(file);
    Scene scene = loadScene(test::dataPath(file));
    PatchMesh mesh = subdivide(scene, {maxArea, 0});
    checkInvariants(scene, mesh, maxArea);
  }
}

TEST(Subdivision, QuadsStayQuadsAndNearSquare) {
  Scene scene = loadScene(test::dataPath("cube-one-emitter.json"));
  PatchMesh mesh = subdivide(scene, {0.01, 0});
  for (const Patch& p : mesh.patches) {
    EXPECT_TRUE(p.isQuad());
    EXPECT_NEAR(mesh.aspectRatio(p), 1.0, 1e-9);
  }
  EXPECT_EQ(mesh.size(), 6 * 10 * 10);
}

TEST(Subdivision, WorstAspectRatioBounded) {
  // Triangles split into similar triangles and quads into grids whose cells approach squares,
  // so no density is worse than the worst input face: the 213 × 105 mm ceiling strip beside
  // the light, aspect 2.03.
  Scene scene = loadScene(test::dataPath("cornell-box.json"));
  for (int n : {100, 1000, 4000, 16000}) {
    PatchMesh mesh = subdivide(scene, {0, n});
    double worst = 0;
    for (const Patch& p : mesh.patches) worst = std::max(worst, mesh.aspectRatio(p));
    EXPECT_LE(worst, 2.03) << n << " patches";
  }
}

TEST(Subdivision, PatchCountTarget) {
  Scene scene = loadScene(test::dataPath("cornell-box.json"));
  for (int n : {200, 1000, 4000, 16000}) {
    PatchMesh mesh = subdivide(scene, {0, n});
    EXPECT_NEAR(mesh.size(), n, 0.05 * n) << "asked for " << n;
  }
}

TEST(Subdivision, MeshSurfaceConformsAcrossFaces) {
  Scene scene = loadScene(test::dataPath("sphere-interior.json"));
  PatchMesh mesh = subdivide(scene, {0, 320 * 9});
  EXPECT_EQ(mesh.size(), 320 * 9);                  // each triangle into 3×3
  EXPECT_NEAR(unmatchedEdgeLength(mesh, 0), 0, 0);  // closed: every edge has its twin
}

// A limit that would need more patches than int counts and memory allow is refused; before,
// int(ceil(len/h)) overflowed and 1e-300 was silently ignored (patches of 1 m²).
TEST(Subdivision, RefusesMoreThanMaxPatches) {
  Scene scene = loadScene(test::dataPath("cornell-box.json"));
  for (double area : {1e-300, 1e-12, 1e-9})
    EXPECT_THROW(subdivide(scene, SubdivisionSettings{area, 0}), TooManyPatches) << area;
  EXPECT_THROW(subdivide(scene, SubdivisionSettings{0, int(kMaxPatches) + 1}), TooManyPatches);
  EXPECT_THROW(subdivide(scene, SubdivisionSettings{std::nan(""), 0}), std::invalid_argument);
}

// Edge lengths that overflow a double are named instead of becoming int(inf).
TEST(Subdivision, RefusesSurfacesWhoseLengthsOverflow) {
  Scene scene;
  Surface s;
  s.name = "huge";
  s.source = "test: huge";
  s.vertices = {{0, 0, 0}, {1e200, 0, 0}, {1e200, 1e200, 0}, {0, 1e200, 0}};
  s.faces = {Face{{0, 1, 2, 3}}};
  scene.surfaces.push_back(s);
  try {
    subdivide(scene, SubdivisionSettings{0, 100});
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("test: huge is too large"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace radkit
