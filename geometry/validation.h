// Validation of a loaded scene: every check that names the file, surface and element.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "geometry/scene.h"
#include "geometry/scene_loader.h"
#include "util/photometry.h"

namespace radkit {

/// Relative non-planarity (distance from the best plane over the polygon's diameter) above
/// which a polygon is split into triangles, with a warning.
constexpr double kPlanarityTolerance = 1e-7;

/// \brief Checks and normalises a scene in place; throws InputError on the first error.
/// Errors: empty scene, no surfaces with faces, NaN/infinite coordinates, reflectance
/// outside [0,1), negative or non-finite emission, unknown material, degenerate (collinear,
/// exact predicate) or zero-area faces, repeated vertices, non-manifold edges or a one-sided
/// (non-orientable) surface, duplicate surface names.
/// Repairs, with a warning: faces wound against their neighbours are reversed (CGAL's
/// orient_polygon_soup), each edge-connected part keeping the winding most of its faces had.
/// Normalises: polygons with more than four vertices, non-convex and non-planar quads are
/// triangulated (non-planar ones with a warning). Warns on self-intersections (CGAL) unless
/// `settings` skip that check. Edge checks run in linear time and memory, face checks in
/// parallel.
/// `repair`: each surface first goes through repairMesh, which turns repeated and degenerate
/// faces and non-manifold edges into repairs (LoadReport::repairs) instead of errors.
/// What validateScene may leave out, and where it reports progress.
struct ValidationSettings {
  bool selfIntersections = true;  ///< LoadOptions::selfIntersections
  /// Per surface (by index; shorter means true): false skips its self-intersection check
  /// (a surface's "check_self_intersections": false).
  std::vector<bool> surfaceSelfIntersections;
  /// A stage ("checking NAME", "self-intersections NAME") and the fraction done.
  std::function<void(const std::string&, double)> progress;
};
void validateScene(Scene& scene, LoadReport& report, bool repair = false,
                   const ValidationSettings& settings = {});

/// \brief Repairs a surface with CGAL's polygon mesh processing: welds vertices at one
/// position, drops faces repeating a vertex or of zero area (exact predicate) and duplicate
/// faces of the same winding, cuts non-manifold edges and vertices (orient_polygon_soup,
/// duplicate_non_manifold_vertices), stitches coincident borders, and winds each
/// edge-connected part the way most of its faces were. Face indices are renumbered.
MeshRepair repairMesh(Surface& surface);

/// Largest |coordinate| validateScene accepts (scene units).
constexpr double kMaxCoordinate = 1e15;

// kMinEmission and kMaxEmission (util/photometry.h) bound a non-zero emission: with areas up to
// kMaxCoordinate² and squared powers in the error estimates, every result stays a normal double.

/// Reports exact self-intersections between non-adjacent faces of one surface (CGAL PMP).
/// Returns the number of intersecting face pairs found (0 when clean).
/// `progress` hears the fraction done after each of its steps.
std::size_t countSelfIntersections(const Surface& surface,
                                   const std::function<void(double)>& progress = {});

}  // namespace radkit
