// formfactors.png: the F matrix as a heat map in patch order, grouped by surface.
#pragma once

#include <string>
#include <vector>

#include "geometry/patch_mesh.h"
#include "solvers/matrix.h"
#include "util/canvas.h"

namespace radkit {

struct HeatMapSettings {
  int matrixPixels = 800;  ///< target side of the matrix area in pixels
  double decades = 6;      ///< log colour scale spans at most this many decades below max
  int fontScale = 2;       ///< stb_easy_font pixels per font unit
  std::string title;       ///< drawn above the matrix when non-empty
};

/// \brief Writes the heat map as PNG (path + ".tmp", then renamed). Row i, column j shows
/// F_ij on a log10 colour scale (viridis; exact zeros light grey), with a colour bar and its
/// decade labels, red lines at surface boundaries and surface names along both axes (names
/// that would overlap their neighbour are left out). With n patches and n <= matrixPixels,
/// each patch gets floor(matrixPixels/n) pixels; above that, each pixel shows the MEAN of
/// the b×b block of F it covers (b = ceil(n/matrixPixels)), so a pixel is the average
/// coupling of the patches it stands for, zeros included.
void writeFormFactorHeatMap(const std::string& path, const PatchMesh& mesh,
                            const std::vector<std::string>& surfaceNames, const FormFactorMatrix& f,
                            const HeatMapSettings& settings = {});

/// A log10 colour scale over whole decades [10^lo, 10^hi] (viridis; zeros light grey), spanning
/// at most `decades` below the largest value; shared by the F heat map and the link matrix.
struct LogColourScale {
  int lo = -1, hi = 0;
  LogColourScale(const std::vector<double>& values, double decades);
  Rgb8 colour(double v) const;
  /// A vertical bar of `side` pixels at (x, top), a label per decade and the legend above.
  void drawBar(Canvas& canvas, int x, int top, int side, const std::string& legend,
               int fontScale) const;
};

}  // namespace radkit
