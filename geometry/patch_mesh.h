// PatchMesh: the scene split into patches, the elements of the radiosity system.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "geometry/scene.h"
#include "util/vec3.h"

namespace radkit {

/// A planar triangle or quadrilateral element. Vertices run counter-clockwise seen from the
/// front side; `normal` is the unit front normal, `area` in scene units².
struct Patch {
  std::array<int, 4> vertex{-1, -1, -1, -1};  ///< indices into PatchMesh::vertices
  int vertexCount = 0;                        ///< 3 or 4
  int surface = -1;                           ///< index into Scene::surfaces
  Vec3 normal;
  Vec3 centroid;  ///< area centroid
  double area = 0;

  bool isQuad() const { return vertexCount == 4; }
};

/// All patches of a scene. Patches are stored grouped by surface, in scene order:
/// surface s owns patches [surfaceBegin[s], surfaceBegin[s+1]).
/// Vertices are shared between the patches of one surface (never across surfaces).
struct PatchMesh {
  std::vector<Vec3> vertices;
  std::vector<Patch> patches;
  std::vector<int> surfaceBegin;  ///< size = surfaces + 1
  /// Per surface (empty: none): rays ignore hits on the back of its patches (Surface::cullBack).
  std::vector<char> cullBack;

  int size() const { return static_cast<int>(patches.size()); }
  Vec3 vertex(const Patch& p, int k) const { return vertices[p.vertex[k]]; }
  /// The polygon of a patch (3 or 4 points).
  std::vector<Vec3> polygon(const Patch& p) const;
  double totalArea() const;
  Bounds3 bounds() const;
  /// Longest edge² over area, scaled so that a square and an equilateral triangle give 1.
  double aspectRatio(const Patch& p) const;
};

/// Computes normal, centroid and area of a planar patch from its vertices.
void computePatchGeometry(const std::vector<Vec3>& vertices, Patch& patch);

/// Longest-edge aspect ratio of a planar polygon: L²/A for quads, L²·√3/(4A) for triangles.
double polygonAspectRatio(const std::vector<Vec3>& polygon);

}  // namespace radkit
