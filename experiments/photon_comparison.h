// Photon map against radiosity: the per-surface comparison (written as comparison.csv by
// output/run_files.h) and a picture of where the two disagree (difference.png).
#pragma once

#include <string>
#include <vector>

#include "output/run_files.h"  // SurfaceRadiosity, SurfaceComparison
#include "photon/estimate.h"
#include "render/radiosity_image.h"
#include "util/canvas.h"

namespace radkit {

/// \brief Pairs surfaces by name. Throws std::invalid_argument naming the first surface of
/// the photon run missing from `radiosity` (a run of another scene).
std::vector<SurfaceComparison> compareSurfaces(const std::vector<SurfaceEstimate>& photon,
                                               const std::vector<SurfaceRadiosity>& radiosity);

/// \brief A false-colour image of z = (Y_photon − Y_radiosity)/σ_photon per pixel, Y the
/// luminance, from the values of the patch each pixel sees: blue below, white at zero, red
/// above, saturating at ±4 (where noise alone rarely goes), with a legend.
Canvas differenceImage(const RadianceImage& seen, const std::vector<Vec3>& photon,
                       const std::vector<Vec3>& photonError, const std::vector<Vec3>& radiosity,
                       const std::string& title);

}  // namespace radkit
