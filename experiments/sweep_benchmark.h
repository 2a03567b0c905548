// Sweep throughput of Jacobi and Gauss-Seidel on a dense matrix against a STREAM-like triad
// measured in the same run and thread count (docs/benchmarks.md). `radkit bench solver`
// prints the result as one JSON object.
#pragma once

#include <cstddef>

namespace radkit {

struct SweepBenchmarkSettings {
  int n = 8192;          ///< dense n x n matrix of doubles (8192: 512 MiB)
  int repetitions = 10;  ///< timed rounds of the three kernels; best counts
  std::size_t triadElements = std::size_t(1) << 24;  ///< per array; 3 x 128 MiB >> any cache
  int threads = 0;                                   ///< 0: TBB's default (all cores)
};

struct SweepBenchmarkResult {
  int n = 0;
  int threads = 0;
  int repetitions = 0;
  double matrixBytes = 0.0;           ///< bytes of F streamed per sweep, n² · 8
  double jacobiSeconds = 0.0;         ///< best sweep (one solver step, three channels)
  double gaussSeidelSeconds = 0.0;    ///< best sweep
  double triadSeconds = 0.0;          ///< best triad pass
  double triadBytes = 0.0;            ///< 3 · 8 · elements per pass (STREAM's count)
  double jacobiBytesPerSecond = 0.0;  ///< matrixBytes / jacobiSeconds
  double gaussSeidelBytesPerSecond = 0.0;
  double triadBytesPerSecond = 0.0;
  double jacobiRatio = 0.0;  ///< jacobi / triad bytes per second; target >= 0.7
  double gaussSeidelRatio = 0.0;
};

/// \brief Builds the dense matrix (furnace-like F_ij = 1/n, ρ = 0.5) and the triad arrays,
///        times `repetitions` rounds of one triad a = b + s c, one step of the registry's
///        jacobi and one of its gauss-seidel, all in one TBB arena of `threads` threads.
///        Allocates n² · 8 + 3 · triadElements · 8 bytes.
SweepBenchmarkResult runSweepBenchmark(const SweepBenchmarkSettings& settings);

}  // namespace radkit
