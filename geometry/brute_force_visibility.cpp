// Exhaustive double-precision visibility: the oracle that RayScene is tested against.
#include <cmath>

#include "geometry/ray_scene.h"

namespace radkit {

namespace {
// Möller–Trumbore ray/triangle test; returns t or NaN for a miss.
double intersectTriangle(const Vec3& o, const Vec3& d, const Vec3& a, const Vec3& b,
                         const Vec3& c) {
  Vec3 e1 = b - a, e2 = c - a;
  Vec3 p = cross(d, e2);
  double det = dot(e1, p);
  if (det == 0) return NAN;
  double inv = 1.0 / det;
  Vec3 s = o - a;
  double u = dot(s, p) * inv;
  if (u < 0 || u > 1) return NAN;
  Vec3 q = cross(s, e1);
  double v = dot(d, q) * inv;
  if (v < 0 || u + v > 1) return NAN;
  return dot(e2, q) * inv;
}
}  // namespace

BruteForceVisibility::BruteForceVisibility(const PatchMesh& mesh)
    : m_mesh(mesh), m_epsilon(rayEpsilon(mesh.bounds())) {}

std::optional<RayHit> BruteForceVisibility::closestHit(const Vec3& origin, const Vec3& direction,
                                                       double tMin, double tMax) const {
  std::optional<RayHit> best;
  for (int i = 0; i < m_mesh.size(); ++i) {
    const Patch& p = m_mesh.patches[i];
    for (int k = 1; k + 1 < p.vertexCount; ++k) {
      double t = intersectTriangle(origin, direction, m_mesh.vertex(p, 0), m_mesh.vertex(p, k),
                                   m_mesh.vertex(p, k + 1));
      if (t > tMin && t < tMax && (!best || t < best->distance)) best = RayHit{i, t};
    }
  }
  return best;
}

bool BruteForceVisibility::occluded(const Vec3& from, const Vec3& nFrom, const Vec3& to,
                                    const Vec3& nTo) const {
  Vec3 p = liftToward(from, nFrom, to, m_epsilon);
  Vec3 q = liftToward(to, nTo, p, m_epsilon);
  return closestHit(p, q - p, 0.0, 1.0).has_value();
}

bool BruteForceVisibility::occluded(const Vec3& from, const Vec3& to) const {
  Vec3 d = to - from;
  double len = length(d);
  if (len <= 2 * m_epsilon) return false;
  return closestHit(from, d, m_epsilon / len, 1.0 - m_epsilon / len).has_value();
}

}  // namespace radkit
