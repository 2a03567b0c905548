// Scene loading: JSON scenes (docs/formats.md) and OBJ/MTL files given directly as the scene.
#pragma once

#include <functional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "geometry/scene.h"
#include "util/errors.h"

namespace radkit {

/// What the mesh repair (LoadOptions::repair) changed in one surface.
struct MeshRepair {
  std::string surface;                  ///< Surface::source
  std::size_t weldedVertices = 0;       ///< vertices at the position of an earlier one, merged
  std::size_t duplicateFaces = 0;       ///< faces repeating another (same winding), removed
  std::size_t degenerateFaces = 0;      ///< faces repeating a vertex or of zero area, removed
  std::size_t nonManifoldEdges = 0;     ///< edges of 3+ faces, cut so each side has at most 2
  std::size_t nonManifoldVertices = 0;  ///< vertices joining separate fans, split
  std::size_t stitchedEdges = 0;        ///< coincident border edges joined
  std::size_t reversedFaces = 0;        ///< faces re-wound to match their part's majority
  bool changed() const;
  std::string describe() const;  ///< "welded 3 duplicate vertices, removed 1 duplicate face"
};

/// Warnings collected while loading (non-planar polygons split, self-intersections, ...).
struct LoadReport {
  std::vector<std::string> warnings;
  std::vector<MeshRepair> repairs;  ///< surfaces the repair changed, in scene order
};

/// How to read a scene beyond what its file says.
struct LoadOptions {
  /// Length unit of the coordinates (m, cm, mm, km, in, ft); "" keeps the scene file's
  /// ("units" in JSON, metres for OBJ). Coordinates stay as written: reports convert.
  std::string units;
  /// Repair meshes with CGAL's polygon mesh processing (weld, drop duplicate and degenerate
  /// faces, cut non-manifold edges and vertices, stitch, orient) instead of refusing them.
  bool repair = false;
  /// Look for self-intersections in every surface (CGAL; a warning when found). The costliest
  /// check on a large mesh (about 8 s a million triangles): false skips it, for meshes known to
  /// be clean, as a surface's "check_self_intersections": false does for one surface.
  bool selfIntersections = true;
  /// Progress of the stages of loading (a stage name, the fraction done); may be empty.
  std::function<void(const std::string& stage, double fraction)> progress;
};

/// Units LoadOptions::units and a JSON scene's "units" accept, and their size in metres.
const std::vector<std::pair<std::string, double>>& knownUnits();

/// \brief Loads a scene file: `.json`, or `.obj` (with its MTL) as a whole scene.
/// Mesh surfaces (OBJ, PLY, OFF, STL) are read relative to the scene file. The result is
/// validated (see validation.h): every error throws InputError, warnings go to `report`.
Scene loadScene(const std::string& path, LoadReport* report = nullptr,
                const LoadOptions& options = {});

}  // namespace radkit
