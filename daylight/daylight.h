// Daylight on patches: each patch's irradiance from the sky (visibility rays weighted by the
// sky's radiance) and from the sun (shadow rays to its disc), and its sky view factor. The
// radiosity pipeline adds ρ times this light to the patches' emission and solves as usual.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "daylight/sky.h"
#include "geometry/patch_mesh.h"
#include "geometry/ray_scene.h"

namespace radkit {

struct Daylight {
  std::vector<Vec3> sky;              ///< W/m² per patch, the ground's glow included
  std::vector<Vec3> sun;              ///< W/m² per patch, direct sun
  std::vector<double> skyViewFactor;  ///< (1/π)∫ V cos θ dω over the sky above the horizon
  /// Per patch, the standard error of sky[i] (channel sum) from its samples' spread, as if
  /// independent (the Latin-hypercube samples used are never worse, up to N/(N − 1)).
  std::vector<double> skyStandardError;
  std::vector<double> skyViewFactorStandardError;
  /// Area-weighted median of skyStandardError / sky over patches the sky lights.
  double skyNoise = 0;
  long long rays = 0;
  double seconds = 0;

  Vec3 total(int i) const { return sky[i] + sun[i]; }
};

/// \brief The area-weighted median of (value, area) pairs (Daylight::skyNoise); 0 when empty.
double areaWeightedMedian(std::vector<std::pair<double, double>> values);

/// \brief Daylight of every patch of `mesh` (front sides only, as radiosity's patches
/// receive): `sky.description().samples` sky rays and `sunSamples` sun rays per patch, on
/// Latin-hypercube points of the patch and of the cosine-weighted hemisphere (or the sun's
/// disc). Parallel over patches; deterministic for a given seed whatever the thread count.
Daylight computeDaylight(const PatchMesh& mesh, const RayScene& rays, const SkyModel& sky,
                         std::uint64_t seed);

}  // namespace radkit
