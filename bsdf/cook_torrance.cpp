// Cook-Torrance with GGX (metallic-roughness parameters):
//   f = (1 − metallic) base / π + D(h) G(ωo, ωi) F(ωi·h) / (4 μo μi)  [+ F_ms f_ms]
// D, G: bsdf/microfacet.h; F: Schlick with F0 = lerp(f0, base, metallic); f_ms: the
// optional Kulla-Conty lobe. Sampling mixes three strategies, chosen by u0 with chances
// that depend on wo alone: visible normals for the specular lobe (pdf G1(ωo) D(h) / (4 μo):
// Heitz 2018, eq. 17, times the reflection Jacobian 1/(4 ωo·h)) and cosine-weighted
// directions for the diffuse and multiple-scattering lobes.
#include <algorithm>
#include <cstdio>

#include "bsdf/bsdf.h"
#include "bsdf/specular.h"
#include "util/frame.h"

namespace radkit {

namespace {

class CookTorranceBsdf final : public Bsdf {
 public:
  CookTorranceBsdf(const Vec3& base, double metallic, double roughness, const Vec3& f0,
                   const BsdfSettings& s)
      : m_diffuse(base * (1 - metallic)),
        m_f0(f0 * (1 - metallic) + base * metallic),
        m_roughness(roughness),
        m_ggx(roughness * roughness),
        m_masking(s.masking) {
    if (s.compensated) {
      m_table = std::make_unique<MicrofacetAlbedoTable>(m_ggx, m_masking, s.albedoTableSize);
      m_msColour = multipleScatteringFresnel(m_f0, m_table->average());
    }
  }

  Vec3 eval(const Vec3& wo, const Vec3& wi) const override {
    if (wo.z <= 0 || wi.z <= 0) return {};
    const Vec3 h = normalize(wo + wi);
    const double dg = m_ggx.D(h) * m_ggx.G(wo, wi, m_masking) / (4 * wo.z * wi.z);
    Vec3 f = m_diffuse / M_PI + fresnelSchlick(m_f0, dot(wi, h)) * dg;
    if (m_table) f += m_msColour * m_table->multipleScattering(wo.z, wi.z);
    return f;
  }

  std::optional<BsdfSample> sample(const Vec3& wo, double u0, double u1, double u2) const override {
    if (wo.z <= 0) return std::nullopt;
    if (u0 >= specularChance(wo)) return mixtureSample(wo, sampleCosineHemisphere(u1, u2));
    const Vec3 m = m_ggx.sampleVisibleNormal(wo, u1, u2);
    return mixtureSample(wo, m * (2 * dot(wo, m)) - wo);
  }

  double pdf(const Vec3& wo, const Vec3& wi) const override {
    if (wo.z <= 0 || wi.z <= 0) return 0;
    const Vec3 h = normalize(wo + wi);
    const double ps = specularChance(wo);
    const double specular = m_ggx.visibleNormalPdf(wo, h) / (4 * dot(wo, h));
    return ps * specular + (1 - ps) * wi.z / M_PI;
  }

  Vec3 diffuseAlbedo() const override { return m_diffuse; }

  std::optional<GlossyLobe> glossyLobe() const override {
    return GlossyLobe{GlossyLobe::Family::Microfacet, m_diffuse, m_f0, m_ggx.alpha()};
  }

  std::string describe() const override {
    char buf[256];
    std::snprintf(
        buf, sizeof buf,
        "cook-torrance(diffuse=[%g, %g, %g], F0=[%g, %g, %g], roughness=%g, alpha=%g, G=%s%s)",
        m_diffuse.x, m_diffuse.y, m_diffuse.z, m_f0.x, m_f0.y, m_f0.z, m_roughness, m_ggx.alpha(),
        maskingShadowingName(m_masking), m_table ? ", Kulla-Conty" : "");
    return buf;
  }

 private:
  /// Chance of sampling visible normals: the specular lobe's share of an albedo estimate
  /// (Schlick F at μo against the diffuse and multiple-scattering albedos).
  double specularChance(const Vec3& wo) const {
    const double specular = meanComponent(fresnelSchlick(m_f0, wo.z));
    double rest = meanComponent(m_diffuse);
    if (m_table) rest += meanComponent(m_msColour) * (1 - m_table->albedo(wo.z));
    return specular + rest > 0 ? std::clamp(specular / (specular + rest), 0.05, 1.0) : 1.0;
  }

  Vec3 m_diffuse, m_f0;
  double m_roughness;
  GgxDistribution m_ggx;
  MaskingShadowing m_masking;
  std::unique_ptr<MicrofacetAlbedoTable> m_table;
  Vec3 m_msColour;
};

}  // namespace

std::unique_ptr<Bsdf> makeCookTorranceBsdf(const Vec3& base, double metallic, double roughness,
                                           const Vec3& f0, const BsdfSettings& settings) {
  return std::make_unique<CookTorranceBsdf>(base, metallic, roughness, f0, settings);
}

std::unique_ptr<Bsdf> createCookTorrance(Params& p, const BsdfSettings& settings) {
  const Vec3 base = p.rgb({"base_color", "reflectance"}, {0.5, 0.5, 0.5});
  Params::checkAlbedo("base_color", base);
  const double metallic = p.number("metallic", 0, 0, 1);
  const double roughness =
      p.number("roughness", 0.5, 0, 1, true, false,
               "use a small value such as 0.01 for a near-mirror, or brdf \"mirror\"");
  if (p.has("f0") && p.has("ior")) throw ParamError("gives both \"f0\" and \"ior\". Fix: give one");
  Vec3 f0{0.04, 0.04, 0.04};
  if (p.has("ior")) {
    const double ior = p.number("ior", 1.5, 1, 10, true, true);
    const double r = (ior - 1) / (ior + 1);  // Schlick's F0 from the index of refraction
    f0 = Vec3{1, 1, 1} * (r * r);
  }
  f0 = p.rgb("f0", f0);
  Params::checkUnit("f0", f0);
  return makeCookTorranceBsdf(base, metallic, roughness, f0, settings);
}

}  // namespace radkit
