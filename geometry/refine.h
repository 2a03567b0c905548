// Element refinement for adaptive meshing: split chosen patches into four and find each
// patch's neighbours on its surface, T-junctions included.
#pragma once

#include <vector>

#include "geometry/patch_mesh.h"

namespace radkit {

/// A refined mesh and where each of its patches came from.
struct RefinedMesh {
  PatchMesh mesh;
  std::vector<int> parent;  ///< parent[k]: the input patch that patch k is (or is a quarter of)
};

/// \brief Splits every patch i with split[i] into four at its edge midpoints: a quad into four
/// quads around its vertex mean, a triangle into four similar triangles. Other patches are
/// copied. Patches stay grouped by surface in scene order; midpoint vertices are shared
/// between neighbours that split the same edge (found by exact coordinates, since
/// (a + b)/2 rounds the same either way). A neighbour left whole gets a T-junction: the
/// midpoint lies on its edge but is not one of its corners. The four children tile the parent
/// exactly (planar parent), so areas still sum to the surface area.
/// \param split one flag per patch of mesh (size mesh.size())
RefinedMesh refinePatches(const PatchMesh& mesh, const std::vector<char>& split);

/// \brief For each patch, the patches of the same surface that touch it: they share a corner,
/// or a corner of one is a (repeated) edge midpoint of the other, i.e. a T-junction left by
/// refinePatches. Sorted, without the patch itself.
std::vector<std::vector<int>> surfaceNeighbours(const PatchMesh& mesh);

}  // namespace radkit
