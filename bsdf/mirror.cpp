// Perfect mirror: a Dirac lobe in the reflected direction, tinted by a colour.
#include <cstdio>

#include "bsdf/bsdf.h"

namespace radkit {

namespace {

class MirrorBsdf final : public Bsdf {
 public:
  explicit MirrorBsdf(const Vec3& colour) : m_colour(colour) {}

  Vec3 eval(const Vec3&, const Vec3&) const override { return {}; }
  double pdf(const Vec3&, const Vec3&) const override { return 0; }
  bool isDelta() const override { return true; }

  std::optional<BsdfSample> sample(const Vec3& wo, double, double, double) const override {
    if (wo.z <= 0) return std::nullopt;
    // f = colour δ(ωi − R(ωo)) / cos θi, so the weight f cos θi / pdf is the colour.
    return BsdfSample{Vec3{-wo.x, -wo.y, wo.z}, m_colour, 1.0, true};
  }

  std::string describe() const override {
    char buf[128];
    std::snprintf(buf, sizeof buf, "mirror(colour=[%g, %g, %g])", m_colour.x, m_colour.y,
                  m_colour.z);
    return buf;
  }

 private:
  Vec3 m_colour;
};

}  // namespace

std::unique_ptr<Bsdf> makeMirrorBsdf(const Vec3& colour) {
  return std::make_unique<MirrorBsdf>(colour);
}

std::unique_ptr<Bsdf> createMirror(Params& p, const BsdfSettings&) {
  const Vec3 colour = p.rgb("specular", {1, 1, 1});
  Params::checkUnit("specular", colour);
  return makeMirrorBsdf(colour);
}

}  // namespace radkit
