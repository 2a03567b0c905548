// Surface-level form factors: what surface_formfactors.csv (output/run_files.h) and the heat
// map show.
#pragma once

#include <string>
#include <vector>

#include "geometry/patch_mesh.h"
#include "geometry/scene.h"
#include "solvers/matrix.h"

namespace radkit {

/// \brief Surface-level factors F_{S→T} = Σ_{i∈S} Σ_{j∈T} A_i F_ij / A_S, row S, column T
/// (surfaces as in mesh.surfaceBegin). Rows of surfaces without area are zero.
DenseMatrix<double> surfaceFormFactors(const PatchMesh& mesh, const FormFactorMatrix& f);

/// \brief The names of a scene's surfaces, in order.
std::vector<std::string> surfaceNames(const Scene& scene);

}  // namespace radkit
