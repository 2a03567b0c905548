// The spherical shell between the ground and the top of the atmosphere: ray-sphere distances
// shared by the ray march, the tables and the reference path tracer (header-only, inlined in
// their hot loops).
#pragma once

#include <algorithm>
#include <cmath>

#include "util/vec3.h"

namespace radkit::atmosphere {

/// e^{−τ} per channel: transmittance from optical depth.
inline Vec3 expNeg(const Vec3& tau) {
  return {std::exp(-tau.x), std::exp(-tau.y), std::exp(-tau.z)};
}

/// Distance from p along unit d to the sphere of radius r about the planet's centre where the
/// ray first meets it from outside, or −1 when it never does. A point on the sphere moving
/// inward meets it at 0, one moving outward or tangentially never (a grazing ray passes).
inline double distanceToSphereFromOutside(const Vec3& p, const Vec3& d, double r) {
  const double b = dot(p, d);
  if (b >= 0) return -1;                                    // the distance to the centre only grows
  const double len = length(p), c = (len - r) * (len + r);  // |p|² − r² without cancellation
  const double disc = b * b - c;
  if (disc < 0) return -1;
  // The near root −b − √disc, written c/(−b + √disc) so it keeps its digits near 0.
  return std::max(0.0, c / (-b + std::sqrt(disc)));
}

/// Distance from p inside the sphere of radius r along unit d to where it leaves it.
inline double distanceToSphereFromInside(const Vec3& p, const Vec3& d, double r) {
  const double b = dot(p, d);
  const double len = length(p), c = std::min(0.0, (len - r) * (len + r));
  const double s = std::sqrt(b * b - c);
  // The far root −b + s; for b > 0 as −c/(b + s), free of cancellation.
  return b > 0 ? -c / (b + s) : s - b;
}

/// The part [t0, t1] of the ray p + t·d inside the atmosphere and before the ground; `ground`
/// says whether it ends on the ground. False when the ray misses the atmosphere.
inline bool atmosphereSegment(const Vec3& p, const Vec3& d, double groundRadius, double topRadius,
                              double& t0, double& t1, bool& ground) {
  if (dot(p, p) <= topRadius * topRadius) {
    t0 = 0;
    t1 = distanceToSphereFromInside(p, d, topRadius);
  } else {
    t0 = distanceToSphereFromOutside(p, d, topRadius);
    if (t0 < 0) return false;
    t1 = t0 + distanceToSphereFromInside(p + d * t0, d, topRadius);
  }
  const double g = distanceToSphereFromOutside(p, d, groundRadius);
  ground = g >= 0 && g <= t1;
  if (ground) t1 = g;
  return true;
}

}  // namespace radkit::atmosphere
