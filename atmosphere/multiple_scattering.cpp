// Transmittance and multiple-scattering tables (multiple_scattering.h; Hillaire 2020).
#include "atmosphere/multiple_scattering.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "atmosphere/shell.h"

namespace radkit::atmosphere {

namespace {
/// Index and fraction of u·(n − 1) for bilinear lookups, u clamped to [0, 1].
void lutCell(double u, int n, int& i, double& f) {
  const double x = std::clamp(u, 0.0, 1.0) * (n - 1);
  i = std::min(n - 2, int(x));
  f = x - i;
}

}  // namespace

TransmittanceLut::TransmittanceLut(const Atmosphere& atmosphere)
    : m_groundRadius(atmosphere.parameters().groundRadius),
      m_topRadius(atmosphere.parameters().topRadius),
      m_transmittance(std::size_t(kAltitudes) * kCosines) {
  const double height = m_topRadius - m_groundRadius;
  tbb::parallel_for(0, kAltitudes, [&](int i) {
    const double u = double(i) / (kAltitudes - 1);
    const double r = m_groundRadius + height * u * u;
    const Vec3 p{0, 0, r};
    const double horizon =
        -std::sqrt(std::max(0.0, 1 - (m_groundRadius / r) * (m_groundRadius / r)));
    for (int j = 0; j < kCosines; ++j) {
      const double v = double(j) / (kCosines - 1);
      const double mu = horizon + (1 - horizon) * v * v;
      const Vec3 d{std::sqrt(std::max(0.0, 1 - mu * mu)), 0, mu};
      const double t = distanceToSphereFromInside(p, d, m_topRadius);
      m_transmittance[std::size_t(i) * kCosines + j] =
          expNeg(atmosphere.opticalDepth(p, p + d * t));
    }
  });
}

Vec3 TransmittanceLut::transmittance(double h, double mu) const {
  const double r = m_groundRadius + std::max(0.0, h);
  const double horizon = -std::sqrt(std::max(0.0, 1 - (m_groundRadius / r) * (m_groundRadius / r)));
  if (mu < horizon) return {0, 0, 0};
  int i, j;
  double fi, fj;
  lutCell(std::sqrt(std::max(0.0, h) / (m_topRadius - m_groundRadius)), kAltitudes, i, fi);
  lutCell(std::sqrt((mu - horizon) / (1 - horizon)), kCosines, j, fj);
  auto at = [&](int a, int b) { return m_transmittance[std::size_t(a) * kCosines + b]; };
  return (at(i, j) * (1 - fj) + at(i, j + 1) * fj) * (1 - fi) +
         (at(i + 1, j) * (1 - fj) + at(i + 1, j + 1) * fj) * fi;
}

MultipleScatteringLut::MultipleScatteringLut(const Atmosphere& atmosphere,
                                             const TransmittanceLut& transmittance)
    : m_height(atmosphere.parameters().topRadius - atmosphere.parameters().groundRadius),
      m_psi(std::size_t(kSize) * kSize) {
  const AtmosphereParameters& ap = atmosphere.parameters();
  const Vec3 albedoTerm = ap.solarIrradiance * (ap.groundAlbedo / kPi);
  const double pu = isotropicPhase();
  const Vec3 betaR = ap.rayleighScattering * ap.relativeDensity;
  const double betaM = ap.mieScattering * ap.relativeDensity;
  const double betaMe = ap.mieExtinction * ap.relativeDensity;
  tbb::parallel_for(0, kSize * kSize, [&](int cellIndex) {
    const int i = cellIndex / kSize, j = cellIndex % kSize;
    const double h = m_height * i / (kSize - 1);
    const double muS = -1 + 2.0 * j / (kSize - 1);
    const Vec3 x{0, 0, ap.groundRadius + h};
    const Vec3 sun{std::sqrt(std::max(0.0, 1 - muS * muS)), 0, muS};
    Vec3 secondOrder{0, 0, 0}, transfer{0, 0, 0};
    const int side = 8;  // kDirections = side², equal-area cells
    for (int a = 0; a < side; ++a)
      for (int b = 0; b < side; ++b) {
        const double mu = 1 - 2 * (a + 0.5) / side, phi = 2 * kPi * (b + 0.5) / side;
        const double s = std::sqrt(std::max(0.0, 1 - mu * mu));
        const Vec3 d{s * std::cos(phi), s * std::sin(phi), mu};
        double t0 = 0, t1 = 0;
        bool ground = false;
        atmosphereSegment(x, d, ap.groundRadius, ap.topRadius, t0, t1, ground);
        const double dt = (t1 - t0) / kSteps;
        Vec3 tau{0, 0, 0}, light{0, 0, 0}, unit{0, 0, 0};
        for (int k = 0; k < kSteps; ++k) {
          const Vec3 y = x + d * (t0 + (k + 0.5) * dt);
          const double ry = length(y), hy = ry - ap.groundRadius;
          const double dR = std::exp(-hy / ap.rayleighScaleHeight);
          const double dM = std::exp(-hy / ap.mieScaleHeight);
          const Vec3 scattering = betaR * dR + Vec3{1, 1, 1} * (betaM * dM);
          const Vec3 extinction = betaR * dR + Vec3{1, 1, 1} * (betaMe * dM);
          const Vec3 t = expNeg(tau + extinction * (dt / 2));
          tau += extinction * dt;
          const Vec3 sunT = transmittance.transmittance(hy, dot(y, sun) / ry);
          light += mul(mul(t, scattering), mul(sunT, ap.solarIrradiance)) * (pu * dt);
          unit += mul(t, scattering) * dt;
        }
        if (ground) {
          const Vec3 g = x + d * t1;
          const double cosSun = dot(g, sun) / length(g);
          if (cosSun > 0)
            light +=
                mul(mul(expNeg(tau), transmittance.transmittance(0, cosSun)), albedoTerm) * cosSun;
        }
        secondOrder += light;
        transfer += unit;
      }
    // p_u ∫ f dω over equal-area cells of 4π/kDirections each is their mean.
    secondOrder = secondOrder / kDirections;
    transfer = transfer / kDirections;
    m_psi[std::size_t(cellIndex)] = {secondOrder.x / (1 - transfer.x),
                                     secondOrder.y / (1 - transfer.y),
                                     secondOrder.z / (1 - transfer.z)};
  });
}

Vec3 MultipleScatteringLut::at(double h, double cosSunZenith) const {
  int i, j;
  double fi, fj;
  lutCell(h / m_height, kSize, i, fi);
  lutCell((cosSunZenith + 1) / 2, kSize, j, fj);
  auto v = [&](int a, int b) { return m_psi[std::size_t(a) * kSize + b]; };
  return (v(i, j) * (1 - fj) + v(i, j + 1) * fj) * (1 - fi) +
         (v(i + 1, j) * (1 - fj) + v(i + 1, j + 1) * fj) * fi;
}

}  // namespace radkit::atmosphere
