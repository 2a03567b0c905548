// The CIE standard overcast sky (Moon and Spencer 1942; CIE S 011, type 16): radiance
// L(θ) = L_z (1 + 2 cos θ)/3 at zenith angle θ, the same at every azimuth.
#include <algorithm>
#include <cmath>

#include "sky/sky_radiance.h"
#include "util/photometry.h"

namespace radkit {

namespace {

class CieOvercastSky final : public SkyRadiance {
 public:
  explicit CieOvercastSky(const Vec3& zenith) : m_zenith(zenith) {}
  Vec3 radiance(const Vec3& local) const override {
    return m_zenith * ((1 + 2 * std::min(1.0, local.z)) / 3);
  }
  // ∫ L_z (1 + 2 cos θ)/3 cos θ dω = 2π L_z (1/2 + 2/3)/3 = 7π L_z / 9.
  Vec3 horizontalIrradiance() const override { return m_zenith * (7 * M_PI / 9); }

 private:
  Vec3 m_zenith;
};

}  // namespace

std::unique_ptr<SkyRadiance> createCieOvercastSky(Params& params) {
  return std::make_unique<CieOvercastSky>(
      radianceOrLuminance(params, "zenith_radiance", "zenith_luminance"));
}

}  // namespace radkit
