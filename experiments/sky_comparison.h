// The sky model against the brute-force reference (docs/atmosphere.md's table, `radkit sky
// --compare`): zenith and near-horizon radiance and the diffuse horizontal irradiance by
// single scattering, single plus multiple scattering, and the path tracer.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "atmosphere/atmosphere.h"

namespace radkit::atmosphere {

struct ComparisonSettings {
  std::vector<double> sunElevationsDeg{2, 10, 30, 60, 90};
  double sunAzimuthDeg = 180;
  double horizonElevationDeg = 2;  ///< the "horizon" rows' view elevation
  double altitude = 1;             ///< the observer's height above the ground (m)
  long long paths = 100000;        ///< reference paths per row
  std::uint64_t seed = 1;
  SkySettings sky;  ///< the model's sample counts (multipleScattering ignored)
  /// The model's single scattering again with these counts, to tell the ray march's
  /// quadrature error from the missing orders.
  SkySettings fine{256, 64, false};
};

struct ComparisonRow {
  double sunElevationDeg = 0;
  std::string quantity;  ///< "zenith", "horizon toward sun", "horizon away from sun", "irradiance"
  Vec3 direction;        ///< local frame; (0, 0, 1) for the irradiance
  Vec3 singleScattering, singleScatteringFine, withMultipleScattering;
  ReferenceEstimate reference;
  double seconds = 0;  ///< the reference's
};

/// \brief The rows for every sun elevation. The irradiance is the model's radiance
/// integrated over the upper hemisphere (midpoint rule in sin²(elevation's complement) and
/// azimuth, 64 × 128, which weights by cos θ) and the reference's referenceHorizontalIrradiance.
/// Each row's reference uses its own seed (seed + row index).
std::vector<ComparisonRow> compareWithReference(const Atmosphere& atmosphere,
                                                const ComparisonSettings& settings);

/// The rows as a Markdown table: per channel (R, G, B) the relative error of each model
/// against the reference, the reference's relative standard error, and |z| of SS+MS.
std::string comparisonMarkdown(const std::vector<ComparisonRow>& rows);

/// The model's diffuse horizontal irradiance at p (planet frame, facing away from the centre).
Vec3 modelHorizontalIrradiance(const Atmosphere& atmosphere, const Vec3& p, const Vec3& sunDir,
                               const SkySettings& settings, int rings = 64);

}  // namespace radkit::atmosphere
