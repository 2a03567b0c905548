// Photometry and the bounds of light, shared by every floor: 683 lm/W at 555 nm as in
// docs/formats.md, photometric = 683 × the Rec. 709 luminance of radiometric (Y(1, 1, 1) = 1, so
// white light of luminance L has radiance L/683 in every channel); and the range of an emission
// inside which results stay finite.
#pragma once

#include <string>

#include "util/params.h"
#include "util/vec3.h"

namespace radkit {

constexpr double kLumensPerWatt = 683.0;
/// An emission outside [kMinEmission, kMaxEmission] (other than 0) overflows or underflows
/// somewhere between the form factors and surfaces.csv: a sun of 1e308 wrote inf.
constexpr double kMinEmission = 1e-60, kMaxEmission = 1e60;

/// \brief Each channel of a light (radiance, irradiance) read as `key` is 0 or in
///        [kMinEmission, kMaxEmission]. \throws ParamError naming the key and the fix.
void checkEmission(const std::string& key, const Vec3& value);

/// \brief A plugin's brightness given either as radiance (W m⁻² sr⁻¹, an RGB triple or one
///        number) under `radianceKey` or as luminance (cd/m², white) under `luminanceKey`:
///        exactly one of the two. Checked by checkEmission.
Vec3 radianceOrLuminance(Params& params, const std::string& radianceKey,
                         const std::string& luminanceKey);

}  // namespace radkit
