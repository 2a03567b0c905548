#include "experiments/sweep_benchmark.h"

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

/// Seconds fn() takes.
template <typename Fn>
double seconds(Fn&& fn) {
  const Clock::time_point t0 = Clock::now();
  fn();
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

/// STREAM's triad a = b + s c over arrays first touched by the same static TBB partition.
class Triad {
 public:
  explicit Triad(std::size_t n)
      : m_a(new double[n]), m_b(new double[n]), m_c(new double[n]), m_all(0, n, 1 << 16) {
    tbb::parallel_for(
        m_all,
        [&](const tbb::blocked_range<std::size_t>& r) {
          for (std::size_t i = r.begin(); i < r.end(); ++i) {
            m_a[i] = 0.0;
            m_b[i] = 1.0;
            m_c[i] = 2.0;
          }
        },
        tbb::static_partitioner());
  }
  void operator()() {
    const double s = 3.0;
    tbb::parallel_for(
        m_all,
        [&](const tbb::blocked_range<std::size_t>& r) {
          for (std::size_t i = r.begin(); i < r.end(); ++i) m_a[i] = m_b[i] + s * m_c[i];
        },
        tbb::static_partitioner());
  }

 private:
  std::unique_ptr<double[]> m_a, m_b, m_c;
  tbb::blocked_range<std::size_t> m_all;
};

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
    // Round-robin, best of each: a neighbour's load on a shared machine then slows all three
    // kernels alike instead of whichever happened to run during it.
    std::unique_ptr<Solver> jacobi = makeSolver("jacobi"), gaussSeidel = makeSolver("gauss-seidel");
    jacobi->start(system, SolverSettings{});  // each start is also one untimed warm-up sweep
    gaussSeidel->start(system, SolverSettings{});
    Triad triad(settings.triadElements);
    triad();
    const double inf = std::numeric_limits<double>::infinity();
    out.jacobiSeconds = out.gaussSeidelSeconds = out.triadSeconds = inf;
    for (int k = 0; k < settings.repetitions; ++k) {
      out.triadSeconds = std::min(out.triadSeconds, seconds(triad));
      out.jacobiSeconds = std::min(out.jacobiSeconds, seconds([&] { jacobi->step(); }));
      out.gaussSeidelSeconds =
          std::min(out.gaussSeidelSeconds, seconds([&] { gaussSeidel->step(); }));
    }
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
