#include "solvers/sor_sweep.h"

#include <algorithm>
#include <utility>

namespace radkit {

namespace {

/// Sums of one block's rows over the columns outside the diagonal block.
struct OffBlockSums {
  Channels low, high;  ///< Σ_{j<I0} F_ij B^{k+1}_j and Σ_{j>=I1} F_ij B^k_j
  explicit OffBlockSums(int rows) : low(makeChannels(rows)), high(makeChannels(rows)) {}
};

template <typename Matrix>
void offBlockRows(const Matrix& m, int i0, int i1, const std::array<const double*, 3>& next,
                  const std::array<const double*, 3>& old, OffBlockSums& sums) {
  const int n = m.rows();
  forRowBlocks(i0, i1, n, storedEntries(m), [&](int begin, int end) {
    rangeDots<3>(m, begin, end, 0, i0, next, [&](int i, const std::array<double, 3>& low) {
      for (int c = 0; c < 3; ++c) sums.low[c][i - i0] = low[c];
    });
    rangeDots<3>(m, begin, end, i1, n, old, [&](int i, const std::array<double, 3>& high) {
      for (int c = 0; c < 3; ++c) sums.high[c][i - i0] = high[c];
    });
  });
}

template <typename Matrix>
void sweep(const Matrix& m, const RadiositySystem& s, const Rgb& omega, const Channels& old,
           Channels& next, Channels& lower, Channels& r) {
  const int n = m.rows();
  const auto nextp = channelPointers(next);
  const auto oldp = channelPointers(old);
  OffBlockSums sums(kSorBlockRows);
  for (int i0 = 0; i0 < n; i0 += kSorBlockRows) {
    const int i1 = std::min(n, i0 + kSorBlockRows);
    offBlockRows(m, i0, i1, nextp, oldp, sums);
    for (int i = i0; i < i1; ++i) {  // diagonal block: rows in order, as Gauss-Seidel requires
      const auto low = rowDots<3>(m, i, i0, i, nextp);
      const auto high = rowDots<3>(m, i, i, i1, oldp);
      for (int c = 0; c < 3; ++c) {
        const double rho = s.reflectance[c][i], e = s.emission[c][i], b = old[c][i];
        const double upper = sums.high[c][i - i0] + high[c];    // Σ_{j>=i} F_ij B^k_j
        const double lowerNext = sums.low[c][i - i0] + low[c];  // Σ_{j<i} F_ij B^{k+1}_j
        r[c][i] = e + rho * (lower[c][i] + upper) - b;
        next[c][i] = b + omega[c] * (e + rho * (lowerNext + upper) - b);
        lower[c][i] = lowerNext;
      }
    }
  }
}

/// lower_i = Σ_{j<i} F_ij x_j, parallel over rows, summed in the sweep's two parts (left of the
/// row's block, then inside it) so that it has the bits a sweep leaving x would have kept.
template <typename Matrix>
void lowerProduct(const Matrix& m, const Channels& x, Channels& lower) {
  const auto xp = channelPointers(x);
  forRowBlocks(m.rows(), storedEntries(m), [&](int begin, int end) {
    for (int i = begin; i < end; ++i) {
      const int i0 = i / kSorBlockRows * kSorBlockRows;
      const auto left = rowDots<3>(m, i, 0, i0, xp);
      const auto inside = rowDots<3>(m, i, i0, i, xp);
      for (int c = 0; c < 3; ++c) lower[c][i] = left[c] + inside[c];
    }
  });
}

}  // namespace

void sorSweep(const RadiositySystem& system, const Rgb& omega, const Channels& old, Channels& next,
              Channels& lower, Channels& r) {
  const int n = system.size();
  for (int c = 0; c < 3; ++c) {
    next[c].resize(static_cast<std::size_t>(n));
    r[c].resize(static_cast<std::size_t>(n));
  }
  std::visit([&](const auto& m) { sweep(m, system, omega, old, next, lower, r); }, system.matrix());
}

void lowerTriangleProduct(const RadiositySystem& system, const Channels& x, Channels& lower) {
  for (auto& channel : lower) channel.resize(static_cast<std::size_t>(system.size()));
  std::visit([&](const auto& m) { lowerProduct(m, x, lower); }, system.matrix());
}

void SorIteration::start(const RadiositySystem& system, const SolverSettings& settings,
                         const Rgb& omega) {
  system.validate();
  m_system = &system;
  m_norm = settings.norm;
  m_omega = omega;
  m_b = system.emission;
  m_next = makeChannels(system.size());
  m_r = makeChannels(system.size());
  lowerTriangleProduct(system, m_b, m_lower);
  m_iterations = 0;
  sweep();
}

void SorIteration::step() {
  std::swap(m_b, m_next);
  ++m_iterations;
  sweep();
}

void SorIteration::sweep() {
  sorSweep(*m_system, m_omega, m_b, m_next, m_lower, m_r);
  m_residual = residualMeasure(*m_system, m_r, m_b, m_norm);
  m_power = residualPower(*m_system, m_r);
}

}  // namespace radkit
