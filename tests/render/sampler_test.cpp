// Samplers: Sobol's (0,2)-net structure survives scrambling and index shuffling, the star
// discrepancy meets the bound for (0,m,2)-nets, points are uniform (χ²) and decorrelated
// across pixels and dimensions, and on a smooth integrand the stratified and Sobol samplers
// converge faster than N^-1/2 while the independent one does not.
#include "render/sampler.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "tests/common/statistics.h"

namespace radkit {
namespace {

constexpr SamplerType kAll[] = {SamplerType::Independent, SamplerType::Stratified,
                                SamplerType::Sobol};

/// Points of one pixel's 2-D dimension `pair` (0: the first get2D, 1: after one get1D and one
/// get2D).
std::vector<std::array<double, 2>> points(Sampler& s, std::uint64_t pixel, int n, int pair) {
  std::vector<std::array<double, 2>> out;
  for (int i = 0; i < n; ++i) {
    s.start(pixel, i);
    if (pair == 1) s.get2D(), s.get1D();
    out.push_back(s.get2D());
  }
  return out;
}

TEST(Sampler, SobolPrefixesAreZeroTwoNets) {
  // Every elementary interval [a/2^j, (a+1)/2^j) × [b/2^k, (b+1)/2^k) with j + k = m holds
  // exactly one of the first 2^m points, for every m up to 8, pixel and dimension pair.
  for (std::uint64_t pixel : {0u, 1u, 77u})
    for (int pair : {0, 1}) {
      auto s = makeSampler(SamplerType::Sobol, 3, 0, 256);
      const auto p = points(*s, pixel, 256, pair);
      for (int m = 1; m <= 8; ++m)
        for (int j = 0; j <= m; ++j) {
          std::set<long> cells;
          for (int i = 0; i < (1 << m); ++i)
            cells.insert(long(p[i][0] * (1 << j)) * (1 << (m - j)) +
                         long(p[i][1] * (1 << (m - j))));
          EXPECT_EQ(cells.size(), std::size_t(1) << m)
              << "pixel " << pixel << " pair " << pair << " m " << m;
        }
    }
  // Unscrambled, the first points are Sobol's: (0, 0), (1/2, 1/2), (1/4, 3/4), (3/4, 1/4).
  EXPECT_EQ(sobol0(1), 1u << 31);
  EXPECT_EQ(sobol1(1), 1u << 31);
  EXPECT_EQ(sobol0(2), 1u << 30);
  EXPECT_EQ(sobol1(2), 3u << 30);
  EXPECT_EQ(sobol0(3), 3u << 30);
  EXPECT_EQ(sobol1(3), 1u << 30);
}

/// Exact star discrepancy of 2-D points: over anchored boxes with corners at the points'
/// coordinates (and 1), the larger of the open-box deficit and the closed-box excess.
double starDiscrepancy(const std::vector<std::array<double, 2>>& p) {
  std::vector<double> xs{1}, ys{1};
  for (const auto& q : p) xs.push_back(q[0]), ys.push_back(q[1]);
  const double n = double(p.size());
  double d = 0;
  for (double x : xs)
    for (double y : ys) {
      int open = 0, closed = 0;
      for (const auto& q : p) {
        open += q[0] < x && q[1] < y;
        closed += q[0] <= x && q[1] <= y;
      }
      d = std::max({d, x * y - open / n, closed / n - x * y});
    }
  return d;
}

TEST(Sampler, SobolMeetsTheNetDiscrepancyBound) {
  // Kritzer (2006): a (0,m,2)-net in base 2 has N·D* <= m/3 + 19/9. Random points of the
  // same count are far above it (N·D* grows like √N): the independent sampler is the control.
  const int m = 8, n = 1 << m;
  const double bound = (m / 3.0 + 19.0 / 9) / n;
  for (std::uint64_t pixel : {5u, 6u}) {
    auto sobol = makeSampler(SamplerType::Sobol, 1, 0, n);
    EXPECT_LE(starDiscrepancy(points(*sobol, pixel, n, 0)), bound);
    auto independent = makeSampler(SamplerType::Independent, 1, 0, n);
    EXPECT_GT(starDiscrepancy(points(*independent, pixel, n, 0)), bound);
  }
}

TEST(Sampler, StatisticalUniformAndDecorrelated) {
  // Pooled over pixels, (first 2-D dimension) and (x of it, the next 1-D dimension) fill a
  // 16 × 16 histogram uniformly; the first number of sample 0 is uniform across pixels (it
  // would be one value if every pixel shared a scramble).
  const double alpha = test::sidakAlpha(0.01, 3 * 3);
  for (SamplerType type : kAll) {
    auto s = makeSampler(type, 9, 0, 16);
    std::vector<double> grid(256, 0), pair(256, 0), first(64, 0);
    for (std::uint64_t pixel = 0; pixel < 1024; ++pixel)
      for (int i = 0; i < 16; ++i) {
        s->start(pixel, i);
        const auto u = s->get2D();
        const double v = s->get1D();
        grid[int(u[0] * 16) * 16 + int(u[1] * 16)] += 1;
        pair[int(u[0] * 16) * 16 + int(v * 16)] += 1;
      }
    for (std::uint64_t pixel = 0; pixel < 4096; ++pixel) {
      s->start(pixel, 0);
      first[int(s->get2D()[0] * 64)] += 1;
    }
    const std::string name = "sampler-" + samplerName(type);
    EXPECT_GT(test::chiSquarePValue(grid, std::vector<double>(256, 64), name + "-grid.csv", alpha),
              alpha)
        << name;
    EXPECT_GT(test::chiSquarePValue(pair, std::vector<double>(256, 64), name + "-pair.csv", alpha),
              alpha)
        << name;
    EXPECT_GT(
        test::chiSquarePValue(first, std::vector<double>(64, 64), name + "-pixels.csv", alpha),
        alpha)
        << name;
  }
}

/// Mean squared error of N-point estimates of ∫∫ u·e^{uv} = e − 2 over R pixels (independent
/// replicates), with its standard error; and the mean error with its standard error.
struct Errors {
  double mse = 0, mseError = 0, bias = 0, biasError = 0;
};

Errors integrate(SamplerType type, int n, int replicates) {
  auto s = makeSampler(type, 4, 0, n);
  std::vector<double> e;
  for (int r = 0; r < replicates; ++r) {
    double sum = 0;
    for (int i = 0; i < n; ++i) {
      s->start(std::uint64_t(r), i);
      const auto u = s->get2D();
      sum += u[0] * std::exp(u[0] * u[1]);
    }
    e.push_back(sum / n - (M_E - 2));
  }
  Errors out;
  double sq2 = 0, e2 = 0;
  for (double x : e) out.mse += x * x, out.bias += x;
  out.mse /= replicates, out.bias /= replicates;
  for (double x : e)
    sq2 += (x * x - out.mse) * (x * x - out.mse), e2 += (x - out.bias) * (x - out.bias);
  out.mseError = std::sqrt(sq2 / (replicates - 1) / replicates);
  out.biasError = std::sqrt(e2 / (replicates - 1) / replicates);
  return out;
}

TEST(Sampler, StatisticalConvergenceOnASmoothIntegrand) {
  // From 16 to 1 024 points an N^-1/2 error shrinks 8×. L = ½ ln(MSE₁₆/MSE₁₀₂₄) has standard
  // error ½√((σ₁/MSE₁)² + (σ₂/MSE₂)²) (delta method); stratified (≈ N^-1) and Sobol (≈ N^-3/2)
  // must beat ln 8 by 4 of them, and independent samples must sit within 4 of ln 8.
  const int replicates = 128;
  for (SamplerType type : kAll) {
    const Errors a = integrate(type, 16, replicates), b = integrate(type, 1024, replicates);
    const double L = 0.5 * std::log(a.mse / b.mse);
    const double se = 0.5 * std::hypot(a.mseError / a.mse, b.mseError / b.mse);
    const std::string name = samplerName(type);
    std::printf("%-11s RMSE 16: %.3g  1024: %.3g  ratio %.1f (N^-1/2: 8)\n", name.c_str(),
                std::sqrt(a.mse), std::sqrt(b.mse), std::exp(L));
    if (type == SamplerType::Independent)
      EXPECT_NEAR(L, std::log(8.0), 4 * se) << name;
    else
      EXPECT_GT(L - 4 * se, std::log(8.0)) << name;
    EXPECT_NEAR(a.bias, 0, 4 * a.biasError) << name;
    EXPECT_NEAR(b.bias, 0, 4 * b.biasError) << name;
  }
}

TEST(Sampler, ReversedSobol1IsSobol1Reversed) {
  // The Sobol sampler works on bit-reversed numbers; its table must be sobol1's, reversed.
  auto reverse = [](std::uint32_t x) {
    std::uint32_t r = 0;
    for (int b = 0; b < 32; ++b) r |= (x >> b & 1u) << (31 - b);
    return r;
  };
  for (std::uint32_t i : {0u, 1u, 2u, 3u, 255u, 256u, 12345u, 0x80000001u, 0xffffffffu})
    EXPECT_EQ(reversedSobol1(i), reverse(sobol1(i))) << i;
}

TEST(Sampler, DeterministicPerSeedAndPermutationsArePermutations) {
  for (SamplerType type : kAll) {
    auto a = makeSampler(type, 7, 1, 8), b = makeSampler(type, 7, 1, 8),
         c = makeSampler(type, 8, 1, 8);
    a->start(12, 0), b->start(12, 0), c->start(12, 0);  // independent streams are read in order
    const double x = a->get1D();
    EXPECT_EQ(x, b->get1D());
    EXPECT_NE(x, c->get1D());
  }
  for (std::uint32_t n : {1u, 5u, 16u, 100u}) {
    std::set<std::uint32_t> seen;
    std::set<std::uint32_t> shuffled;
    for (std::uint32_t i = 0; i < n; ++i)
      seen.insert(permuteIndex(i, n, 1234)), shuffled.insert(shuffleIndex(i, n, 99));
    EXPECT_EQ(seen.size(), n);
    EXPECT_LT(*seen.rbegin(), n);
    EXPECT_EQ(shuffled.size(), n);
    EXPECT_LT(*shuffled.rbegin(), n);
  }
  EXPECT_THROW(parseSamplerType("halton"), std::invalid_argument);
}

}  // namespace
}  // namespace radkit
