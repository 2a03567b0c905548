// More of the brute-force reference (referenceSkyRadiance is in atmosphere.h): the diffuse
// irradiance of a horizontal plane, by the same path tracer.
#pragma once

#include "atmosphere/atmosphere.h"

namespace radkit::atmosphere {

/// \brief Irradiance (W/m² per channel) that the sky alone (the sun's direct beam excluded)
/// gives a horizontal plane at p facing away from the planet's centre: the path tracer from
/// cosine-weighted directions, each path's estimate π·L. Mean and standard error over `paths`.
ReferenceEstimate referenceHorizontalIrradiance(const Atmosphere& atmosphere, const Vec3& p,
                                                const Vec3& sunDir, long long paths,
                                                std::uint64_t seed);

}  // namespace radkit::atmosphere
