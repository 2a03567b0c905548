#include "solvers/system_input.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <numeric>
#include <string>
#include <utility>

#include "util/format.h"

namespace radkit {

namespace {

[[noreturn]] void refuse(const std::string& what) { throw SystemInputError(what); }

/// Ten digits: a row sum of 1.0500001 must not print as the tolerance it exceeds.
std::string num(double v) { return formatNumber(v, 10); }
std::string num(std::int64_t v) { return std::to_string(v); }

std::string shapeText(const std::vector<std::int64_t>& shape) {
  std::string s = "(";
  for (std::size_t k = 0; k < shape.size(); ++k) s += (k ? ", " : "") + std::to_string(shape[k]);
  return s + (shape.size() == 1 ? ",)" : ")");
}

std::string cell(std::int64_t i, std::int64_t j) {
  return "[" + std::to_string(i) + ", " + std::to_string(j) + "]";
}

/// The side n of a square (n, n) shape, 1 <= n < INT_MAX.
int patchCount(std::int64_t rows, std::int64_t cols, const std::string& shape) {
  if (rows != cols || rows < 0)
    refuse("F: expected a square (n, n) matrix, got shape " + shape +
           ". Fix: one row and one column per patch");
  if (rows == 0) refuse("F: shape " + shape + " has no patches. Fix: at least one patch");
  if (rows >= INT_MAX)
    refuse("F: " + num(rows) + " patches are more than radkit indexes (" +
           std::to_string(INT_MAX - 1) + "). Fix: fewer patches");
  return static_cast<int>(rows);
}

/// One stored value of F: finite and >= 0. `where` names it as the caller's arrays do.
void checkEntry(double v, const std::string& where) {
  if (std::isfinite(v) && v >= 0.0) return;
  refuse(where + " = " + num(v) + (std::isfinite(v) ? " is negative" : " is not finite") +
         ". Fix: a form factor F_ij is the fraction of patch i's light that reaches patch j, "
         "in [0, 1]");
}

void checkRowSum(int i, double sum) {
  if (sum <= 1.0 + kRowSumTolerance) return;  // NaN cannot occur: entries are finite, >= 0
  refuse("F row " + std::to_string(i) + " sums to " + num(sum) + ", above 1 + " +
         num(kRowSumTolerance) +
         ": rho F would create light, so B is wrong and the solvers need not converge. Fix: "
         "row " +
         std::to_string(i) + " holds the fractions of patch " + std::to_string(i) +
         "'s light reaching each patch, which sum to at most 1 (1 in a closed room); "
         "recompute F with more samples, or scale the row down");
}

void checkSize(const ArrayRef<double>& values, const std::vector<std::int64_t>& shape,
               const char* name) {
  std::uint64_t count = 1;
  for (std::int64_t d : shape) {
    if (d < 0)
      refuse(std::string(name) + ": shape " + shapeText(shape) +
             " has a negative extent. Fix: an array's shape as numpy gives it");
    count = d == 0 ? 0 : (count > UINT64_MAX / std::uint64_t(d) ? UINT64_MAX : count * d);
  }
  if (count != values.size)
    refuse(std::string(name) + ": " + std::to_string(values.size) + " values for shape " +
           shapeText(shape) + ". Fix: pass a contiguous array");
}

/// CSR of n rows from `nnz` entries (row(k), col(k), value(k)), every index already checked:
/// entries grouped by row in their given order, then each row sorted by column with
/// duplicates summed (scipy's sum_duplicates), as CsrMatrix requires.
template <typename Row, typename Col, typename Value>
CsrMatrix<double> buildCsr(int n, std::size_t nnz, Row row, Col col, Value value) {
  std::vector<std::int64_t> start(static_cast<std::size_t>(n) + 1, 0);
  for (std::size_t k = 0; k < nnz; ++k) ++start[static_cast<std::size_t>(row(k)) + 1];
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<std::int64_t> next(start.begin(), start.end() - 1);
  std::vector<std::pair<int, double>> entry(nnz);
  for (std::size_t k = 0; k < nnz; ++k)
    entry[static_cast<std::size_t>(next[static_cast<std::size_t>(row(k))]++)] = {
        static_cast<int>(col(k)), value(k)};
  std::vector<std::int64_t> rowStart(static_cast<std::size_t>(n) + 1, 0);
  std::vector<int> column;
  std::vector<double> data;
  column.reserve(nnz);
  data.reserve(nnz);
  for (int i = 0; i < n; ++i) {
    const auto first = entry.begin() + start[i], last = entry.begin() + start[i + 1];
    std::stable_sort(first, last, [](const auto& a, const auto& b) { return a.first < b.first; });
    for (auto e = first; e != last; ++e) {
      if (static_cast<std::int64_t>(column.size()) > rowStart[i] && column.back() == e->first)
        data.back() += e->second;
      else
        column.push_back(e->first), data.push_back(e->second);
    }
    rowStart[i + 1] = static_cast<std::int64_t>(column.size());
  }
  return CsrMatrix<double>(n, std::move(rowStart), std::move(column), std::move(data));
}

void checkRowSums(const CsrMatrix<double>& m) {
  for (int i = 0; i < m.rows(); ++i) {
    double sum = 0.0;
    for (std::int64_t k = m.rowBegin(i); k < m.rowEnd(i); ++k) sum += m.value(k);
    checkRowSum(i, sum);
  }
}

/// Per-patch values as (n,) or, when `rgb`, also (n, 3); spread into three channels.
Channels patchValues(const ArrayInput& a, int n, const char* name, bool rgb) {
  checkSize(a.values, a.shape, name);
  const bool grey = a.shape.size() == 1 && a.shape[0] == n;
  if (!grey && !(rgb && a.shape.size() == 2 && a.shape[0] == n && a.shape[1] == 3)) {
    const std::string side = std::to_string(n);
    refuse(std::string(name) + ": expected shape " +
           (rgb ? "(" + side + ", 3) or (" + side + ",)" : "(" + side + ",)") + ", got " +
           shapeText(a.shape) + ". Fix: one " +
           (rgb ? "row (3 channels, or 1 value: grey)" : "value") + " per patch of the " + side +
           " x " + side + " F");
  }
  Channels c = makeChannels(n);
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) c[k][i] = a.values[grey ? i : 3 * std::size_t(i) + k];
  return c;
}

/// Name of element (i, channel k) as the caller indexes its array.
std::string element(const char* name, const ArrayInput& a, int i, int k) {
  return std::string(name) + (a.shape.size() == 1 ? "[" + std::to_string(i) + "]" : cell(i, k));
}

}  // namespace

