#include "util/photometry.h"

#include "util/format.h"

namespace radkit {

void checkEmission(const std::string& key, const Vec3& value) {
  for (double c : {value.x, value.y, value.z}) {
    if (c < 0)
      throw ParamError("\"" + key +
                       "\" must not be negative (light cannot be taken away). Fix: give 0 or more");
    if (c != 0 && !(c >= kMinEmission && c <= kMaxEmission))
      throw ParamError("\"" + key + "\" " + formatNumber(c) + " is outside [" +
                       formatNumber(kMinEmission) + ", " + formatNumber(kMaxEmission) +
                       "], where results stay finite. Fix: give it in a unit that brings it into "
                       "range");
  }
}

Vec3 radianceOrLuminance(Params& params, const std::string& radianceKey,
                         const std::string& luminanceKey) {
  const bool radianceGiven = params.has(radianceKey);
  if (radianceGiven == params.has(luminanceKey))
    throw ParamError("needs exactly one of \"" + radianceKey + "\" (W m⁻² sr⁻¹) and \"" +
                     luminanceKey + "\" (cd/m²)");
  // Both are read, so that a message about an unused key lists both.
  const Vec3 radiance = params.rgb(radianceKey, {0, 0, 0});
  const double l = params.number(luminanceKey, 0) / kLumensPerWatt;
  if (radianceGiven) {
    checkEmission(radianceKey, radiance);
    return radiance;
  }
  checkEmission(luminanceKey, {l, l, l});
  return {l, l, l};
}

}  // namespace radkit
