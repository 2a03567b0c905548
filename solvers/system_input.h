// A radiosity system given as arrays (the Python module's System(F, area, reflectance,
// emission); fuzz/python_arrays_fuzzer.cpp): every shape, index and value is checked here,
// before any of it reaches CsrMatrix or a solver, which trust their input (an index out of
// range there is a read or write outside the arrays). A refusal names the argument, the element
// and the fix, in the terms of the arrays as given (numpy indices, scipy's CSR field names).
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "solvers/matrix.h"
#include "solvers/radiosity_system.h"

namespace radkit {

/// Array input that cannot make a radiosity system. An std::invalid_argument, so Python sees
/// a ValueError.
class SystemInputError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// Σ_j F_ij may exceed 1 by this much. Exact form factors of a closed room sum to 1 and no row
/// sums above it; radkit's own point-polygon F does by estimation noise (measured: 1.5 % on
/// data/closed-room.json at 60 patches, 0.9 % on the Cornell box at 100, 1.8 % for a cube with
/// a blocker at 16 rays, docs/formfactors.md). Far above that, ρF creates light: B is wrong
/// and the iteration need not converge. Monte-carlo F at its default 16 samples sums to up to
/// 1.9 and is refused as arrays; System(form_factors) takes radkit's own F as it is.
constexpr double kRowSumTolerance = 0.05;

/// Areas and emission at most this, areas and non-zero reflectances at least its inverse. The
/// solvers form products such as cg's (A/ρ) E² and Southwell's A_i/A_j; within these bounds
/// none overflows a double (found by fuzz/python_arrays_fuzzer.cpp: E = 1.8e308 made B inf in
/// the first sweep, a subnormal ρ made cg's A/ρ inf). Only ratios of areas matter and B is
/// linear in E, so rescaling brings any system inside.
constexpr double kMaxMagnitude = 1e50;

/// A read-only view of `size` values.
template <typename T>
struct ArrayRef {
  const T* data = nullptr;
  std::size_t size = 0;
  const T& operator[](std::size_t i) const { return data[i]; }
};

/// An array of doubles as numpy holds it: C order, with its shape.
struct ArrayInput {
  ArrayRef<double> values;
  std::vector<std::int64_t> shape;
};

/// scipy's compressed sparse arrays: `indptr` per row (CSR) or per column (CSC), `indices` the
/// other coordinate of each entry, `data` its value; indices widened to 64 bits.
struct CompressedInput {
  bool columns = false;  ///< CSC: indptr runs over columns, indices are rows
  std::int64_t rows = 0, cols = 0;
  ArrayRef<std::int64_t> indptr, indices;
  ArrayRef<double> data;
};

/// scipy's COO arrays: entry k is data[k] at (row[k], col[k]).
struct CooInput {
  std::int64_t rows = 0, cols = 0;
  ArrayRef<std::int64_t> row, col;
  ArrayRef<double> data;
};

/// \brief F from a dense (n, n) array. Throws SystemInputError unless F is square with n >= 1,
///        every entry is finite and >= 0 (F_ii too: a patch may see itself, as an enclosure
///        given as one patch does) and every row sums to at most 1 + kRowSumTolerance.
DenseMatrix<double> checkedDenseFormFactors(const ArrayInput& f);

/// \brief F from CSR or CSC arrays, with the checks of checkedDenseFormFactors and: indptr has
///        n + 1 entries, starts at 0, never decreases and ends at len(indices) = len(data);
///        every index is in [0, n). Duplicate entries are summed (scipy's meaning of them) and
///        columns sorted, as CsrMatrix requires.
CsrMatrix<double> checkedCompressedFormFactors(const CompressedInput& f);

/// \brief F from COO arrays: row, col and data of one length, every index in [0, n);
///        duplicates summed; the entry and row-sum checks of checkedDenseFormFactors.
CsrMatrix<double> checkedCooFormFactors(const CooInput& f);

/// \brief The system B = E + ρ F B of F (which must outlive it) and per-patch arrays: area
///        (n,), each in [1/kMaxMagnitude, kMaxMagnitude]; reflectance (n, 3) or (n,) (grey),
///        each 0 or in [1/kMaxMagnitude, 1); emission (n, 3) or (n,), each in [0,
///        kMaxMagnitude]. Throws SystemInputError.
RadiositySystem checkedSystem(const FormFactorMatrix& f, const ArrayInput& area,
                              const ArrayInput& reflectance, const ArrayInput& emission);

}  // namespace radkit
