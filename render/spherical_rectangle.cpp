#include "render/spherical_rectangle.h"

#include <algorithm>
#include <cmath>

namespace radkit {

SphericalRectangle::SphericalRectangle(const Vec3& origin, const Vec3& corner, const Vec3& ex,
                                       const Vec3& ey)
    : m_origin(origin) {
  const double ex_len = length(ex), ey_len = length(ey);
  if (!(ex_len > 0) || !(ey_len > 0)) return;
  m_x = ex / ex_len;
  m_y = ey / ey_len;
  m_z = cross(m_x, m_y);
  // The rectangle in the local frame (x, y, z) at the origin, on the plane z = z0 < 0.
  const Vec3 d = corner - origin;
  m_x0 = dot(d, m_x), m_y0 = dot(d, m_y), m_z0 = dot(d, m_z);
  if (m_z0 > 0) {
    m_z0 = -m_z0;
    m_z = -m_z;
  }
  m_x1 = m_x0 + ex_len, m_y1 = m_y0 + ey_len;
  if (!(m_z0 < 0)) return;
  // Normals of the planes through the origin and each edge (v00 × v10, v10 × v11, v11 × v01,
  // v01 × v00, normalised: each has a zero component since the edges are axis-aligned); the
  // spherical rectangle's interior angles are the angles between consecutive ones (§3).
  const Vec3 n0 = Vec3{0, m_z0, -m_y0} / std::sqrt(m_z0 * m_z0 + m_y0 * m_y0);
  const Vec3 n1 = Vec3{-m_z0, 0, m_x1} / std::sqrt(m_z0 * m_z0 + m_x1 * m_x1);
  const Vec3 n2 = Vec3{0, -m_z0, m_y1} / std::sqrt(m_z0 * m_z0 + m_y1 * m_y1);
  const Vec3 n3 = Vec3{m_z0, 0, -m_x0} / std::sqrt(m_z0 * m_z0 + m_x0 * m_x0);
  auto angle = [](const Vec3& a, const Vec3& b) {
    return std::acos(std::clamp(-dot(a, b), -1.0, 1.0));
  };
  const double g0 = angle(n0, n1), g1 = angle(n1, n2), g2 = angle(n2, n3), g3 = angle(n3, n0);
  m_b0 = n0.z, m_b1 = n2.z;
  m_k = 2 * M_PI - g2 - g3;
  // Girard: the area of a spherical quadrilateral is its angle sum minus 2π.
  m_solidAngle = std::max(0.0, g0 + g1 - m_k);
}

Vec3 SphericalRectangle::sample(double u, double v) const {
  // u picks the x coordinate by the solid angle to its left (inverting the area of the
  // sub-rectangle [x0, xu], which is linear in u), v the height along that column (its
  // solid angle is linear in h = y/√(x² + y² + z0²)).
  const double au = u * m_solidAngle + m_k;
  const double fu = (std::cos(au) * m_b0 - m_b1) / std::sin(au);
  double cu = std::copysign(1.0, fu) / std::sqrt(fu * fu + m_b0 * m_b0);
  cu = std::clamp(cu, -1.0, 1.0);
  const double xu = std::clamp(-(cu * m_z0) / std::sqrt(std::max(1e-300, 1 - cu * cu)), m_x0, m_x1);
  const double dist = std::sqrt(xu * xu + m_z0 * m_z0);
  const double h0 = m_y0 / std::sqrt(dist * dist + m_y0 * m_y0),
               h1 = m_y1 / std::sqrt(dist * dist + m_y1 * m_y1);
  const double hv = h0 + v * (h1 - h0), hv2 = hv * hv;
  const double yv = hv2 < 1 - 1e-12 ? std::clamp(hv * dist / std::sqrt(1 - hv2), m_y0, m_y1) : m_y1;
  return m_origin + m_x * xu + m_y * yv + m_z * m_z0;
}

bool patchRectangle(const Vec3* v, int count, Vec3& corner, Vec3& ex, Vec3& ey) {
  if (count != 4) return false;
  corner = v[0], ex = v[1] - v[0], ey = v[3] - v[0];
  const double scale = length(ex) * length(ey);
  if (!(scale > 0)) return false;
  const double tol = 1e-9 * scale;
  return std::fabs(dot(ex, ey)) <= tol && length(v[2] - v[1] - ey) * length(ex) <= tol &&
         length(v[2] - v[3] - ex) * length(ey) <= tol;
}

}  // namespace radkit
