#include "solvers/sor_sweep.h"

#include <algorithm>
#include <utility>

namespace radkit {

namespace {

/// Sums of one block's rows over the columns outside the diagonal block.
struct OffBlockSums {
  Channels lowNew, lowOld, high;  ///< Σ_{j<I0} F_ij B^{k+1}_j, Σ_{j<I0} F_ij B^k_j, Σ_{j>=I1} F_ij B^k_j
  explicit OffBlockSums(int rows)
      : lowNew(makeChannels(rows)), lowOld(makeChannels(rows)), high(makeChannels(rows)) {}
};

template <typename Matrix>
void offBlockRows(const Matrix& m, int i0, int i1, const std::array<const double*, 6>& newOld,
                  const std::array<const double*, 3>& old, OffBlockSums& sums) {
  const int n = m.rows();
  auto rows = [&](int begin, int end) {
    for (int i = begin; i < end; ++i) {
      const auto low = rowDots<6>(m, i, 0, i0, newOld);
      const auto high = rowDots<3>(m, i, i1, n, old);
      for (int c = 0; c < 3; ++c) {
        sums.lowNew[c][i - i0] = low[c];
        sums.lowOld[c][i - i0] = low[3 + c];
        sums.high[c][i - i0] = high[c];
      }
    }
  };
  const std::size_t entries = storedEntries(m);
  if (entries < kSerialEntries) {
    rows(i0, i1);
    return;
  }
  const std::size_t perRow = std::max<std::size_t>(1, entries / static_cast<std::size_t>(n));
  const int grain = static_cast<int>(std::max<std::size_t>(1, kSerialEntries / perRow));
  tbb::parallel_for(tbb::blocked_range<int>(i0, i1, grain),
                    [&](const tbb::blocked_range<int>& r) { rows(r.begin(), r.end()); });
}

template <typename Matrix>
void sweep(const Matrix& m, const RadiositySystem& s, const Rgb& omega, const Channels& old,
           Channels& next, Channels& r) {
  const int n = m.rows();
  const std::array<const double*, 6> newOld = {next[0].data(), next[1].data(), next[2].data(),
                                               old[0].data(),  old[1].data(),  old[2].data()};
  const auto oldp = channelPointers(old);
  OffBlockSums sums(kSorBlockRows);
  for (int i0 = 0; i0 < n; i0 += kSorBlockRows) {
    const int i1 = std::min(n, i0 + kSorBlockRows);
    offBlockRows(m, i0, i1, newOld, oldp, sums);
    for (int i = i0; i < i1; ++i) {  // diagonal block: rows in order, as Gauss-Seidel requires
      const auto low = rowDots<6>(m, i, i0, i, newOld);
      const auto high = rowDots<3>(m, i, i, i1, oldp);
      for (int c = 0; c < 3; ++c) {
        const double rho = s.reflectance[c][i], e = s.emission[c][i], b = old[c][i];
        const double rest = sums.high[c][i - i0] + high[c];
        const double fbNew = sums.lowNew[c][i - i0] + low[c] + rest;
        const double fbOld = sums.lowOld[c][i - i0] + low[3 + c] + rest;
        r[c][i] = e + rho * fbOld - b;
        next[c][i] = b + omega[c] * (e + rho * fbNew - b);
      }
    }
  }
}

}  // namespace

void sorSweep(const RadiositySystem& system, const Rgb& omega, const Channels& old,
              Channels& next, Channels& r) {
  const int n = system.size();
  for (int c = 0; c < 3; ++c) {
    next[c].resize(static_cast<std::size_t>(n));
    r[c].resize(static_cast<std::size_t>(n));
  }
  std::visit([&](const auto& m) { sweep(m, system, omega, old, next, r); }, system.matrix());
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
  m_iterations = 0;
  sweep();
}

void SorIteration::step() {
  std::swap(m_b, m_next);
  ++m_iterations;
  sweep();
}

void SorIteration::sweep() {
  sorSweep(*m_system, m_omega, m_b, m_next, m_r);
  m_residual = residualMeasure(*m_system, m_r, m_b, m_norm);
  m_power = residualPower(*m_system, m_r);
}

}  // namespace radkit
