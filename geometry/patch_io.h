// Per-patch output files: patches.csv (columns in docs/formats.md) and a VTK XML PolyData (.vtp)
// file for ParaView, written as text without VTK (only viewer/ links VTK).
#pragma once

#include <string>
#include <vector>

#include "geometry/patch_mesh.h"
#include "geometry/scene.h"

namespace radkit {

/// \brief Writes `id,surface,area,cx,cy,cz,nx,ny,nz,rho_r,rho_g,rho_b,e_r,e_g,e_b,b_r,b_g,b_b`.
/// \param radiosity per-patch B (W/m²) or nullptr for zeros.
void writePatchesCsv(const std::string& path, const Scene& scene, const PatchMesh& mesh,
                     const std::vector<Vec3>* radiosity);

/// \brief Writes the patches as VTK XML PolyData with cell data: surface id, area,
/// reflectance, emission, radiosity (when given).
/// A named per-patch scalar written as cell data (hierarchical radiosity's level, links, ...).
struct CellArray {
  std::string name;
  std::vector<double> values;
};

void writePatchesVtp(const std::string& path, const Scene& scene, const PatchMesh& mesh,
                     const std::vector<Vec3>* radiosity, const std::vector<CellArray>& extra = {});

}  // namespace radkit
