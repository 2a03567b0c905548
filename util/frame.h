// The local shading frame and the cosine-weighted hemisphere warp: header-only so bsdf/,
// which links nothing of geometry/, can use them.
#pragma once

#include <algorithm>
#include <cmath>

#include "util/vec3.h"

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

/// The local direction with cos θ = mu and azimuth phi (z is the normal).
inline Vec3 localDirection(double mu, double phi) {
  const double s = std::sqrt(std::max(0.0, 1 - mu * mu));
  return {s * std::cos(phi), s * std::sin(phi), mu};
}

/// \brief sin x and cos x for |x| ≤ π/4 by their Taylor series (the first terms left out are
/// below 5e-18 there): the concentric warp needs no more, and libm's general sincos cost about a
/// tenth of a Lambertian path tracer's time. Evaluated in Estrin's scheme, whose products run
/// side by side, not in Horner's chain of nine dependent steps.
inline void sinCosQuarterPi(double x, double& sin, double& cos) {
  const double y = x * x, y2 = y * y, y4 = y2 * y2;
  // sin x = x Σ s_k y^k, cos x = Σ c_k y^k with s_k = (−1)^k/(2k+1)!, c_k = (−1)^k/(2k)!.
  const double s01 = 1 - y * (1.0 / 6), s23 = 1.0 / 120 - y * (1.0 / 5040),
               s45 = 1.0 / 362880 - y * (1.0 / 39916800),
               s67 = 1.0 / 6227020800 - y * (1.0 / 1307674368000), s8 = 1.0 / 355687428096000;
  const double c01 = 1 - y * 0.5, c23 = 1.0 / 24 - y * (1.0 / 720),
               c45 = 1.0 / 40320 - y * (1.0 / 3628800),
               c67 = 1.0 / 479001600 - y * (1.0 / 87178291200), c8 = 1.0 / 20922789888000;
  sin = x * ((s01 + y2 * s23) + y4 * ((s45 + y2 * s67) + y4 * s8));
  cos = (c01 + y2 * c23) + y4 * ((c45 + y2 * c67) + y4 * c8);
}

/// \brief Cosine-weighted direction on the hemisphere z > 0: the unit square mapped to the
/// unit disk by Shirley & Chiu's concentric map (1997), lifted by Malley's method. The map
/// keeps strata compact (the polar map stretches them into thin wedges at the centre), which
/// is what stratified and Sobol samples need. u in [0,1)².
inline Vec3 sampleCosineHemisphere(double u0, double u1) {
  const double a = 2 * u0 - 1, b = 2 * u1 - 1;
  if (a == 0 && b == 0) return {0, 0, 1};
  // Right and left wedges (|a| > |b|): radius a, angle (π/4)(b/a); upper and lower ones:
  // radius b, angle π/2 − (π/4)(a/b). Selects, not branches: which wedge is a coin toss.
  const bool side = std::fabs(a) > std::fabs(b);
  const double r = side ? a : b, other = side ? b : a;
  double s, c;
  sinCosQuarterPi(M_PI / 4 * (other / r), s, c);
  return {r * (side ? c : s), r * (side ? s : c), std::sqrt(std::max(0.0, 1 - r * r))};
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
  const double r = std::sqrt(local.x * local.x + local.y * local.y);
  double a = 0, b = 0;
  if (std::fabs(local.x) >= std::fabs(local.y) && local.x != 0) {
    a = std::copysign(r, local.x);
    b = a * std::atan(local.y / local.x) * (4 / M_PI);
  } else if (local.y != 0) {
    b = std::copysign(r, local.y);
    a = b * std::atan(local.x / local.y) * (4 / M_PI);
  }
  u0 = (a + 1) / 2;
  u1 = (b + 1) / 2;
}

}  // namespace radkit
