// Writers for the form-factor outputs: formfactors.mtx and surface_formfactors.csv (the heat
// map is in form_factor_heat_map.h). Each writes path + ".tmp" and renames it into place.
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

/// \brief Writes F as Matrix Market `coordinate real general`: row i+1, column j+1, F_ij, for
/// every stored non-zero; `comments` become `%` lines after the banner (describe the run).
/// Values are printed as the shortest text that reads back exactly (std::to_chars; float
/// storage as floats). Streamed: the text
/// is never held in memory whole.
void writeMatrixMarket(const std::string& path, const FormFactorMatrix& f,
                       const std::vector<std::string>& comments);

/// Magic of formfactors.bin, version 1.
constexpr char kFormFactorBinaryMagic[9] = "RADKITF1";

/// \brief Writes F compactly for the viewer (formfactors.bin), streamed row by row, all
/// numbers little-endian: the 8-byte magic, int64 n, int64 non-zeros, then per row an int32
/// k and either (k >= 0) k uint32 columns ascending and k float32 values, or (k = −1, when
/// that is smaller) n float32 values. At most 4n² + 4n + 24 bytes.
void writeFormFactorBinary(const std::string& path, const FormFactorMatrix& f);

/// \brief Writes `from,to,F` for every ordered pair of surfaces (names quoted when needed).
/// \param surfaceNames one name per surface of the mesh (see surfaceNames()).
void writeSurfaceFormFactors(const std::string& path, const PatchMesh& mesh,
                             const std::vector<std::string>& surfaceNames,
                             const FormFactorMatrix& f);

/// \brief The names of a scene's surfaces, in order.
std::vector<std::string> surfaceNames(const Scene& scene);

}  // namespace radkit
