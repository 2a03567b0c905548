#include "solvers/sweep_benchmark.h"

#include <algorithm>
#include <chrono>
#include <limits>
#include <memory>
#include <stdexcept>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

#include "solvers/registry.h"

namespace radkit {

namespace {

using Clock = std::chrono::steady_clock;

template <typename Fn>
double bestSeconds(int repetitions, Fn&& fn) {
  double best = std::numeric_limits<double>::infinity();
  for (int k = 0; k < repetitions; ++k) {
    const Clock::time_point t0 = Clock::now();
    fn();
    best = std::min(best, std::chrono::duration<double>(Clock::now() - t0).count());
  }
  return best;
}

/// STREAM's triad a = b + s c, TBB-parallel with a static partition (the same one that first
/// touched the arrays).
double triadSeconds(std::size_t n, int repetitions) {
  std::unique_ptr<double[]> a(new double[n]), b(new double[n]), c(new double[n]);
  const tbb::blocked_range<std::size_t> all(0, n, 1 << 16);
  tbb::parallel_for(all, [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i < r.end(); ++i) {
      a[i] = 0.0;
      b[i] = 1.0;
      c[i] = 2.0;
    }
  }, tbb::static_partitioner());
  const double s = 3.0;
  return bestSeconds(repetitions, [&] {
    tbb::parallel_for(all, [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t i = r.begin(); i < r.end(); ++i) a[i] = b[i] + s * c[i];
    }, tbb::static_partitioner());
  });
}

/// Best seconds per step of the named solver on the system.
double sweepSeconds(const char* name, const RadiositySystem& system, int repetitions) {
  std::unique_ptr<Solver> solver = makeSolver(name);
  solver->start(system, SolverSettings{});  // also one untimed warm-up sweep
  return bestSeconds(repetitions, [&] { solver->step(); });
}

}  // namespace

SweepBenchmarkResult runSweepBenchmark(const SweepBenchmarkSettings& settings) {
  if (settings.n < 1 || settings.repetitions < 1 || settings.triadElements < 1)
    throw std::invalid_argument("runSweepBenchmark: n, repetitions and triadElements must be >= 1");
  tbb::task_arena arena(settings.threads > 0 ? settings.threads : tbb::task_arena::automatic);
  SweepBenchmarkResult out;
  arena.execute([&] {
    const int n = settings.n;
    FormFactorMatrix f = DenseMatrix<double>(n);
    auto& dense = std::get<DenseMatrix<double>>(f);
    tbb::parallel_for(0, n, [&](int i) { std::fill(dense.row(i), dense.row(i) + n, 1.0 / n); });
    RadiositySystem system;
    system.formFactors = &f;
    system.area.assign(static_cast<std::size_t>(n), 1.0);
    system.reflectance = makeChannels(n, 0.5);
    system.emission = makeChannels(n, 0.0);
    for (auto& channel : system.emission) channel[0] = 1.0;

    out.n = n;
    out.threads = arena.max_concurrency();
    out.repetitions = settings.repetitions;
    out.matrixBytes = static_cast<double>(DenseMatrix<double>::bytesFor(n));
    out.jacobiSeconds = sweepSeconds("jacobi", system, settings.repetitions);
    out.gaussSeidelSeconds = sweepSeconds("gauss-seidel", system, settings.repetitions);
    out.triadSeconds = triadSeconds(settings.triadElements, settings.repetitions);
  });
  out.triadBytes = 3.0 * sizeof(double) * static_cast<double>(settings.triadElements);
  out.jacobiBytesPerSecond = out.matrixBytes / out.jacobiSeconds;
  out.gaussSeidelBytesPerSecond = out.matrixBytes / out.gaussSeidelSeconds;
  out.triadBytesPerSecond = out.triadBytes / out.triadSeconds;
  out.jacobiRatio = out.jacobiBytesPerSecond / out.triadBytesPerSecond;
  out.gaussSeidelRatio = out.gaussSeidelBytesPerSecond / out.triadBytesPerSecond;
  return out;
}

}  // namespace radkit
