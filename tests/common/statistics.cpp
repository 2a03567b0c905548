// Statistical test helpers (Nori's chi2test/ttest, adapted): χ² goodness of fit.
#include "tests/common/statistics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

namespace radkit::test {

double chiSquareTail(double x, int k) {
  // Q(a, z) with a = k/2, z = x/2: series for z < a + 1, Lentz continued fraction otherwise
  // (Numerical Recipes §6.2).
  double a = 0.5 * k, z = 0.5 * x;
  if (z <= 0) return 1.0;
  double lg = std::lgamma(a);
  if (z < a + 1) {
    double term = 1 / a, sum = term;
    for (int n = 1; n < 1000 && std::fabs(term) > 1e-16 * std::fabs(sum); ++n)
      term *= z / (a + n), sum += term;
    return 1 - sum * std::exp(-z + a * std::log(z) - lg);
  }
  double b = z + 1 - a, c = 1e300, d = 1 / b, h = d;
  for (int i = 1; i < 1000; ++i) {
    double an = -i * (i - a);
    b += 2;
    d = an * d + b;
    if (std::fabs(d) < 1e-300) d = 1e-300;
    c = b + an / c;
    if (std::fabs(c) < 1e-300) c = 1e-300;
    d = 1 / d;
    double delta = d * c;
    h *= delta;
    if (std::fabs(delta - 1) < 1e-15) break;
  }
  return std::exp(-z + a * std::log(z) - lg) * h;
}

/// Pools cells expecting < 5 into one, returns the p-value; fails on samples in zero cells.
double chiSquarePValue(const std::vector<double>& observed, const std::vector<double>& expected,
                       const std::string& dumpName, double alpha) {
  double chi2 = 0, pooledObs = 0, pooledExp = 0;
  int dof = -1;
  for (std::size_t k = 0; k < observed.size(); ++k) {
    if (expected[k] <= 0) {
      EXPECT_EQ(observed[k], 0) << "sample where the pdf is zero (cell " << k << ")";
      continue;
    }
    if (expected[k] < 5) {
      pooledObs += observed[k], pooledExp += expected[k];
      continue;
    }
    chi2 += (observed[k] - expected[k]) * (observed[k] - expected[k]) / expected[k];
    ++dof;
  }
  if (pooledExp > 0) chi2 += (pooledObs - pooledExp) * (pooledObs - pooledExp) / pooledExp, ++dof;
  double p = chiSquareTail(chi2, dof);
  if (p < alpha) {
    std::ofstream dump(dumpName);
    dump << "cell,observed,expected\n";
    for (std::size_t k = 0; k < observed.size(); ++k)
      dump << k << ',' << observed[k] << ',' << expected[k] << '\n';
  }
  return p;
}

double sidakAlpha(double alpha, int tests) { return 1 - std::pow(1 - alpha, 1.0 / tests); }

double studentTCritical(double alpha, double nu) {
  const bool normal = !std::isfinite(nu) || nu > 1e6;
  const double logC =
      normal ? 0 : std::lgamma((nu + 1) / 2) - std::lgamma(nu / 2) - 0.5 * std::log(nu * M_PI);
  auto density = [&](double x) {
    return normal ? std::exp(-0.5 * x * x) / std::sqrt(2 * M_PI)
                  : std::exp(logC - (nu + 1) / 2 * std::log1p(x * x / nu));
  };
  // P(|T| > t) = 1 − 2 ∫_0^t density.
  auto tail = [&](double t) {
    const int n = 4000;
    const double h = t / n;
    double sum = density(0) + density(t);
    for (int i = 1; i < n; ++i) sum += density(i * h) * (i % 2 ? 4 : 2);
    return 1 - 2 * sum * h / 3;
  };
  double lo = 0, hi = 1;
  while (tail(hi) > alpha) hi *= 2;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (tail(mid) > alpha ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace radkit::test
