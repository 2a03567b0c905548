// Photon map against radiosity: the per-surface comparison table (comparison.csv) and a
// picture of where the two disagree (difference.png).
#pragma once

#include <string>
#include <vector>

#include "photon/estimate.h"
#include "render/radiosity_image.h"
#include "util/canvas.h"

namespace radkit {

/// One named surface's radiosity, as `radkit run` writes it to surfaces.csv.
struct SurfaceRadiosity {
  std::string name;
  double area = 0;  ///< scene units²
  Vec3 radiosity;   ///< W/m²
};

/// \brief Reads `surface,area,b_r,b_g,b_b[,...]` (docs/formats.md). Throws std::runtime_error
/// naming the file, the line and what to fix.
std::vector<SurfaceRadiosity> readSurfacesCsv(const std::string& path);

/// One row of comparison.csv.
struct SurfaceComparison {
  std::string name;
  double area = 0;           ///< scene units²
  Vec3 photon, photonError;  ///< photon-map B and its estimated standard error
  Vec3 radiosity;            ///< the radiosity solution's B
  Vec3 relativeDifference;   ///< (photon − radiosity)/radiosity, 0 where radiosity is 0
  Vec3 zScore;               ///< (photon − radiosity)/photonError, 0 where the error is 0
};

/// \brief Pairs surfaces by name. Throws std::invalid_argument naming the first surface of
/// the photon run missing from `radiosity` (a run of another scene).
std::vector<SurfaceComparison> compareSurfaces(const std::vector<SurfaceEstimate>& photon,
                                               const std::vector<SurfaceRadiosity>& radiosity);

/// \brief Writes
/// `surface,area,photon_b_r,...,radiosity_b_r,...,rel_diff_r,...,photon_se_r,...,z_r,...`.
void writeComparisonCsv(const std::string& path, const std::vector<SurfaceComparison>& rows);

/// \brief A false-colour image of z = (Y_photon − Y_radiosity)/σ_photon per pixel, Y the
/// luminance, from the values of the patch each pixel sees: blue below, white at zero, red
/// above, saturating at ±4 (where noise alone rarely goes), with a legend.
Canvas differenceImage(const RadianceImage& seen, const std::vector<Vec3>& photon,
                       const std::vector<Vec3>& photonError, const std::vector<Vec3>& radiosity,
                       const std::string& title);

}  // namespace radkit
