// Vector kernels and matrix-vector products over every FormFactorMatrix storage. Entries may be
// stored in float; every product is accumulated in double. Each row's sum is computed in a fixed
// order by one thread, so results are bit-identical whatever the TBB partition.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <type_traits>
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "solvers/matrix.h"

namespace radkit {

/// One value per RGB channel.
using Rgb = std::array<double, 3>;
/// One vector (indexed by patch) per RGB channel.
using Channels = std::array<std::vector<double>, 3>;

/// \brief Three vectors of n entries, each set to value.
Channels makeChannels(int n, double value = 0.0);

/// \brief max over channels and patches of |x|.
double maxAbs(const Channels& x);

/// \brief True when every entry of every channel is finite.
bool allFinite(const Channels& x);

/// \brief Σ_i a_i b_i, summed over fixed chunks (in parallel) then the chunk sums in order, so
///        the result does not depend on the thread count.
double dot(const std::vector<double>& a, const std::vector<double>& b);

/// \brief y_c = F x_c for the three channels, streaming F once; parallel over rows.
void multiply(const FormFactorMatrix& f, const Channels& x, Channels& y);

/// \brief Row sums Σ_j F_ij (1 in a closed enclosure).
std::vector<double> rowSums(const FormFactorMatrix& f);

/// Below this many matrix entries a product runs on the calling thread: TBB's task overhead
/// (about a microsecond) would dominate the 6x6 test matrices iterated 1e5 times.
constexpr std::size_t kSerialEntries = std::size_t(1) << 15;

/// \brief Calls rows(begin, end) over the rows [first, last) of an n-row matrix holding
///        `entries` entries: in parallel, about kSerialEntries matrix entries per task, when the
///        whole matrix holds at least kSerialEntries entries; serially otherwise.
template <typename Fn>
inline void forRowBlocks(int first, int last, int n, std::size_t entries, Fn&& rows) {
  if (entries < kSerialEntries || last - first < 2) {
    rows(first, last);
    return;
  }
  const std::size_t perRow = std::max<std::size_t>(1, entries / static_cast<std::size_t>(n));
  const int grain = static_cast<int>(std::max<std::size_t>(1, kSerialEntries / perRow));
  tbb::parallel_for(tbb::blocked_range<int>(first, last, grain),
                    [&](const tbb::blocked_range<int>& r) { rows(r.begin(), r.end()); });
}

/// \brief forRowBlocks over all n rows.
template <typename Fn>
inline void forRowBlocks(int n, std::size_t entries, Fn&& rows) {
  forRowBlocks(0, n, n, entries, std::forward<Fn>(rows));
}

// ---- row-segment dot products, the inner loops of every solver ----

/// Two doubles in one SSE2 register (GCC/Clang vector extension): written out because GCC
/// will not reassociate a double reduction itself without -ffast-math.
using Lanes = double __attribute__((vector_size(16)));

template <typename T>
inline Lanes loadLanes(const T* p) {
  if constexpr (std::is_same_v<T, double>) {
    Lanes v;
    std::memcpy(&v, p, sizeof v);
    return v;
  } else {
    return Lanes{static_cast<double>(p[0]), static_cast<double>(p[1])};
  }
}

/// Σ_{j in [begin,end)} f_j x_k[j] for K vectors at once: the row f is read once for all K.
/// Four partial sums per vector (two registers of two lanes) in a fixed order, so the result
/// depends only on the data and on begin, never on threads.
template <int K, typename T>
inline std::array<double, K> segmentDots(const T* f, int begin, int end,
                                         const std::array<const double*, K>& x) {
  Lanes s[K][2] = {};
  int j = begin;
  for (; j + 4 <= end; j += 4) {
    const Lanes f0 = loadLanes(f + j), f1 = loadLanes(f + j + 2);
    for (int k = 0; k < K; ++k) {
      s[k][0] += f0 * loadLanes(x[k] + j);
      s[k][1] += f1 * loadLanes(x[k] + j + 2);
    }
  }
  std::array<double, K> out{};
  for (int k = 0; k < K; ++k) {
    const Lanes t = s[k][0] + s[k][1];
    double sum = t[0] + t[1];
    for (int jj = j; jj < end; ++jj) sum += static_cast<double>(f[jj]) * x[k][jj];
    out[k] = sum;
  }
  return out;
}

/// Dense row i, columns [begin, end).
template <int K, typename T>
inline std::array<double, K> rowDots(const DenseMatrix<T>& m, int i, int begin, int end,
                                     const std::array<const double*, K>& x) {
  return segmentDots<K>(m.row(i), begin, end, x);
}

/// Rows a dense product takes at once in rangeDots.
constexpr int kRowsAtOnce = 4;

/// segmentDots for kRowsAtOnce rows f[0..3] at once. Each row's arithmetic is exactly
/// segmentDots' (same partial sums, same order), so a row's result does not depend on whether it
/// was taken alone or in a group. Sharing each load of x among four rows halves the loads per
/// matrix entry, and four streams of F in flight keep more memory requests outstanding per core:
/// a one-row sweep reached 10 GB/s on one core, this one 14 GB/s (docs/solvers.md).
template <int K, typename T>
inline void segmentDotsRows(const std::array<const T*, kRowsAtOnce>& f, int begin, int end,
                            const std::array<const double*, K>& x,
                            std::array<std::array<double, K>, kRowsAtOnce>& out) {
  constexpr int R = kRowsAtOnce;
  Lanes s[R][K][2] = {};
  int j = begin;
  for (; j + 4 <= end; j += 4) {
    Lanes f0[R], f1[R];
    for (int r = 0; r < R; ++r) {
      f0[r] = loadLanes(f[r] + j);
      f1[r] = loadLanes(f[r] + j + 2);
    }
    for (int k = 0; k < K; ++k) {
      const Lanes x0 = loadLanes(x[k] + j), x1 = loadLanes(x[k] + j + 2);
      for (int r = 0; r < R; ++r) {
        s[r][k][0] += f0[r] * x0;
        s[r][k][1] += f1[r] * x1;
      }
    }
  }
  for (int r = 0; r < R; ++r)
    for (int k = 0; k < K; ++k) {
      const Lanes t = s[r][k][0] + s[r][k][1];
      double sum = t[0] + t[1];
      for (int jj = j; jj < end; ++jj) sum += static_cast<double>(f[r][jj]) * x[k][jj];
      out[r][k] = sum;
    }
}

/// First stored entry of CSR row i whose column is >= col (columns are sorted).
template <typename T>
inline std::int64_t csrLowerBound(const CsrMatrix<T>& m, int i, int col) {
  std::int64_t lo = m.rowBegin(i), hi = m.rowEnd(i);
  while (lo < hi) {
    const std::int64_t mid = lo + (hi - lo) / 2;
    if (m.column(mid) < col)
      lo = mid + 1;
    else
      hi = mid;
  }
  return lo;
}

/// CSR row i, columns [begin, end).
template <int K, typename T>
inline std::array<double, K> rowDots(const CsrMatrix<T>& m, int i, int begin, int end,
                                     const std::array<const double*, K>& x) {
  const std::int64_t k0 = begin <= 0 ? m.rowBegin(i) : csrLowerBound(m, i, begin);
  const std::int64_t k1 = end >= m.cols() ? m.rowEnd(i) : csrLowerBound(m, i, end);
  std::array<double, K> out{};
  for (std::int64_t e = k0; e < k1; ++e) {
    const double v = static_cast<double>(m.value(e));
    const int j = m.column(e);
    for (int k = 0; k < K; ++k) out[k] += v * x[k][j];
  }
  return out;
}

/// \brief Calls out(i, rowDots<K>(m, i, begin, end, x)) for every row i in [rowBegin, rowEnd),
///        in order; dense rows are taken kRowsAtOnce at a time, with the same results.
template <int K, typename T, typename Out>
inline void rangeDots(const DenseMatrix<T>& m, int rowBegin, int rowEnd, int begin, int end,
                      const std::array<const double*, K>& x, Out&& out) {
  int i = rowBegin;
  std::array<std::array<double, K>, kRowsAtOnce> dots;
  for (; i + kRowsAtOnce <= rowEnd; i += kRowsAtOnce) {
    std::array<const T*, kRowsAtOnce> rows;
    for (int r = 0; r < kRowsAtOnce; ++r) rows[r] = m.row(i + r);
    segmentDotsRows<K>(rows, begin, end, x, dots);
    for (int r = 0; r < kRowsAtOnce; ++r) out(i + r, dots[r]);
  }
  for (; i < rowEnd; ++i) out(i, rowDots<K>(m, i, begin, end, x));
}

template <int K, typename T, typename Out>
inline void rangeDots(const CsrMatrix<T>& m, int rowBegin, int rowEnd, int begin, int end,
                      const std::array<const double*, K>& x, Out&& out) {
  for (int i = rowBegin; i < rowEnd; ++i) out(i, rowDots<K>(m, i, begin, end, x));
}

/// Calls fn(j, F_ij) for every stored entry of row i (zeros of a dense row included).
template <typename T, typename Fn>
inline void forEachInRow(const DenseMatrix<T>& m, int i, Fn&& fn) {
  const T* r = m.row(i);
  for (int j = 0; j < m.cols(); ++j) fn(j, static_cast<double>(r[j]));
}

template <typename T, typename Fn>
inline void forEachInRow(const CsrMatrix<T>& m, int i, Fn&& fn) {
  for (std::int64_t e = m.rowBegin(i); e < m.rowEnd(i); ++e)
    fn(m.column(e), static_cast<double>(m.value(e)));
}

/// Entries stored in row i (n for a dense row).
template <typename T>
inline std::size_t rowEntries(const DenseMatrix<T>& m, int) {
  return static_cast<std::size_t>(m.cols());
}
template <typename T>
inline std::size_t rowEntries(const CsrMatrix<T>& m, int i) {
  return static_cast<std::size_t>(m.rowEnd(i) - m.rowBegin(i));
}

/// Entries stored in the whole matrix (n² for dense).
template <typename T>
inline std::size_t storedEntries(const DenseMatrix<T>& m) {
  return static_cast<std::size_t>(m.rows()) * static_cast<std::size_t>(m.cols());
}
template <typename T>
inline std::size_t storedEntries(const CsrMatrix<T>& m) {
  return m.nonZeros();
}

/// Pointers to the three channels, for rowDots<3>.
inline std::array<const double*, 3> channelPointers(const Channels& x) {
  return {x[0].data(), x[1].data(), x[2].data()};
}

}  // namespace radkit
