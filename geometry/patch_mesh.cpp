#include "geometry/patch_mesh.h"
#include "geometry/visibility.h"

#include <algorithm>
#include <cmath>

namespace radkit {

namespace {
// Vector area of a polygon (Newell's method): half the sum of cross products of consecutive
// vertices. Its length is the area of a planar polygon, its direction the normal.
Vec3 vectorArea(const std::vector<Vec3>& poly) {
  Vec3 sum;
  for (std::size_t k = 0; k < poly.size(); ++k) sum += cross(poly[k], poly[(k + 1) % poly.size()]);
  return sum * 0.5;
}
}  // namespace

void computePatchGeometry(const std::vector<Vec3>& vertices, Patch& patch) {
  std::vector<Vec3> poly;
  for (int k = 0; k < patch.vertexCount; ++k) poly.push_back(vertices[patch.vertex[k]]);
  // Newell's vector area is exact for planar polygons and robust for thin ones.
  Vec3 va = vectorArea(poly);
  patch.area = length(va);
  patch.normal = patch.area > 0 ? va / patch.area : Vec3{0, 0, 0};
  // Area centroid: area-weighted centroids of the fan triangles.
  Vec3 c;
  double w = 0;
  for (int k = 1; k + 1 < patch.vertexCount; ++k) {
    double a = length(cross(poly[k] - poly[0], poly[k + 1] - poly[0]));
    c += (poly[0] + poly[k] + poly[k + 1]) * (a / 3.0);
    w += a;
  }
  if (w > 0) {
    patch.centroid = c / w;
  } else {
    Vec3 mean;
    for (const Vec3& p : poly) mean += p;
    patch.centroid = mean / double(poly.size());
  }
}

double polygonAspectRatio(const std::vector<Vec3>& polygon) {
  double longest2 = 0;
  for (std::size_t k = 0; k < polygon.size(); ++k) {
    Vec3 e = polygon[(k + 1) % polygon.size()] - polygon[k];
    longest2 = std::max(longest2, dot(e, e));
  }
  double area = length(vectorArea(polygon));
  if (area <= 0) return INFINITY;
  return polygon.size() == 3 ? longest2 * std::sqrt(3.0) / (4.0 * area) : longest2 / area;
}

std::vector<Vec3> PatchMesh::polygon(const Patch& p) const {
  std::vector<Vec3> poly;
  for (int k = 0; k < p.vertexCount; ++k) poly.push_back(vertices[p.vertex[k]]);
  return poly;
}

double PatchMesh::totalArea() const {
  double a = 0;
  for (const Patch& p : patches) a += p.area;
  return a;
}

Bounds3 PatchMesh::bounds() const {
  Bounds3 b;
  for (const Vec3& v : vertices) b.extend(v);
  return b;
}

double PatchMesh::aspectRatio(const Patch& p) const { return polygonAspectRatio(polygon(p)); }

double rayEpsilon(const Bounds3& b) {
  if (b.empty()) return kRayEpsilonRelative;
  double extent = b.diagonal();
  for (int a = 0; a < 3; ++a) extent = std::max({extent, std::fabs(b.lo[a]), std::fabs(b.hi[a])});
  return kRayEpsilonRelative * extent;
}

}  // namespace radkit
