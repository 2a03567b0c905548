// The spherical Rayleigh and Mie atmosphere (atmosphere.h): coefficients, optical depth,
// transmittance and the single-scattering ray march of Nishita et al. 1993 with Hillaire's
// 2020 multiple-scattering term.
#include "atmosphere/atmosphere.h"

#include <algorithm>
#include <cmath>
#include <mutex>

#include "atmosphere/multiple_scattering.h"
#include "atmosphere/shell.h"

namespace radkit::atmosphere {

struct Atmosphere::Tables {
  std::once_flag once;
  std::unique_ptr<TransmittanceLut> transmittance;
  std::unique_ptr<MultipleScatteringLut> multipleScattering;
};

namespace {

/// Gauss-Legendre nodes and weights on [−1, 1], six points (Abramowitz and Stegun, 25.4.30).
constexpr double kGaussNodes[3] = {0.2386191860831969, 0.6612093864662645, 0.9324695142031521};
constexpr double kGaussWeights[3] = {0.4679139345726910, 0.3607615730481386, 0.1713244923791704};

}  // namespace

double rayleighCoefficient(double wavelength, double refractiveIndex, double numberDensity,
                           double relativeDensity) {
  if (relativeDensity == 0) return 0;
  // n − 1 and N both scale with the density, so (n² − 1)²/N grows linearly with it (up to a
  // factor (1 + (n − 1)/2)², 3e-4 at standard density). The naive formula with n fixed would
  // fall as 1/N.
  const double n = 1 + (refractiveIndex - 1) * relativeDensity;
  const double N = numberDensity * relativeDensity;
  // King correction factor for the anisotropy of N₂ and O₂, depolarisation δ ≈ 0.035
  // (Bucholtz 1995; Preetham, Shirley and Smits 1999, appendix).
  const double delta = 0.035;
  const double king = (6 + 3 * delta) / (6 - 7 * delta);
  const double n2 = n * n - 1;
  return 8 * kPi * kPi * kPi * n2 * n2 / (3 * N * std::pow(wavelength, 4)) * king;
}

Vec3 sunDirection(double elevationDeg, double azimuthDeg) {
  const double e = elevationDeg * kPi / 180, a = azimuthDeg * kPi / 180;
  return {std::cos(e) * std::sin(a), std::cos(e) * std::cos(a), std::sin(e)};
}

Atmosphere::Atmosphere(const AtmosphereParameters& parameters)
    : m_p(parameters), m_tables(std::make_unique<Tables>()) {}
Atmosphere::~Atmosphere() = default;
Atmosphere::Atmosphere(Atmosphere&&) noexcept = default;
Atmosphere& Atmosphere::operator=(Atmosphere&&) noexcept = default;

const MultipleScatteringLut& Atmosphere::multipleScattering() const {
  Tables& t = *m_tables;
  std::call_once(t.once, [&] {
    t.transmittance = std::make_unique<TransmittanceLut>(*this);
    t.multipleScattering = std::make_unique<MultipleScatteringLut>(*this, *t.transmittance);
  });
  return *t.multipleScattering;
}

Vec3 Atmosphere::rayleighScatteringAt(double h) const {
  return m_p.rayleighScattering * (m_p.relativeDensity * std::exp(-h / m_p.rayleighScaleHeight));
}

double Atmosphere::mieScatteringAt(double h) const {
  return m_p.mieScattering * m_p.relativeDensity * std::exp(-h / m_p.mieScaleHeight);
}

Vec3 Atmosphere::extinctionAt(double h) const {
  const double mie = m_p.mieExtinction * m_p.relativeDensity * std::exp(-h / m_p.mieScaleHeight);
  return rayleighScatteringAt(h) + Vec3{mie, mie, mie};  // no absorption by air (no ozone)
}

Vec3 Atmosphere::opticalDepth(const Vec3& a, const Vec3& b) const {
  const double len = length(b - a);
  if (!(len > 0)) return {0, 0, 0};
  const Vec3 d = (b - a) / len;
  // The distance to the centre falls until the closest approach tc and rises after it, so
  // each side is cut into pieces of at most 2 H_min in altitude (equal in altitude, not in
  // length: a grazing ray is long where the air barely changes), with six-point
  // Gauss-Legendre on each: relative error below 1e-12 for an exponential over 2 H
  // (the error term of A&S 25.4.30).
  const double tc = -dot(a, d);
  const double rc2 = std::max(0.0, dot(a, a) - tc * tc);
  const double hMin = std::min(m_p.rayleighScaleHeight, m_p.mieScaleHeight);
  double columnR = 0, columnM = 0;
  auto integrate = [&](double ta, double tb, double side) {
    if (!(tb > ta)) return;
    const double ra = length(a + d * ta), rb = length(a + d * tb);
    const int pieces = std::max(1, int(std::ceil(std::fabs(rb - ra) / (2 * hMin))));
    double t0 = ta;
    for (int k = 1; k <= pieces; ++k) {
      const double r = ra + (rb - ra) * k / pieces;
      const double t1 =
          k == pieces ? tb : std::clamp(tc + side * std::sqrt(std::max(0.0, r * r - rc2)), t0, tb);
      const double half = (t1 - t0) / 2, mid = (t0 + t1) / 2;
      for (int q = 0; q < 6; ++q) {
        const double t = mid + (q < 3 ? -1 : 1) * kGaussNodes[q % 3] * half;
        const double h = length(a + d * t) - m_p.groundRadius;
        columnR += kGaussWeights[q % 3] * half * std::exp(-h / m_p.rayleighScaleHeight);
        columnM += kGaussWeights[q % 3] * half * std::exp(-h / m_p.mieScaleHeight);
      }
      t0 = t1;
    }
  };
  const double split = std::clamp(tc, 0.0, len);
  integrate(0, split, -1);
  integrate(split, len, 1);
  const double mie = m_p.mieExtinction * columnM;
  return (m_p.rayleighScattering * columnR + Vec3{mie, mie, mie}) * m_p.relativeDensity;
}

Vec3 Atmosphere::transmittanceToTop(const Vec3& p, const Vec3& d) const {
  double t0 = 0, t1 = 0;
  bool ground = false;
  if (!atmosphereSegment(p, d, m_p.groundRadius, m_p.topRadius, t0, t1, ground)) return {1, 1, 1};
  if (ground) return {0, 0, 0};
  return expNeg(opticalDepth(p + d * t0, p + d * t1));
}

Vec3 Atmosphere::sunIrradiance(const Vec3& p, const Vec3& sunDir) const {
  return mul(m_p.solarIrradiance, transmittanceToTop(p, sunDir));
}

Vec3 Atmosphere::skyRadiance(const Vec3& p, const Vec3& dir, const Vec3& sunDir,
                             const SkySettings& settings) const {
  double t0 = 0, t1 = 0;
  bool ground = false;
  if (!atmosphereSegment(p, dir, m_p.groundRadius, m_p.topRadius, t0, t1, ground)) return {0, 0, 0};
  const MultipleScatteringLut* ms = settings.multipleScattering ? &multipleScattering() : nullptr;
  const int n = std::max(1, settings.viewSamples), nLight = std::max(1, settings.lightSamples);
  const double dt = (t1 - t0) / n;
  // cos θ between the sunlight's travel (−sunDir) and the scattered light's (−dir).
  const double mu = dot(dir, sunDir);
  const double phaseR = rayleighPhase(mu), phaseM = cornetteShanksPhase(mu, m_p.mieG);
  const double rho = m_p.relativeDensity;
  const Vec3 betaR = m_p.rayleighScattering * rho;
  const double betaM = m_p.mieScattering * rho, betaMe = m_p.mieExtinction * rho;
  // Column densities (∫ e^{−h/H} dt) from p to the current sample, per species.
  double columnR = 0, columnM = 0;
  Vec3 sum{0, 0, 0};
  for (int i = 0; i < n; ++i) {
    const Vec3 x = p + dir * (t0 + (i + 0.5) * dt);
    const double r = length(x), h = r - m_p.groundRadius;
    const double dR = std::exp(-h / m_p.rayleighScaleHeight);
    const double dM = std::exp(-h / m_p.mieScaleHeight);
    const double viewR = columnR + dR * dt / 2, viewM = columnM + dM * dt / 2;
    columnR += dR * dt;
    columnM += dM * dt;
    Vec3 source{0, 0, 0};
    if (distanceToSphereFromOutside(x, sunDir, m_p.groundRadius) < 0) {
      const double tl = distanceToSphereFromInside(x, sunDir, m_p.topRadius) / nLight;
      double lightR = 0, lightM = 0;
      for (int k = 0; k < nLight; ++k) {
        const double hl = length(x + sunDir * ((k + 0.5) * tl)) - m_p.groundRadius;
        lightR += std::exp(-hl / m_p.rayleighScaleHeight);
        lightM += std::exp(-hl / m_p.mieScaleHeight);
      }
      const Vec3 sunT = expNeg(betaR * (lightR * tl) + Vec3{1, 1, 1} * (betaMe * lightM * tl));
      source = mul(betaR * (dR * phaseR) + Vec3{1, 1, 1} * (betaM * dM * phaseM),
                   mul(sunT, m_p.solarIrradiance));
    }
    if (ms) source += mul(betaR * dR + Vec3{1, 1, 1} * (betaM * dM), ms->at(h, dot(x, sunDir) / r));
    sum += mul(expNeg(betaR * viewR + Vec3{1, 1, 1} * (betaMe * viewM)), source) * dt;
  }
  return sum;
}

}  // namespace radkit::atmosphere
