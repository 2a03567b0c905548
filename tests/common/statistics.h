// Statistical test helpers shared by every sampler and Monte Carlo test.
#pragma once

#include <string>
#include <vector>

namespace radkit::test {

/// Upper tail of the χ² distribution with k degrees of freedom (regularized Γ(k/2, x/2)).
double chiSquareTail(double x, int k);

/// \brief χ² goodness of fit of histogram counts against expected counts (docs/oracles.md): cells
/// expecting fewer than 5 are pooled, a sample in a cell of zero expectation fails the test
/// (gtest failure), and when p < alpha both tables are written to `dumpName` as CSV.
/// \return the p-value.
double chiSquarePValue(const std::vector<double>& observed, const std::vector<double>& expected,
                       const std::string& dumpName, double alpha);

/// Šidák-corrected level for one of m tests at family level alpha: 1 − (1 − α)^(1/m).
double sidakAlpha(double alpha, int tests);

/// \brief Two-sided critical value of Student's t with nu degrees of freedom (nu > 0, may be
/// fractional, as Welch–Satterthwaite's): P(|T| > t) = alpha. Simpson's rule on the density
/// and bisection; nu = ∞ is the normal distribution.
double studentTCritical(double alpha, double nu);

}  // namespace radkit::test
