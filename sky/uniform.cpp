// The uniform sky: the same radiance from every direction above the horizon.
#include <cmath>

#include "sky/sky_radiance.h"
#include "util/photometry.h"

namespace radkit {

namespace {

class UniformSky final : public SkyRadiance {
 public:
  explicit UniformSky(const Vec3& radiance) : m_radiance(radiance) {}
  Vec3 radiance(const Vec3&) const override { return m_radiance; }
  Vec3 horizontalIrradiance() const override { return m_radiance * M_PI; }

 private:
  Vec3 m_radiance;
};

}  // namespace

std::unique_ptr<SkyRadiance> createUniformSky(Params& params) {
  return std::make_unique<UniformSky>(radianceOrLuminance(params, "radiance", "luminance"));
}

}  // namespace radkit
