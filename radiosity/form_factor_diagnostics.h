// FormFactorDiagnostics: what report.json says about a form-factor run.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "geometry/patch_mesh.h"
#include "solvers/matrix.h"

namespace radkit {

struct FormFactorDiagnostics {
  std::string method;       ///< registry name
  std::string description;  ///< FormFactorMethod::describe()
  std::string storage;      ///< storageName()
  int patches = 0;
  std::size_t nonZeros = 0;
  std::size_t matrixBytes = 0;

  // Row sums Σ_j F_ij: ≤ 1 always; = 1 in a closed enclosure (maxDeviationFromOne).
  double rowSumMin = 0, rowSumMax = 0, rowSumMean = 0, maxDeviationFromOne = 0;
  // Reciprocity: max over pairs of |A_iF_ij − A_jF_ji| / max(A_iF_ij, A_jF_ji), and the
  // area-weighted mean Σ|A_iF_ij − A_jF_ji| / Σ(A_iF_ij + A_jF_ji).
  double maxRelativeReciprocityError = 0, meanRelativeReciprocityError = 0;
  double maxRelativeReciprocityErrorBeforeEnforcement = 0;
  bool reciprocityByConstruction = false;  ///< F_ji derived from F_ij by the method
  bool reciprocityEnforced = false;        ///< --ff-enforce reciprocity was given

  long long pairsFacing = 0, pairsCulled = 0, overlappingPairs = 0;
  std::pair<int, int> firstOverlap{-1, -1};
  long long raysCast = 0, raysSaved = 0, quadraturePoints = 0, kernelPoints = 0;
  /// point-polygon: pairs per rule, [0] adaptive contour, [n] tensor level n (else empty).
  std::vector<long long> pairsByRule;
  int threads = 1;
  double rayThreadSeconds = 0;       ///< summed over threads
  double geometryThreadSeconds = 0;  ///< summed over threads
  double raysPerSecond = 0;          ///< raysCast / (rayThreadSeconds / threads)
  std::vector<std::pair<std::string, double>> phaseSeconds;  ///< wall seconds per phase
  std::vector<std::string> warnings;
};

/// \brief Fills row sums and reciprocity errors from a finished matrix.
void measureFormFactorMatrix(const FormFactorMatrix& f, const PatchMesh& mesh,
                             FormFactorDiagnostics& d);

/// \brief Largest relative reciprocity error of F (see FormFactorDiagnostics).
double maxRelativeReciprocityError(const FormFactorMatrix& f, const PatchMesh& mesh);

/// \brief The diagnostics as the "form_factors" object of report.json.
nlohmann::json toJson(const FormFactorDiagnostics& d);

}  // namespace radkit
