// Smooth reconstruction of a piecewise-constant radiosity solution that never blurs across a
// crease or a shadow edge: each patch corner takes the area-weighted mean of only those
// patches around the vertex that lie on the same surface, face within a crease angle of the
// patch and agree with it within their error (discontinuity meshing's spirit: where
// neighbours disagree by more than the solution can explain, the jump is kept). Works on any
// PatchMesh, so uniform meshes and hierarchical leaves alike get it.
#pragma once

#include <array>
#include <vector>

#include "geometry/patch_mesh.h"

namespace radkit {

struct SmoothSettings {
  double creaseAngleDeg = 30;  ///< neighbours whose normals differ by more are not averaged
  /// Error of a patch's B when none is given: this fraction of its luminance. Neighbours whose
  /// luminances differ by more than `errorMultiple` × the combined error keep their own values.
  double relativeError = 0.1;
  double errorMultiple = 3;
};

/// The reconstruction: B per patch and the reconstructed B at each of its corners.
class SmoothRadiosity {
 public:
  /// \param error per-patch standard error of B (luminance units), or empty for
  ///        settings.relativeError × Y(B).
  SmoothRadiosity(const PatchMesh& mesh, const std::vector<Vec3>& radiosity,
                  const SmoothSettings& settings = {}, const std::vector<double>& error = {});

  /// \brief B at a point of patch p: the patch value plus the mean-value interpolation of the
  /// corners' departures from it, so a patch whose corners all equal it returns it exactly.
  Vec3 at(int patch, const Vec3& point) const;
  const std::array<Vec3, 4>& corners(int patch) const { return m_corner[patch]; }

 private:
  const PatchMesh& m_mesh;
  std::vector<Vec3> m_patch;
  std::vector<std::array<Vec3, 4>> m_corner;
};

/// \brief SmoothRadiosity's corner values for polygons given as point indices (the viewer's
/// patches.vtp): one value per polygon corner, polygon by polygon, so a display that
/// interpolates between corners gets the same crease, surface and jump rule as render.png.
/// Polygons need not share points; ones with more than 4 corners stay flat.
std::vector<Vec3> smoothCornerValues(const std::vector<Vec3>& points,
                                     const std::vector<std::vector<int>>& polygons,
                                     const std::vector<int>& surface,
                                     const std::vector<Vec3>& perPatch,
                                     const SmoothSettings& settings = {});
/// \brief The same for a scalar per patch (false colour, a row of F): it is smoothed as the
/// grey Vec3{v, v, v}, whose luminance is v.
std::vector<double> smoothCornerValues(const std::vector<Vec3>& points,
                                       const std::vector<std::vector<int>>& polygons,
                                       const std::vector<int>& surface,
                                       const std::vector<double>& perPatch,
                                       const SmoothSettings& settings = {});

/// \brief Mean value coordinates of x in a convex planar polygon (Floater 2003): smooth inside,
/// linear on the edges, the barycentric coordinates for a triangle. `count` is 3 or 4.
std::array<double, 4> meanValueCoordinates(const Vec3* poly, int count, const Vec3& x);

}  // namespace radkit
