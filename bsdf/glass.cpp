// Smooth dielectric: Fresnel-weighted choice between mirror reflection and refraction
// (pbrt-v4 DielectricBxDF with roughness 0). Radiance is scaled by 1/η² across the
// interface (pbrt-v4, TransportMode::Radiance), so a closed glass object leaves it unchanged.
#include <cstdio>

#include "bsdf/bsdf.h"
#include "bsdf/specular.h"

namespace radkit {

namespace {

class GlassBsdf final : public Bsdf {
 public:
  explicit GlassBsdf(double eta) : m_eta(eta) {}

  Vec3 eval(const Vec3&, const Vec3&) const override { return {}; }
  double pdf(const Vec3&, const Vec3&) const override { return 0; }
  bool isDelta() const override { return true; }
  bool transmits() const override { return true; }

  std::optional<BsdfSample> sample(const Vec3& wo, double u0, double, double) const override {
    if (wo.z == 0) return std::nullopt;
    const double f = fresnelDielectric(wo.z, m_eta);
    if (u0 < f) return BsdfSample{Vec3{-wo.x, -wo.y, wo.z}, Vec3{1, 1, 1}, f, true};
    // Entering (wo outside, wo.z > 0) the relative index is η, leaving it is 1/η.
    const bool entering = wo.z > 0;
    const double etaRel = entering ? m_eta : 1 / m_eta;
    Vec3 wt;
    if (!refract(wo, Vec3{0, 0, entering ? 1.0 : -1.0}, etaRel, wt)) return std::nullopt;
    BsdfSample s{wt, Vec3{1, 1, 1} / (etaRel * etaRel), 1 - f, true};
    s.radianceScale = 1 / (etaRel * etaRel);
    return s;
  }

  std::string describe() const override {
    char buf[64];
    std::snprintf(buf, sizeof buf, "glass(ior=%g)", m_eta);
    return buf;
  }

 private:
  double m_eta;
};

}  // namespace

std::unique_ptr<Bsdf> makeGlassBsdf(double eta) { return std::make_unique<GlassBsdf>(eta); }

std::unique_ptr<Bsdf> createGlass(Params& p, const BsdfSettings&) {
  return makeGlassBsdf(p.number("ior", 1.5, 1, 10, true, true));
}

}  // namespace radkit