DenseMatrix<double> checkedDenseFormFactors(const ArrayInput& f) {
  const std::string shape = shapeText(f.shape);
  if (f.shape.size() != 2)
    refuse("F: expected a square (n, n) array, got shape " + shape +
           ". Fix: one row and one column per patch, or a scipy.sparse matrix");
  checkSize(f.values, f.shape, "F");
  const int n = patchCount(f.shape[0], f.shape[1], shape);
  DenseMatrix<double> m(n);
  for (int i = 0; i < n; ++i) {
    const double* row = f.values.data + static_cast<std::size_t>(i) * n;
    double sum = 0.0;
    for (int j = 0; j < n; ++j) {
      checkEntry(row[j], "F" + cell(i, j));
      sum += row[j];
    }
    checkRowSum(i, sum);
    std::copy(row, row + n, m.row(i));
  }
  return m;
}

CsrMatrix<double> checkedCompressedFormFactors(const CompressedInput& f) {
  const char* kind = f.columns ? "CSC" : "CSR";
  const char* major = f.columns ? "column" : "row";
  const char* minor = f.columns ? "row" : "column";
  const int n = patchCount(f.rows, f.cols, shapeText({f.rows, f.cols}));
  if (f.indptr.size != static_cast<std::size_t>(n) + 1)
    refuse(std::string("F.indptr has ") + std::to_string(f.indptr.size) + " entries for " +
           std::to_string(n) + " " + major + "s. Fix: a " + kind + " matrix of n " + major +
           "s has n + 1 pointers, indptr[i] the first entry of " + major + " i");
  if (f.indptr[0] != 0) refuse("F.indptr[0] = " + num(f.indptr[0]) + ". Fix: pointers start at 0");
  for (int i = 0; i < n; ++i)
    if (f.indptr[i + 1] < f.indptr[i])
      refuse("F.indptr[" + std::to_string(i + 1) + "] = " + num(f.indptr[i + 1]) +
             " is below F.indptr[" + std::to_string(i) + "] = " + num(f.indptr[i]) + ": " + major +
             " " + std::to_string(i) +
             " would end before it starts. Fix: pointers "
             "never decrease");
  const std::int64_t nnz = f.indptr[n];
  if (f.indices.size != f.data.size || static_cast<std::uint64_t>(nnz) != f.indices.size)
    refuse("F.indptr[" + std::to_string(n) + "] = " + num(nnz) + " entries, but F.indices has " +
           std::to_string(f.indices.size) + " and F.data " + std::to_string(f.data.size) +
           ". Fix: indptr[-1] = len(indices) = len(data) (F.prune() drops entries past "
           "indptr[-1])");
  std::vector<int> owner(static_cast<std::size_t>(nnz));  // the row (CSC: column) of entry k
  for (int i = 0; i < n; ++i)
    for (std::int64_t k = f.indptr[i]; k < f.indptr[i + 1]; ++k) {
      owner[static_cast<std::size_t>(k)] = i;
      const std::int64_t j = f.indices[static_cast<std::size_t>(k)];
      if (j < 0 || j >= n)
        refuse("F.indices[" + std::to_string(k) + "] = " + num(j) + " (an entry of " + major + " " +
               std::to_string(i) + ") is outside [0, " + std::to_string(n) + "). Fix: " + minor +
               " indices of an n x n matrix are 0 .. n - 1");
      const double v = f.data[static_cast<std::size_t>(k)];
      checkEntry(
          v, "F.data[" + std::to_string(k) + "] (F" + (f.columns ? cell(j, i) : cell(i, j)) + ")");
    }
  const auto ownerOf = [&](std::size_t k) { return std::int64_t(owner[k]); };
  const auto indexOf = [&](std::size_t k) { return f.indices[k]; };
  const auto valueOf = [&](std::size_t k) { return f.data[k]; };
  CsrMatrix<double> m = f.columns ? buildCsr(n, f.data.size, indexOf, ownerOf, valueOf)
                                  : buildCsr(n, f.data.size, ownerOf, indexOf, valueOf);
  checkRowSums(m);
  return m;
}

