#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "experiments/sweep_benchmark.h"

namespace radkit {

TEST(SweepBenchmark, Construct) {
  SweepBenchmarkSettings s;
  s.n = 0;
  EXPECT_THROW(runSweepBenchmark(s), std::invalid_argument);
}

// Small sizes only: the figures must be finite and consistent; no test asserts wall-clock time.
TEST(SweepBenchmark, ExactFiguresConsistent) {
  SweepBenchmarkSettings s;
  s.n = 300;
  s.repetitions = 2;
  s.triadElements = 1 << 16;
  s.threads = 2;
  const SweepBenchmarkResult r = runSweepBenchmark(s);
  EXPECT_EQ(r.n, 300);
  EXPECT_GE(r.threads, 1);
  EXPECT_EQ(r.matrixBytes, 300.0 * 300 * 8);
  EXPECT_EQ(r.triadBytes, 3.0 * 8 * (1 << 16));
  for (double v : {r.jacobiSeconds, r.gaussSeidelSeconds, r.triadSeconds})
    EXPECT_TRUE(std::isfinite(v) && v > 0.0);
  EXPECT_DOUBLE_EQ(r.jacobiRatio, r.jacobiBytesPerSecond / r.triadBytesPerSecond);
}

// The full N = 8192 measurement (512 MiB); run by hand with --gtest_also_run_disabled_tests.
TEST(SweepBenchmark, DISABLED_FullSize) {
  const SweepBenchmarkResult r = runSweepBenchmark(SweepBenchmarkSettings{});
  std::cout << "threads " << r.threads << " jacobi " << r.jacobiBytesPerSecond / 1e9
            << " GB/s gauss-seidel " << r.gaussSeidelBytesPerSecond / 1e9 << " GB/s triad "
            << r.triadBytesPerSecond / 1e9 << " GB/s ratios " << r.jacobiRatio << " "
            << r.gaussSeidelRatio << "\n";
}

}  // namespace radkit
