// Matrix storage for the radiosity system: dense row-major and compressed sparse rows, each in
// double or float. Float halves the memory of the form-factor matrix at ~1e-7 relative
// accuracy per entry; double is the default wherever accuracy is at stake.
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "util/check.h"
#include "util/large_array_allocator.h"

namespace radkit {

/// Square dense matrix, row-major.
template <typename T>
class DenseMatrix {
 public:
  using Scalar = T;
  DenseMatrix() = default;
  explicit DenseMatrix(int n) : m_n(n), m_data(static_cast<std::size_t>(n) * n, T(0)) {}
  /// \brief An n×n matrix whose entries are not set: the caller writes every one (in
  /// parallel, so that both the writes and the page faults are shared by the threads).
  static DenseMatrix uninitialized(int n) {
    DenseMatrix m;
    m.m_n = n;
    m.m_data.resize(static_cast<std::size_t>(n) * n);
    return m;
  }

  int rows() const { return m_n; }
  int cols() const { return m_n; }
  T& operator()(int i, int j) {
    RADKIT_DCHECK(inRange(i) && inRange(j));
    return m_data[static_cast<std::size_t>(i) * m_n + j];
  }
  T operator()(int i, int j) const {
    RADKIT_DCHECK(inRange(i) && inRange(j));
    return m_data[static_cast<std::size_t>(i) * m_n + j];
  }
  T* row(int i) {
    RADKIT_DCHECK(inRange(i));
    return m_data.data() + static_cast<std::size_t>(i) * m_n;
  }
  const T* row(int i) const {
    RADKIT_DCHECK(inRange(i));
    return m_data.data() + static_cast<std::size_t>(i) * m_n;
  }
  std::size_t bytes() const { return m_data.size() * sizeof(T); }
  std::size_t nonZeros() const;

  static std::size_t bytesFor(int n) { return static_cast<std::size_t>(n) * n * sizeof(T); }

 private:
  bool inRange(int i) const { return i >= 0 && i < m_n; }
  int m_n = 0;
  std::vector<T, LargeArrayAllocator<T>> m_data;
};

/// Square sparse matrix in compressed sparse row form; columns sorted within each row.
template <typename T>
class CsrMatrix {
 public:
  using Scalar = T;
  CsrMatrix() = default;
  /// Takes ownership of CSR arrays; rowStart has n+1 entries.
  CsrMatrix(int n, std::vector<std::int64_t> rowStart, std::vector<int> column,
            std::vector<T> value)
      : m_n(n),
        m_rowStart(std::move(rowStart)),
        m_column(std::move(column)),
        m_value(std::move(value)) {
    if (static_cast<int>(m_rowStart.size()) != n + 1 || m_column.size() != m_value.size())
      throw std::invalid_argument("CsrMatrix: inconsistent array sizes");
  }

  int rows() const { return m_n; }
  int cols() const { return m_n; }
  std::int64_t rowBegin(int i) const {
    RADKIT_DCHECK(i >= 0 && i < m_n);
    return m_rowStart[i];
  }
  std::int64_t rowEnd(int i) const {
    RADKIT_DCHECK(i >= 0 && i < m_n);
    return m_rowStart[i + 1];
  }
  int column(std::int64_t k) const {
    RADKIT_DCHECK(k >= 0 && k < static_cast<std::int64_t>(m_column.size()));
    return m_column[k];
  }
  T value(std::int64_t k) const {
    RADKIT_DCHECK(k >= 0 && k < static_cast<std::int64_t>(m_value.size()));
    return m_value[k];
  }
  std::size_t nonZeros() const { return m_value.size(); }
  std::size_t bytes() const {
    return m_rowStart.size() * sizeof(std::int64_t) + m_column.size() * sizeof(int) +
           m_value.size() * sizeof(T);
  }
  /// Entry (i, j), zero when not stored (binary search in the row).
  T operator()(int i, int j) const;

  static std::size_t bytesFor(int n, std::size_t nonZeros) {
    return (static_cast<std::size_t>(n) + 1) * sizeof(std::int64_t) +
           nonZeros * (sizeof(int) + sizeof(T));
  }

 private:
  int m_n = 0;
  std::vector<std::int64_t> m_rowStart;
  std::vector<int> m_column;
  std::vector<T> m_value;
};

/// The form-factor matrix F in whichever storage the run chose.
using FormFactorMatrix =
    std::variant<DenseMatrix<double>, DenseMatrix<float>, CsrMatrix<double>, CsrMatrix<float>>;

/// "dense-double", "dense-float", "csr-double" or "csr-float".
std::string storageName(const FormFactorMatrix& f);
int matrixSize(const FormFactorMatrix& f);
std::size_t matrixBytes(const FormFactorMatrix& f);

// ---- inline definitions ----

template <typename T>
std::size_t DenseMatrix<T>::nonZeros() const {
  std::size_t n = 0;
  for (T v : m_data) n += (v != T(0));
  return n;
}

template <typename T>
T CsrMatrix<T>::operator()(int i, int j) const {
  RADKIT_DCHECK(i >= 0 && i < m_n && j >= 0 && j < m_n);
  std::int64_t lo = m_rowStart[i], hi = m_rowStart[i + 1];
  while (lo < hi) {
    std::int64_t mid = (lo + hi) / 2;
    if (m_column[mid] < j)
      lo = mid + 1;
    else
      hi = mid;
  }
  return (lo < m_rowStart[i + 1] && m_column[lo] == j) ? m_value[lo] : T(0);
}

}  // namespace radkit
