// The exact differential-area-to-polygon form factor: Lambert's contour integral (Nusselt's
// projected solid angle), with the polygon first clipped to the point's front half-space.
#pragma once

#include <vector>

#include "util/vec3.h"

namespace radkit {

/// Capacity of the stack buffers for clipped patches (a quad clipped by four planes has 8).
constexpr int kMaxPolygonVertices = 16;

/// \brief Clips a convex or non-convex planar polygon to the closed half-space
/// {p : n·(p − x) >= 0} (Sutherland–Hodgman against one plane).
/// \param in, count  the polygon
/// \param out        receives the clipped polygon, capacity count + 1
/// \return the number of vertices written (0 when nothing lies in front)
int clipToHalfSpace(const Vec3* in, int count, const Vec3& x, const Vec3& n, Vec3* out);

/// \brief Form factor from a differential area at x (unit normal n) to a polygon, unoccluded:
/// F = (1/2π) |Σ_k γ_k n·(v_k × v_k+1)/|v_k × v_k+1||   (Lambert; Cohen & Wallace ch. 4).
/// The polygon is clipped to the front half-space of (x, n) first, so it may straddle the
/// tangent plane. It is the projected solid angle over π, independent of the polygon's
/// orientation: callers decide whether x sees the polygon's front. Result in [0, 1].
double pointToPolygonFormFactor(const Vec3& x, const Vec3& n, const Vec3* polygon, int count);

/// Convenience overload for tests and small tools.
double pointToPolygonFormFactor(const Vec3& x, const Vec3& n, const std::vector<Vec3>& polygon);

/// The contour sum alone, without clipping: valid only when the whole polygon lies in front of
/// the tangent plane. Exposed so tests can show why clipping is needed.
double unclippedContourFormFactor(const Vec3& x, const Vec3& n, const Vec3* polygon, int count);

/// pointToPolygonFormFactor for points x of one plane (through planePoint, normal n): every
/// such x clips the polygon by the same plane, so the clip is done once. For integrating
/// over a patch; at most kMaxPolygonVertices − 1 vertices.
class PlaneToPolygon {
 public:
  PlaneToPolygon(const Vec3& planePoint, const Vec3& n, const Vec3* polygon, int count);
  double operator()(const Vec3& x) const {
    return m_count < 3 ? 0.0 : unclippedContourFormFactor(x, m_normal, m_clipped, m_count);
  }

 private:
  Vec3 m_clipped[kMaxPolygonVertices];
  Vec3 m_normal;
  int m_count = 0;
};

}  // namespace radkit
