#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "analytic_systems.h"

namespace radkit {
using namespace radkit::test;

TEST(Kernels, Construct) {
  const Channels x = makeChannels(4, 2.5);
  for (const auto& channel : x) EXPECT_EQ(channel, std::vector<double>(4, 2.5));
  EXPECT_EQ(
      maxAbs({std::vector<double>{1, -3}, std::vector<double>{2, 0}, std::vector<double>{0, 0}}),
      3.0);
}

// y = F x on every storage against a naive long-double product; sizes straddle the serial and
// parallel paths and the 4-wide unrolled loop's tail.
TEST(Kernels, ExactMultiplyEveryStorage) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int n : {1, 3, 7, 250}) {
    std::vector<double> f(std::size_t(n) * n);
    for (double& v : f) v = u(rng) < 0.3 ? 0.0 : u(rng);
    Channels x = makeChannels(n);
    for (auto& channel : x)
      for (double& v : channel) v = u(rng) - 0.5;
    for (Storage s : kAllStorages) {
      Problem p = makeProblem(f, std::vector<double>(n, 1.0), makeChannels(n), makeChannels(n), s);
      Channels y;
      multiply(*p.f, x, y);
      for (int c = 0; c < 3; ++c)
        for (int i = 0; i < n; ++i) {
          long double expect = 0;
          for (int j = 0; j < n; ++j)
            expect +=
                std::visit([&](const auto& m) { return (long double)m(i, j); }, *p.f) * x[c][j];
          EXPECT_NEAR(y[c][i], double(expect), 1e-13 * n) << storageLabel(s) << " n " << n;
        }
    }
  }
}

TEST(Kernels, ExactSegmentsAddUpToRow) {
  DenseMatrix<float> m(9);
  for (int j = 0; j < 9; ++j) m(2, j) = float(j + 1);
  std::vector<double> ones(9, 1.0);
  const std::array<const double*, 1> x = {ones.data()};
  EXPECT_EQ(rowDots<1>(m, 2, 0, 9, x)[0], 45.0);
  EXPECT_EQ(rowDots<1>(m, 2, 2, 7, x)[0], 3.0 + 4 + 5 + 6 + 7);
  CsrMatrix<double> c(3, {0, 2, 2, 5}, {0, 2, 0, 1, 2}, {1, 2, 3, 4, 5});
  EXPECT_EQ(rowDots<1>(c, 2, 1, 3, {ones.data()})[0], 9.0);
  EXPECT_EQ(rowDots<1>(c, 0, 1, 2, {ones.data()})[0], 0.0);
  EXPECT_EQ(rowSums(FormFactorMatrix(c)), (std::vector<double>{3, 0, 12}));
}

// Dense rows taken four at a time give each row exactly the one-row kernel's bits, whatever
// the row range's start and length and the column segment's tail.
TEST(Kernels, ExactRowGroupsMatchSingleRows) {
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int n = 23;
  DenseMatrix<double> d(n);
  DenseMatrix<float> f(n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      d(i, j) = u(rng);
      f(i, j) = float(u(rng));
    }
  Channels x = makeChannels(n);
  for (auto& channel : x)
    for (double& v : channel) v = u(rng) * 1e3;
  const auto xp = channelPointers(x);
  auto check = [&](const auto& m, int rowBegin, int rowEnd, int begin, int end) {
    int visited = 0;
    rangeDots<3>(m, rowBegin, rowEnd, begin, end, xp, [&](int i, const std::array<double, 3>& s) {
      EXPECT_EQ(i, rowBegin + visited++);
      const auto one = rowDots<3>(m, i, begin, end, xp);
      for (int c = 0; c < 3; ++c) EXPECT_EQ(0, std::memcmp(&s[c], &one[c], sizeof(double))) << i;
    });
    EXPECT_EQ(visited, rowEnd - rowBegin);
  };
  for (auto [rowBegin, rowEnd, begin, end] : {std::array<int, 4>{0, 23, 0, 23},
                                              {1, 22, 3, 20},
                                              {5, 8, 0, 7},
                                              {2, 2, 0, 23},
                                              {0, 16, 9, 9}}) {
    check(d, rowBegin, rowEnd, begin, end);
    check(f, rowBegin, rowEnd, begin, end);
  }
}

TEST(Kernels, ExactDotIsDeterministic) {
  std::vector<double> a(100003), b(100003);
  for (std::size_t i = 0; i < a.size(); ++i) {
    a[i] = std::sin(double(i));
    b[i] = std::cos(0.5 * double(i));
  }
  const double first = dot(a, b);
  for (int k = 0; k < 5; ++k)
    EXPECT_EQ(std::memcmp(&first, &(const double&)dot(a, b), sizeof first), 0);
  long double naive = 0;
  for (std::size_t i = 0; i < a.size(); ++i) naive += (long double)a[i] * b[i];
  EXPECT_NEAR(first, double(naive), 1e-10);
}

}  // namespace radkit
