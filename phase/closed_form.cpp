#include "phase/closed_form.h"

#include <cmath>

#include "util/frame.h"

namespace radkit {

double isotropicPhase() { return 1 / (4 * kPi); }

double rayleighPhase(double cosTheta) { return 3 * (1 + cosTheta * cosTheta) / (16 * kPi); }

double cornetteShanksPhase(double cosTheta, double g) {
  const double k = 3 * (1 - g * g) / (2 * (2 + g * g));
  const double denom = 1 + g * g - 2 * g * cosTheta;
  return k * (1 + cosTheta * cosTheta) / (denom * std::sqrt(denom)) / (4 * kPi);
}

double henyeyGreensteinPhase(double cosTheta, double g) {
  const double denom = 1 + g * g - 2 * g * cosTheta;
  return (1 - g * g) / (denom * std::sqrt(denom)) / (4 * kPi);
}

double sampleRayleighCosine(double u) {
  const double z = 4 * u - 2;
  const double a = std::cbrt(z + std::sqrt(z * z + 1));
  return std::fmin(1.0, std::fmax(-1.0, a - 1 / a));
}

double sampleHenyeyGreensteinCosine(double u, double g) {
  if (std::fabs(g) < 1e-6) return 2 * u - 1;
  const double s = (1 - g * g) / (1 - g + 2 * g * u);
  return std::fmin(1.0, std::fmax(-1.0, (1 + g * g - s * s) / (2 * g)));
}

double sampleCornetteShanksCosine(Rng& rng, double g) {
  for (;;) {
    const double mu = sampleHenyeyGreensteinCosine(rng.uniform(), g);
    if (2 * rng.uniform() < 1 + mu * mu) return mu;
  }
}

Vec3 directionAround(const Vec3& axis, double mu, double u) {
  return Frame(axis).toWorld(localDirection(mu, 2 * kPi * u));
}

}  // namespace radkit
