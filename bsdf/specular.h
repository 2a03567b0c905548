// Perfect specular interactions shared by photon tracing and path tracing: mirror
// reflection, refraction (Snell) and the exact dielectric Fresnel reflectance.
#pragma once

#include <algorithm>
#include <cmath>

#include "util/vec3.h"

namespace radkit {

/// Mirror direction of `incoming` (pointing away from the surface) about unit normal n.
inline Vec3 reflect(const Vec3& wo, const Vec3& n) { return n * (2 * dot(wo, n)) - wo; }

/// \brief Refracts wo (pointing away from the surface, on the side n points to) through an
/// interface with relative index eta = n_transmitted / n_incident.
/// \return false on total internal reflection.
inline bool refract(const Vec3& wo, const Vec3& n, double eta, Vec3& wt) {
  double cosI = dot(wo, n);
  double sin2T = std::max(0.0, 1 - cosI * cosI) / (eta * eta);
  if (sin2T >= 1) return false;
  double cosT = std::sqrt(1 - sin2T);
  wt = -wo / eta + n * (cosI / eta - cosT);
  return true;
}

/// \brief Unpolarised Fresnel reflectance of a dielectric interface (pbrt-v4 FrDielectric):
/// cosThetaI > 0 on the side of index 1, eta = n_inside / n_outside; 1 under total internal
/// reflection.
inline double fresnelDielectric(double cosThetaI, double eta) {
  cosThetaI = std::clamp(cosThetaI, -1.0, 1.0);
  if (cosThetaI < 0) {  // leaving the medium: swap sides
    eta = 1 / eta;
    cosThetaI = -cosThetaI;
  }
  double sin2T = (1 - cosThetaI * cosThetaI) / (eta * eta);
  if (sin2T >= 1) return 1;
  double cosT = std::sqrt(1 - sin2T);
  double rParl = (eta * cosThetaI - cosT) / (eta * cosThetaI + cosT);
  double rPerp = (cosThetaI - eta * cosT) / (cosThetaI + eta * cosT);
  return 0.5 * (rParl * rParl + rPerp * rPerp);
}

/// Schlick's approximation F0 + (1 − F0)(1 − cos θ)^5, per channel.
inline Vec3 fresnelSchlick(const Vec3& f0, double cosTheta) {
  double m = std::pow(1 - std::clamp(cosTheta, 0.0, 1.0), 5);
  return f0 + (Vec3{1, 1, 1} - f0) * m;
}

}  // namespace radkit
