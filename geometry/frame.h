// The local shading frame and the cosine-weighted hemisphere warp: header-only so bsdf/,
// which links nothing of geometry/, can use them.
#pragma once

#include <algorithm>
#include <cmath>

#include "geometry/vec3.h"

namespace radkit {

/// Orthonormal frame around a unit normal (Duff et al. 2017, branchless).
struct Frame {
  Vec3 s, t, n;
  explicit Frame(const Vec3& normal) : n(normal) {
    const double sign = std::copysign(1.0, n.z);
    const double a = -1.0 / (sign + n.z);
    const double b = n.x * n.y * a;
    s = {1 + sign * n.x * n.x * a, sign * b, -sign * n.x};
    t = {b, sign + n.y * n.y * a, -n.y};
  }
  Vec3 toWorld(const Vec3& local) const { return s * local.x + t * local.y + n * local.z; }
  Vec3 toLocal(const Vec3& w) const { return {dot(w, s), dot(w, t), dot(w, n)}; }
};

/// \brief Cosine-weighted direction on the hemisphere z > 0 (polar map of the unit disk,
/// lifted by Malley's method). u in [0,1)².
/// The local direction with cos θ = mu and azimuth phi (z is the normal).
inline Vec3 localDirection(double mu, double phi) {
  const double s = std::sqrt(std::max(0.0, 1 - mu * mu));
  return {s * std::cos(phi), s * std::sin(phi), mu};
}

inline Vec3 sampleCosineHemisphere(double u0, double u1) {
  // Uniform on the unit disk (r = √u0, φ = 2πu1), projected up: density cos θ/π (Malley).
  const double r = std::sqrt(u0), phi = 2 * M_PI * u1;
  return {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0, 1 - u0))};
}

/// \brief Direction uniform in solid angle in the cone cos θ ≥ cosMax around z (a disc light
/// of uniform radiance, the sun). u in [0,1)²; density 1/(2π(1 − cosMax)).
inline Vec3 sampleUniformCone(double cosMax, double u0, double u1) {
  return localDirection(1 - u0 * (1 - cosMax), 2 * M_PI * u1);
}

/// \brief Density per steradian of sampleCosineHemisphere: cos θ / π (0 below the horizon).
inline double cosineHemispherePdf(const Vec3& local) { return local.z > 0 ? local.z / M_PI : 0.0; }

/// \brief Inverse of sampleCosineHemisphere: the (u0, u1) that produce the direction.
inline void invertCosineHemisphereSample(const Vec3& local, double& u0, double& u1) {
  u0 = local.x * local.x + local.y * local.y;
  double phi = std::atan2(local.y, local.x);
  if (phi < 0) phi += 2 * M_PI;
  u1 = phi / (2 * M_PI);
}

}  // namespace radkit
