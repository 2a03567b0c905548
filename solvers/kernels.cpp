#include "solvers/kernels.h"

#include <cmath>

#include <tbb/parallel_for.h>

namespace radkit {

namespace {

/// Fixed chunk for deterministic reductions; independent of the thread count.
constexpr std::size_t kDotChunk = 4096;

}  // namespace

Channels makeChannels(int n, double value) {
  const auto size = static_cast<std::size_t>(std::max(n, 0));
  return {std::vector<double>(size, value), std::vector<double>(size, value),
          std::vector<double>(size, value)};
}

double maxAbs(const Channels& x) {
  double m = 0.0;
  for (const auto& channel : x)
    for (double v : channel) {
      if (std::isnan(v)) return v;  // std::max would drop a NaN and hide a divergence
      m = std::max(m, std::fabs(v));
    }
  return m;
}

bool allFinite(const Channels& x) {
  for (const auto& channel : x)
    for (double v : channel)
      if (!std::isfinite(v)) return false;
  return true;
}

double dot(const std::vector<double>& a, const std::vector<double>& b) {
  const std::size_t n = std::min(a.size(), b.size());
  const std::size_t chunks = (n + kDotChunk - 1) / kDotChunk;
  std::vector<double> partial(chunks, 0.0);
  auto chunkSum = [&](std::size_t c) {
    const std::size_t end = std::min(n, (c + 1) * kDotChunk);
    double s = 0.0;
    for (std::size_t i = c * kDotChunk; i < end; ++i) s += a[i] * b[i];
    partial[c] = s;
  };
  if (n < 4 * kDotChunk) {
    for (std::size_t c = 0; c < chunks; ++c) chunkSum(c);
  } else {
    tbb::parallel_for(std::size_t(0), chunks, chunkSum);
  }
  double s = 0.0;
  for (double p : partial) s += p;  // sequential, fixed order: deterministic
  return s;
}

void multiply(const FormFactorMatrix& f, const Channels& x, Channels& y) {
  std::visit(
      [&](const auto& m) {
        const int n = m.rows();
        for (auto& channel : y) channel.resize(static_cast<std::size_t>(n));
        const auto xp = channelPointers(x);
        auto rows = [&](int begin, int end) {
          rangeDots<3>(m, begin, end, 0, n, xp, [&](int i, const std::array<double, 3>& s) {
            for (int c = 0; c < 3; ++c) y[c][i] = s[c];
          });
        };
        forRowBlocks(n, storedEntries(m), rows);
      },
      f);
}

std::vector<double> rowSums(const FormFactorMatrix& f) {
  const int n = matrixSize(f);
  Channels ones = makeChannels(n, 1.0);
  Channels sums;
  multiply(f, ones, sums);
  return sums[0];
}

}  // namespace radkit
