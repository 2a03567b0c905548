// Where F lives: dense (double or float) when it fits the memory budget, else CSR; the plan
// is made, and its size reported, before anything large is allocated.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <variant>

#include "geometry/patch_mesh.h"
#include "radiosity/form_factor_method.h"
#include "solvers/matrix.h"
#include "util/setting_names.h"

namespace radkit {

/// The fix MemoryBudgetError's message offers for the patch count; a caller that knows the mesh
/// is at its floor (one patch per input face) removes it.
inline std::string fewerPatchesFix() {
  return "use fewer patches (" + setting("max_area") + " larger or " + setting("patches") +
         " smaller), ";
}

/// Thrown when no storage fits the budget; the message names the options that would help.
class MemoryBudgetError : public std::runtime_error {
 public:
  MemoryBudgetError(const std::string& message, int patches, std::size_t smallestBytes = 0,
                    std::size_t budget = 0)
      : std::runtime_error(message),
        patches(patches),
        smallestBytes(smallestBytes),
        budget(budget) {}
  int patches;                ///< the mesh's patch count
  std::size_t smallestBytes;  ///< the least any storage needs for them (float, dense or sparse)
  std::size_t budget;         ///< the budget it was refused against
};

/// The storage chosen for a run and the memory it needs.
struct StoragePlan {
  bool dense = true;
  FormFactorPrecision precision = FormFactorPrecision::Double;
  int patches = 0;
  std::size_t denseBytes = 0;   ///< n² · sizeof(scalar)
  long long facingPairs = -1;   ///< unordered pairs that can be non-zero (-1: not counted)
  std::size_t sparseBytes = 0;  ///< CSR bound incl. assembly buffers (0: not computed)
  std::size_t bytes = 0;        ///< peak bytes of the chosen storage
  std::size_t budget = 0;
  /// "dense-double", "dense-float", "csr-double" or "csr-float" (solvers/matrix.h names).
  std::string storageName() const;
  /// "dense-double: 128.0 MiB of 8.00 GiB budget" and the like.
  std::string describe() const;
};

/// \brief Chooses dense (settings.precision) when n²·sizeof fits settings.memoryBudget, else
/// CSR sized from an upper bound on the non-zeros (pairs that face each other, O(n²) cheap
/// tests). Throws MemoryBudgetError naming --memory-budget, --max-area/--patches and
/// --ff-storage float when nothing fits.
StoragePlan planStorage(const PatchMesh& mesh, const FormFactorSettings& settings);

/// "1.50 GiB", "12.0 MiB", "512 B".
std::string formatBytes(double bytes);

/// \brief Calls fn(i, j, F_ij) for every stored non-zero, row by row, columns ascending.
template <typename Fn>
void forEachNonZero(const FormFactorMatrix& f, Fn&& fn) {
  std::visit(
      [&](const auto& m) {
        using M = std::decay_t<decltype(m)>;
        if constexpr (std::is_same_v<M, DenseMatrix<double>> ||
                      std::is_same_v<M, DenseMatrix<float>>) {
          for (int i = 0; i < m.rows(); ++i) {
            const auto* row = m.row(i);
            for (int j = 0; j < m.cols(); ++j)
              if (row[j] != 0) fn(i, j, double(row[j]));
          }
        } else {
          for (int i = 0; i < m.rows(); ++i)
            for (auto k = m.rowBegin(i); k < m.rowEnd(i); ++k)
              fn(i, m.column(k), double(m.value(k)));
        }
      },
      f);
}

/// \brief F_ij from any storage (binary search for CSR).
double formFactorAt(const FormFactorMatrix& f, int i, int j);

}  // namespace radkit
