// Energy-normalised (modified) Phong: f = kd/π + ks (n + 2)/(2π) cos^n α, α the angle
// between ωi and the mirror direction of ωo (Lafortune & Willems 1994). The (n + 2)/(2π)
// factor makes the specular albedo 1 at normal incidence and below 1 elsewhere, so
// kd + ks <= 1 conserves energy. Sampling picks a lobe in proportion to the mean of kd and
// ks; the specular lobe draws cos α = u^(1/(n+1)) around the mirror direction.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "bsdf/bsdf.h"
#include "util/frame.h"

namespace radkit {

namespace {

class PhongBsdf final : public Bsdf {
 public:
  PhongBsdf(const Vec3& kd, const Vec3& ks, double shininess)
      : m_kd(kd), m_ks(ks), m_n(std::max(0.0, shininess)) {
    const double d = meanComponent(kd), s = meanComponent(ks);
    m_diffuseChance = d + s > 0 ? d / (d + s) : 1.0;
  }

  Vec3 eval(const Vec3& wo, const Vec3& wi) const override {
    if (wo.z <= 0 || wi.z <= 0) return {};
    return m_kd / M_PI + m_ks * specularLobe(wo, wi);
  }

  std::optional<BsdfSample> sample(const Vec3& wo, double u0, double u1, double u2) const override {
    if (wo.z <= 0) return std::nullopt;
    if (u0 < m_diffuseChance) return mixtureSample(wo, sampleCosineHemisphere(u1, u2));
    // cos α = u^(1/(n+1)) has density (n + 1)/(2π) cos^n α about the mirror direction.
    const double cosA = std::pow(u1, 1 / (m_n + 1)),
                 sinA = std::sqrt(std::max(0.0, 1 - cosA * cosA));
    const double phi = 2 * M_PI * u2;
    return mixtureSample(
        wo, Frame(mirror(wo)).toWorld({sinA * std::cos(phi), sinA * std::sin(phi), cosA}));
  }

  double pdf(const Vec3& wo, const Vec3& wi) const override {
    if (wo.z <= 0 || wi.z <= 0) return 0;
    const double cosA = std::max(0.0, dot(wi, mirror(wo)));
    return m_diffuseChance * wi.z / M_PI +
           (1 - m_diffuseChance) * (m_n + 1) / (2 * M_PI) * std::pow(cosA, m_n);
  }

  Vec3 diffuseAlbedo() const override { return m_kd; }

  std::optional<GlossyLobe> glossyLobe() const override {
    return GlossyLobe{GlossyLobe::Family::Phong, m_kd, m_ks, std::sqrt(2 / (m_n + 2))};
  }

  std::string describe() const override {
    char buf[160];
    std::snprintf(buf, sizeof buf, "phong(kd=[%g, %g, %g], ks=[%g, %g, %g], n=%g)", m_kd.x, m_kd.y,
                  m_kd.z, m_ks.x, m_ks.y, m_ks.z, m_n);
    return buf;
  }

 private:
  static Vec3 mirror(const Vec3& wo) { return {-wo.x, -wo.y, wo.z}; }
  double specularLobe(const Vec3& wo, const Vec3& wi) const {
    const double cosA = std::max(0.0, dot(wi, mirror(wo)));
    return (m_n + 2) / (2 * M_PI) * std::pow(cosA, m_n);
  }

  Vec3 m_kd, m_ks;
  double m_n;
  double m_diffuseChance;
};

}  // namespace

std::unique_ptr<Bsdf> makePhongBsdf(const Vec3& kd, const Vec3& ks, double shininess) {
  return std::make_unique<PhongBsdf>(kd, ks, shininess);
}

std::unique_ptr<Bsdf> createPhong(Params& p, const BsdfSettings&) {
  const Vec3 kd = p.rgb({"kd", "reflectance"}, {0.5, 0.5, 0.5}), ks = p.rgb("ks", {0, 0, 0});
  const double n = p.number("shininess", 32, 0, 1e6);
  Params::checkAlbedo("kd", kd);
  Params::checkUnit("ks", ks);
  for (int c = 0; c < 3; ++c)
    if (!(kd[c] + ks[c] < 1))
      throw ParamError(
          "kd + ks = " + std::to_string(kd[c] + ks[c]) + " (channel " + std::to_string(c) +
          ") must stay below 1 for an energy-conserving Phong material. Fix: lower kd or ks.");
  return makePhongBsdf(kd, ks, n);
}

}  // namespace radkit
