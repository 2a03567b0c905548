#include "bsdf/microfacet.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace radkit {

const char* maskingShadowingName(MaskingShadowing g) {
  switch (g) {
    case MaskingShadowing::HeightCorrelated:
      return "height-correlated";
    case MaskingShadowing::Separable:
      return "separable";
    case MaskingShadowing::SchlickGgx:
      return "schlick";
    default:
      return "cook-torrance";
  }
}

MaskingShadowing parseMaskingShadowing(const std::string& name) {
  for (MaskingShadowing g : {MaskingShadowing::HeightCorrelated, MaskingShadowing::Separable,
                             MaskingShadowing::SchlickGgx, MaskingShadowing::CookTorrance})
    if (name == maskingShadowingName(g)) return g;
  throw std::invalid_argument("unknown shadowing-masking term \"" + name +
                              "\": use height-correlated, separable, schlick or cook-torrance");
}

GgxDistribution::GgxDistribution(double alpha) : m_alpha(std::max(alpha, 1e-4)) {}

double GgxDistribution::D(const Vec3& m) const {
  if (m.z <= 0) return 0;
  const double a2 = m_alpha * m_alpha, c2 = m.z * m.z;
  const double t = c2 * (a2 - 1) + 1;
  return a2 / (M_PI * t * t);
}

double GgxDistribution::lambda(const Vec3& w) const {
  const double c2 = w.z * w.z;
  if (c2 <= 0) return INFINITY;
  const double tan2 = std::max(0.0, 1 - c2) / c2;
  return 0.5 * (std::sqrt(1 + m_alpha * m_alpha * tan2) - 1);
}

double GgxDistribution::G1(const Vec3& w) const { return w.z > 0 ? 1 / (1 + lambda(w)) : 0.0; }

double GgxDistribution::G(const Vec3& wo, const Vec3& wi, MaskingShadowing g) const {
  if (wo.z <= 0 || wi.z <= 0) return 0;
  switch (g) {
    case MaskingShadowing::HeightCorrelated:
      return 1 / (1 + lambda(wo) + lambda(wi));
    case MaskingShadowing::Separable:
      return G1(wo) * G1(wi);
    case MaskingShadowing::SchlickGgx: {
      // k = (r + 1)²/8 with perceptual roughness r = √α; G1 = μ / (μ(1 − k) + k).
      const double r = std::sqrt(m_alpha), k = (r + 1) * (r + 1) / 8;
      auto g1 = [k](double mu) { return mu / (mu * (1 - k) + k); };
      return g1(wo.z) * g1(wi.z);
    }
    default: {
      const Vec3 h = normalize(wo + wi);
      const double vh = std::max(dot(wo, h), 1e-300);
      return std::min({1.0, 2 * h.z * wo.z / vh, 2 * h.z * wi.z / vh});
    }
  }
}

Vec3 GgxDistribution::sampleVisibleNormal(const Vec3& wo, double u0, double u1) const {
  // Heitz 2018: stretch to the hemisphere configuration, sample the projected disk with
  // its lower half warped to the visible part, then unstretch.
  const Vec3 vh = normalize(Vec3{m_alpha * wo.x, m_alpha * wo.y, wo.z});
  const double lensq = vh.x * vh.x + vh.y * vh.y;
  const Vec3 t1 = lensq > 0 ? Vec3{-vh.y, vh.x, 0} / std::sqrt(lensq) : Vec3{1, 0, 0};
  const Vec3 t2 = cross(vh, t1);
  const double r = std::sqrt(u0), phi = 2 * M_PI * u1;
  const double p1 = r * std::cos(phi);
  const double s = 0.5 * (1 + vh.z);
  const double p2 = (1 - s) * std::sqrt(std::max(0.0, 1 - p1 * p1)) + s * r * std::sin(phi);
  const Vec3 nh = t1 * p1 + t2 * p2 + vh * std::sqrt(std::max(0.0, 1 - p1 * p1 - p2 * p2));
  return normalize(Vec3{m_alpha * nh.x, m_alpha * nh.y, std::max(1e-12, nh.z)});
}

double GgxDistribution::visibleNormalPdf(const Vec3& wo, const Vec3& m) const {
  if (wo.z <= 0) return 0;
  return G1(wo) * std::max(0.0, dot(wo, m)) * D(m) / wo.z;  // Heitz 2014, eq. 16
}

double directionalAlbedo(const GgxDistribution& d, MaskingShadowing g, double mu, int strata) {
  mu = std::clamp(mu, 1e-6, 1.0);
  const Vec3 wo{std::sqrt(1 - mu * mu), 0, mu};
  // With m ~ D_ωo and ωi = reflect(ωo, m), pdf(ωi) = D_ωo(m) / (4 ωo·m), so
  // f μi / pdf = [D G / (4 μo μi)] μi · 4 (ωo·m) μo / (G1(ωo) (ωo·m) D) = G / G1(ωo).
  const double g1 = d.G1(wo);
  double sum = 0;
  for (int i = 0; i < strata; ++i)
    for (int j = 0; j < strata; ++j) {
      const Vec3 m = d.sampleVisibleNormal(wo, (i + 0.5) / strata, (j + 0.5) / strata);
      const Vec3 wi = m * (2 * dot(wo, m)) - wo;
      if (wi.z > 0) sum += d.G(wo, wi, g) / g1;
    }
  return sum / (double(strata) * strata);
}

MicrofacetAlbedoTable::MicrofacetAlbedoTable(const GgxDistribution& d, MaskingShadowing g,
                                             int muCount, int strata) {
  for (int k = 0; k < muCount; ++k)
    m_albedo.push_back(directionalAlbedo(d, g, (k + 0.5) / muCount, strata));
  // E_avg = 2 ∫ E μ dμ (Kulla & Conty 2017) of the interpolant, midpoint rule on 4096 cells.
  const int n = 4096;
  double sum = 0;
  for (int k = 0; k < n; ++k) {
    const double mu = (k + 0.5) / n;
    sum += albedo(mu) * mu;
  }
  m_average = 2 * sum / n;
}

double MicrofacetAlbedoTable::albedo(double mu) const {
  const int n = int(m_albedo.size());
  const double x = std::clamp(mu, 0.0, 1.0) * n - 0.5;
  if (x <= 0) return m_albedo.front();
  if (x >= n - 1) return m_albedo.back();
  const int k = int(x);
  const double t = x - k;
  return m_albedo[k] * (1 - t) + m_albedo[k + 1] * t;
}

double MicrofacetAlbedoTable::multipleScattering(double muO, double muI) const {
  if (muO <= 0 || muI <= 0 || m_average >= 1) return 0;
  return (1 - albedo(muO)) * (1 - albedo(muI)) / (M_PI * (1 - m_average));
}

Vec3 multipleScatteringFresnel(const Vec3& f0, double averageAlbedo) {
  Vec3 out;
  for (int c = 0; c < 3; ++c) {
    const double fAvg = f0[c] + (1 - f0[c]) / 21;  // hemispherical average of Schlick's F
    out[c] = fAvg * fAvg * averageAlbedo / (1 - fAvg * (1 - averageAlbedo));
  }
  return out;
}

}  // namespace radkit
