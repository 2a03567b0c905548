// Image error against a reference render, region by region, with the reference's own noise
// taken out: given K ≥ 2 independent renders of the reference, their mean is the reference and
// the spread between them estimates its variance, which E[(x − r̄)²] = E[(x − truth)²] +
// Var(r̄) lets us subtract (x independent of the reference renders).
#pragma once

#include <string>
#include <vector>

#include "render/radiosity_image.h"

namespace radkit {

struct RegionError {
  std::string name;
  int pixels = 0;
  double referenceMean = 0;   ///< mean radiance over the region's pixels and channels
  double rawRmse = 0;         ///< √mean (x − r̄)² over pixels and channels
  double referenceNoise = 0;  ///< √mean Var(r̄): the reference's own RMS error
  double rmse = 0;            ///< √max(0, raw² − noise²): the image's error against the truth
  double relative() const { return referenceMean > 0 ? rmse / referenceMean : 0; }
};

/// \brief Errors of `image` against the mean of `references` (same size) over each region:
/// `region[k]` names pixel k's region by index into `names` (−1: in no region but "all").
/// The first row is "all" (every pixel). Throws std::invalid_argument on a size mismatch.
std::vector<RegionError> compareToReference(const RadianceImage& image,
                                            const std::vector<RadianceImage>& references,
                                            const std::vector<int>& region,
                                            const std::vector<std::string>& names);

/// \brief Regions of an image by what its pixels see: surface s where the 3 × 3 neighbourhood
/// shows s alone, `edgeRegion` where it shows more than one, −1 where the ray escapes.
std::vector<int> surfaceRegions(const std::vector<int>& pixelSurface, int width, int height,
                                int edgeRegion);

}  // namespace radkit
