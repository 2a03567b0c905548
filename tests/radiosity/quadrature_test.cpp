// Gauss–Legendre rules and patch charts.
#include <gtest/gtest.h>

#include <cmath>

#include "radiosity/quadrature.h"

namespace radkit {

TEST(Quadrature, Construct) {
  EXPECT_THROW(gaussLegendre(0), std::invalid_argument);
  for (int n = 1; n <= 8; ++n) {
    GaussLegendreRule r = gaussLegendre(n);
    double sum = 0;
    for (int k = 0; k < n; ++k) {
      sum += r.weights[k];
      EXPECT_GT(r.nodes[k], 0.0);
      EXPECT_LT(r.nodes[k], 1.0);
    }
    EXPECT_NEAR(sum, 1.0, 1e-14);
  }
}

// The n-point rule integrates x^p exactly for p <= 2n − 1: ∫₀¹ x^p dx = 1/(p+1).
TEST(Quadrature, ExactPolynomials) {
  for (int n = 1; n <= 8; ++n) {
    GaussLegendreRule r = gaussLegendre(n);
    for (int p = 0; p <= 2 * n - 1; ++p) {
      double q = 0;
      for (int k = 0; k < n; ++k) q += r.weights[k] * std::pow(r.nodes[k], p);
      EXPECT_NEAR(q, 1.0 / (p + 1), 1e-14) << "n=" << n << " p=" << p;
    }
  }
}

// Charts integrate the constant 1 to the area and x to the first moment (centroid · area).
TEST(Quadrature, ExactChartMoments) {
  Vec3 quad[4] = {{0, 0, 0}, {3, 0, 0}, {2, 1, 0}, {0.5, 1, 0}};
  Vec3 tri[3] = {{0, 0, 0}, {2, 0.5, 0}, {0.5, 1.5, 1}};
  QuadratureSettings s;
  s.order = 3;
  s.maxDepth = 0;
  AdaptiveCubature cubature(s);
  QuadratureStats st;
  auto one = [](const Vec3&) { return 1.0; };
  auto x = [](const Vec3& p) { return p.x; };
  EXPECT_NEAR(cubature.integrate(quad, 4, 1e-9, one, st), 2.25, 1e-13);
  double triArea = 0.5 * length(cross(tri[1] - tri[0], tri[2] - tri[0]));
  EXPECT_NEAR(cubature.integrate(tri, 3, 1e-9, one, st), triArea, 1e-13);
  EXPECT_NEAR(cubature.integrate(tri, 3, 1e-9, x, st), triArea * (0 + 2 + 0.5) / 3, 1e-13);
  Vec3 pent[5] = {{0, 0, 0}, {2, 0, 0}, {3, 1, 0}, {1, 2, 0}, {-1, 1, 0}};
  EXPECT_NEAR(cubature.integrate(pent, 5, 1e-9, one, st), 5.0, 1e-12);  // shoelace
}

}  // namespace radkit
