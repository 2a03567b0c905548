// Lambertian reflection: f = ρ/π, sampled in proportion to cos θ (Nori's diffuse.cpp).
#include <cstdio>

#include "bsdf/bsdf.h"
#include "util/frame.h"

namespace radkit {

namespace {

class LambertBsdf final : public Bsdf {
 public:
  explicit LambertBsdf(const Vec3& albedo) : m_albedo(albedo) {}

  Vec3 eval(const Vec3& wo, const Vec3& wi) const override {
    if (wo.z <= 0 || wi.z <= 0) return {};
    return m_albedo / M_PI;
  }

  std::optional<BsdfSample> sample(const Vec3& wo, double, double u1, double u2) const override {
    if (wo.z <= 0) return std::nullopt;
    BsdfSample s;
    s.wi = sampleCosineHemisphere(u1, u2);
    s.pdf = cosineHemispherePdf(s.wi);
    if (!(s.pdf > 0)) return std::nullopt;
    // f cos θ / pdf = (ρ/π) cos θ / (cos θ/π) = ρ: the cosine cancels.
    s.weight = m_albedo;
    return s;
  }

  double pdf(const Vec3& wo, const Vec3& wi) const override {
    return wo.z > 0 ? cosineHemispherePdf(wi) : 0.0;
  }

  Vec3 diffuseAlbedo() const override { return m_albedo; }
  bool lambertian() const override { return true; }
  bool choosesLobe() const override { return false; }

  std::string describe() const override {
    char buf[128];
    std::snprintf(buf, sizeof buf, "lambert(albedo=[%g, %g, %g])", m_albedo.x, m_albedo.y,
                  m_albedo.z);
    return buf;
  }

 private:
  Vec3 m_albedo;
};

}  // namespace

std::unique_ptr<Bsdf> makeLambertBsdf(const Vec3& albedo) {
  return std::make_unique<LambertBsdf>(albedo);
}

std::unique_ptr<Bsdf> createLambert(Params& p, const BsdfSettings&) {
  const Vec3 albedo = p.rgb("reflectance", {0.5, 0.5, 0.5});
  Params::checkAlbedo("reflectance", albedo);
  return makeLambertBsdf(albedo);
}

}  // namespace radkit
