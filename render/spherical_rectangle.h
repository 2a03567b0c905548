// Uniform sampling of the solid angle a rectangle subtends (Ureña, Fajardo & King 2013, "An
// Area-Preserving Parametrization for Spherical Rectangles", EGSR). Next-event estimation
// with it has density 1/Ω per steradian, so the 1/r² and the emitter's cosine drop out of
// the estimator: only the receiver's cosine, the BSDF and visibility vary over the light.
#pragma once

#include "util/vec3.h"

namespace radkit {

class SphericalRectangle {
 public:
  /// \brief The rectangle corner + s·ex + t·ey (s, t in [0, 1], ex ⟂ ey) seen from `origin`.
  SphericalRectangle(const Vec3& origin, const Vec3& corner, const Vec3& ex, const Vec3& ey);

  /// Solid angle Ω (sr); 0 when the origin lies in the rectangle's plane.
  double solidAngle() const { return m_solidAngle; }
  /// \brief The point of the rectangle hit by a direction uniform in its solid angle, (u, v)
  /// in [0, 1)² (the map is area-preserving and continuous, so stratified (u, v) stay
  /// stratified). Requires solidAngle() > 0.
  Vec3 sample(double u, double v) const;

 private:
  Vec3 m_origin, m_x, m_y, m_z;
  double m_x0 = 0, m_y0 = 0, m_x1 = 0, m_y1 = 0, m_z0 = 0;
  double m_b0 = 0, m_b1 = 0, m_k = 0, m_solidAngle = 0;
};

/// \brief Corner and orthogonal edges of a patch that is a rectangle (4 vertices, opposite
/// edges equal and adjacent ones at right angles within a relative 1e-9); false otherwise.
bool patchRectangle(const Vec3* v, int count, Vec3& corner, Vec3& ex, Vec3& ey);

}  // namespace radkit
