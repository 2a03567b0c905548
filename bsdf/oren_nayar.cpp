// Oren-Nayar rough diffuse reflection, the qualitative model of Oren & Nayar 1994 (eq. 30, as
// in pbrt-v3 §8.4.2): f = R/π (A + B max(0, cos(φi − φo)) sin α tan β), α = max(θi, θo),
// β = min(θi, θo), A = 1 − σ²/(2(σ² + 0.33)), B = 0.45 σ²/(σ² + 0.09), σ the slope deviation.
// Sampled by cosine; radiosity sees the Lambertian albedo with the same reflected power
// under uniform light, the bihemispherical albedo ρ_bh = (1/π) ∫∫ f cos θi cos θo dωi dωo.
// This file, one line in bsdf/registry.cpp and one in bsdf/CMakeLists.txt are all it takes
// (docs/extending.md).
#include <cmath>
#include <cstdio>

#include "bsdf/bsdf.h"
#include "util/frame.h"

namespace radkit {

namespace {

class OrenNayarBsdf final : public Bsdf {
 public:
  OrenNayarBsdf(const Vec3& reflectance, double sigmaDeg) : m_r(reflectance), m_sigmaDeg(sigmaDeg) {
    const double s2 = std::pow(sigmaDeg * M_PI / 180, 2);
    m_a = 1 - s2 / (2 * (s2 + 0.33));
    m_b = 0.45 * s2 / (s2 + 0.09);
    m_albedo = m_r * bihemisphericalFactor();
  }

  Vec3 eval(const Vec3& wo, const Vec3& wi) const override {
    if (wo.z <= 0 || wi.z <= 0) return {};
    return m_r * (factor(wo, wi) / M_PI);
  }

  std::optional<BsdfSample> sample(const Vec3& wo, double, double u1, double u2) const override {
    if (wo.z <= 0) return std::nullopt;
    return mixtureSample(wo, sampleCosineHemisphere(u1, u2));
  }

  double pdf(const Vec3& wo, const Vec3& wi) const override {
    return wo.z > 0 ? cosineHemispherePdf(wi) : 0.0;
  }

  Vec3 diffuseAlbedo() const override { return m_albedo; }

  std::string describe() const override {
    char buf[160];
    std::snprintf(buf, sizeof buf,
                  "oren-nayar(reflectance=[%g, %g, %g], sigma=%g deg, albedo=[%g, %g, %g])", m_r.x,
                  m_r.y, m_r.z, m_sigmaDeg, m_albedo.x, m_albedo.y, m_albedo.z);
    return buf;
  }

 private:
  /// A + B max(0, cos Δφ) sin α tan β for unit local directions above the surface.
  double factor(const Vec3& wo, const Vec3& wi) const {
    const double sinO = std::sqrt(std::max(0.0, 1 - wo.z * wo.z)),
                 sinI = std::sqrt(std::max(0.0, 1 - wi.z * wi.z));
    double cosDphi = 0;
    if (sinO > 1e-9 && sinI > 1e-9) cosDphi = (wo.x * wi.x + wo.y * wi.y) / (sinO * sinI);
    // α is the larger polar angle (smaller cosine), β the smaller.
    const double sinAlpha = wi.z < wo.z ? sinI : sinO;
    const double tanBeta = wi.z < wo.z ? sinO / wo.z : sinI / wi.z;
    return m_a + m_b * std::max(0.0, cosDphi) * sinAlpha * tanBeta;
  }

  /// (1/π²) ∫∫ factor cos θi cos θo dωi dωo by the midpoint rule in (cos² θi, cos² θo, Δφ),
  /// where cos θ dω = ½ d(cos² θ) dφ makes the weights uniform (48³ nodes; tests/bsdf/
  /// registry_test.cpp checks it against Monte Carlo).
  double bihemisphericalFactor() const {
    constexpr int n = 48;
    double sum = 0;
    for (int i = 0; i < n; ++i)
      for (int o = 0; o < n; ++o) {
        const double ci = std::sqrt((i + 0.5) / n), co = std::sqrt((o + 0.5) / n);
        const double si = std::sqrt(1 - ci * ci), so = std::sqrt(1 - co * co);
        for (int k = 0; k < n; ++k) {
          const double phi = M_PI * (k + 0.5) / n;  // Δφ in [0, π], symmetric
          sum += factor({so, 0, co}, {si * std::cos(phi), si * std::sin(phi), ci});
        }
      }
    return sum / (double(n) * n * n);
  }

  Vec3 m_r, m_albedo;
  double m_sigmaDeg, m_a, m_b;
};

}  // namespace

std::unique_ptr<Bsdf> createOrenNayar(Params& p, const BsdfSettings&) {
  const Vec3 r = p.rgb("reflectance", {0.5, 0.5, 0.5});
  Params::checkAlbedo("reflectance", r);
  return std::make_unique<OrenNayarBsdf>(r, p.number("sigma", 20, 0, 90, false, true));
}

}  // namespace radkit
