// computeFormFactors: the whole F matrix of a PatchMesh with a chosen method, in the storage
// that fits the memory budget, with diagnostics. The C++ entry point behind `radkit formfactors`.
#pragma once

#include <functional>
#include <string>

#include "geometry/patch_mesh.h"
#include "geometry/visibility.h"
#include "radiosity/form_factor_diagnostics.h"
#include "radiosity/form_factor_method.h"
#include "radiosity/form_factor_storage.h"
#include "solvers/matrix.h"

namespace radkit {

/// Progress and memory messages ("dense-double: 122 MiB needed ..."); may be empty.
using FormFactorLog = std::function<void(const std::string&)>;
/// Fraction of the pair work done (0..1), called from worker threads one at a time.
using FormFactorProgress = std::function<void(double)>;

struct FormFactorResult {
  FormFactorMatrix matrix;
  FormFactorDiagnostics diagnostics;
  StoragePlan plan;
};

/// \brief Computes F_ij for all patch pairs, rows in parallel (TBB, all threads of the
/// current arena). Deterministic for a given settings.seed whatever the thread count.
/// Logs the storage plan before allocating. Never alters F unless settings.enforceReciprocity.
/// \throws std::invalid_argument for bad settings (--ff-samples 0, unknown --ff),
///         MemoryBudgetError when no storage fits settings.memoryBudget.
FormFactorResult computeFormFactors(const PatchMesh& mesh, const Visibility& visibility,
                                    const FormFactorSettings& settings,
                                    const FormFactorLog& log = {},
                                    const FormFactorProgress& progress = {});

/// \brief Replaces A_iF_ij and A_jF_ji by their mean for every pair (the explicit
/// --ff-enforce reciprocity). Dense storage only; computeFormFactors handles CSR itself.
template <typename T>
void enforceReciprocity(DenseMatrix<T>& f, const PatchMesh& mesh);

}  // namespace radkit