CsrMatrix<double> checkedCooFormFactors(const CooInput& f) {
  const int n = patchCount(f.rows, f.cols, shapeText({f.rows, f.cols}));
  if (f.row.size != f.data.size || f.col.size != f.data.size)
    refuse("F.row, F.col and F.data have " + std::to_string(f.row.size) + ", " +
           std::to_string(f.col.size) + " and " + std::to_string(f.data.size) +
           " entries. Fix: one row, one column and one value per entry");
  for (std::size_t k = 0; k < f.data.size; ++k) {
    for (const auto& [name, index] :
         {std::pair<const char*, std::int64_t>{"row", f.row[k]}, {"col", f.col[k]}})
      if (index < 0 || index >= n)
        refuse(std::string("F.") + name + "[" + std::to_string(k) + "] = " + num(index) +
               " is outside [0, " + std::to_string(n) +
               "). Fix: indices of an n x n matrix "
               "are 0 .. n - 1");
    checkEntry(f.data[k], "F.data[" + std::to_string(k) + "] (F" + cell(f.row[k], f.col[k]) + ")");
  }
  CsrMatrix<double> m = buildCsr(
      n, f.data.size, [&](std::size_t k) { return f.row[k]; },
      [&](std::size_t k) { return f.col[k]; }, [&](std::size_t k) { return f.data[k]; });
  checkRowSums(m);
  return m;
}

RadiositySystem checkedSystem(const FormFactorMatrix& f, const ArrayInput& area,
                              const ArrayInput& reflectance, const ArrayInput& emission) {
  const int n = matrixSize(f);
  RadiositySystem s;
  s.formFactors = &f;
  const Channels a = patchValues(area, n, "area", false);
  s.area = a[0];
  const std::string bounds = " in [" + num(1 / kMaxMagnitude) + ", " + num(kMaxMagnitude) + "]";
  for (int i = 0; i < n; ++i) {
    const double v = s.area[i];
    if (!(std::isfinite(v) && v > 0.0))
      refuse(element("area", area, i, 0) + " = " + num(v) +
             " must be finite and > 0. Fix: patch areas (only their ratios matter); leave out "
             "patches of no area");
    if (!(v >= 1 / kMaxMagnitude && v <= kMaxMagnitude))
      refuse(element("area", area, i, 0) + " = " + num(v) + " is not" + bounds +
             ", where the solvers' products stay finite. Fix: only the ratios of areas matter: "
             "rescale them all");
  }
  s.reflectance = patchValues(reflectance, n, "reflectance", true);
  s.emission = patchValues(emission, n, "emission", true);
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) {
      const double rho = s.reflectance[k][i], e = s.emission[k][i];
      if (!(rho >= 0.0 && rho < 1.0))
        refuse(element("reflectance", reflectance, i, k) + " = " + num(rho) +
               " is outside [0, 1). Fix: a diffuse reflectance is the fraction of the light "
               "a patch reflects, below 1 (at 1 a closed room has no finite B)");
      if (rho > 0.0 && rho < 1 / kMaxMagnitude)
        refuse(element("reflectance", reflectance, i, k) + " = " + num(rho) + " is below " +
               num(1 / kMaxMagnitude) + " but not 0 (cg divides by it). Fix: 0");
      if (!(std::isfinite(e) && e >= 0.0))
        refuse(element("emission", emission, i, k) + " = " + num(e) +
               " must be finite and >= 0. Fix: emitted radiosity in W/m^2, 0 for a patch that "
               "does not emit");
      if (e > kMaxMagnitude)
        refuse(element("emission", emission, i, k) + " = " + num(e) + " is above " +
               num(kMaxMagnitude) +
               ", beyond which B overflows. Fix: B is proportional to E: rescale E and B");
    }
  return s;
}

}  // namespace radkit
