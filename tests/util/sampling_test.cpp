// Sampling warps: round trips through their inverses, and χ² tests against their pdfs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "radiosity/contour.h"  // clipToHalfSpace: exact cell areas for the expected counts
#include "tests/common/statistics.h"
#include "util/sampling.h"

namespace radkit {
namespace {
// Šidák-corrected significance for the two χ² tests of this file.
const double kAlpha = test::sidakAlpha(0.01, 2);

}  // namespace

TEST(Sampling, Construct) {
  Rng a(7, 3, 4), b(7, 3, 4), c(7, 4, 3);
  EXPECT_EQ(a.nextBits(), b.nextBits());
  EXPECT_NE(Rng(7, 3, 4).nextBits(), c.nextBits());
  std::vector<double> u;
  std::vector<int> scratch;
  Rng r(1, 2, 3);
  latinHypercube(10, 3, r, u, scratch);
  for (int d = 0; d < 3; ++d) {  // one point per stratum in every dimension
    std::vector<int> count(10, 0);
    for (int k = 0; k < 10; ++k) ++count[int(u[k * 3 + d] * 10)];
    for (int c10 : count) EXPECT_EQ(c10, 1);
  }
}

TEST(Sampling, ExactRoundTrips) {
  Rng r(5, 0, 0);
  Vec3 a{0, 0, 0}, b{2, 0.3, 0}, c{0.5, 1.5, 0.2};
  for (int k = 0; k < 1000; ++k) {
    double u0 = r.uniform(), u1 = r.uniform(), v0, v1;
    Vec3 w = sampleCosineHemisphere(u0, u1);
    EXPECT_NEAR(length(w), 1.0, 1e-12);
    invertCosineHemisphereSample(w, v0, v1);
    EXPECT_NEAR(v0, u0, 1e-9);
    EXPECT_NEAR(v1, u1, 1e-9);
    Vec3 p = sampleUniformTriangle(a, b, c, u0, u1);
    invertUniformTriangleSample(a, b, c, p, v0, v1);
    EXPECT_NEAR(v0, u0, 1e-9);
    EXPECT_NEAR(v1, u1, 1e-7);
  }
  Frame f(normalize(Vec3{0.3, -0.5, -0.8}));
  EXPECT_NEAR(dot(f.s, f.t), 0, 1e-15);
  EXPECT_NEAR(dot(cross(f.s, f.t), f.n), 1, 1e-12);
}

// The concentric warp's sine and cosine: their Taylor series against libm over all of
// [−π/4, π/4], to a few units in the last place.
TEST(Sampling, SinCosQuarterPiMatchesLibm) {
  double worst = 0;
  for (int k = -100000; k <= 100000; ++k) {
    const double x = M_PI / 4 * k / 100000.0;
    double s, c;
    sinCosQuarterPi(x, s, c);
    worst = std::max({worst, std::fabs(s - std::sin(x)), std::fabs(c - std::cos(x))});
  }
  EXPECT_LE(worst, 4e-16);
}

// Directions histogrammed on a (cos θ, φ) grid; expected counts from the claimed pdf
// integrated over each cell (dω = d(cos θ) dφ) by a 4×4 midpoint rule.
TEST(Sampling, StatisticalCosineHemisphere) {
  const int nz = 10, nphi = 20, N = 200000;
  std::vector<double> observed(nz * nphi, 0), expected(nz * nphi, 0);
  Rng r(11, 0, 0);
  for (int k = 0; k < N; ++k) {
    Vec3 w = sampleCosineHemisphere(r.uniform(), r.uniform());
    double phi = std::atan2(w.y, w.x) + M_PI;
    int a = std::min(nz - 1, int(w.z * nz)), b = std::min(nphi - 1, int(phi / (2 * M_PI) * nphi));
    ++observed[a * nphi + b];
  }
  const int sub = 4;
  double dz = 1.0 / nz, dphi = 2 * M_PI / nphi;
  for (int a = 0; a < nz; ++a)
    for (int b = 0; b < nphi; ++b)
      for (int i = 0; i < sub; ++i)
        for (int j = 0; j < sub; ++j) {
          double z = (a + (i + 0.5) / sub) * dz, phi = (b + (j + 0.5) / sub) * dphi - M_PI;
          double s = std::sqrt(1 - z * z);
          Vec3 w{s * std::cos(phi), s * std::sin(phi), z};
          expected[a * nphi + b] += N * cosineHemispherePdf(w) * dz * dphi / (sub * sub);
        }
  EXPECT_GT(test::chiSquarePValue(observed, expected, "chi2_cosine_hemisphere.csv", kAlpha),
            kAlpha);
}

// Points on a trapezoid histogrammed on a grid over its bounding rectangle; the pdf 1/A
// integrated over a cell is the area of cell ∩ patch over A (exact, by polygon clipping).
TEST(Sampling, StatisticalPatchArea) {
  Vec3 quad[4] = {{0, 0, 0}, {3, 0, 0}, {2, 1, 0}, {0.5, 1, 0}};
  double area = 0.5 * (3 + 1.5) * 1;
  const int nx = 12, ny = 6, N = 100000;
  std::vector<double> observed(nx * ny, 0), expected(nx * ny, 0);
  Rng r(13, 0, 0);
  for (int k = 0; k < N; ++k) {
    Vec3 p = samplePatchUniform(quad, 4, r.uniform(), r.uniform());
    ++observed[std::min(ny - 1, int(p.y * ny)) * nx + std::min(nx - 1, int(p.x / 3 * nx))];
  }
  for (int a = 0; a < ny; ++a)
    for (int b = 0; b < nx; ++b) {
      Vec3 poly[16], tmp[16];
      int m = 4;
      std::copy(quad, quad + 4, poly);
      double x0 = 3.0 * b / nx, x1 = 3.0 * (b + 1) / nx, y0 = double(a) / ny, y1 = (a + 1.0) / ny;
      const Vec3 planes[4][2] = {{{x0, 0, 0}, {1, 0, 0}},
                                 {{x1, 0, 0}, {-1, 0, 0}},
                                 {{0, y0, 0}, {0, 1, 0}},
                                 {{0, y1, 0}, {0, -1, 0}}};
      for (const auto& pl : planes) {
        m = clipToHalfSpace(poly, m, pl[0], pl[1], tmp);
        std::copy(tmp, tmp + m, poly);
      }
      double cellArea = 0;
      for (int k = 1; k + 1 < m; ++k)
        cellArea += 0.5 * cross(poly[k] - poly[0], poly[k + 1] - poly[0]).z;
      expected[a * nx + b] = N * cellArea * patchUniformPdf(area);
    }
  EXPECT_GT(test::chiSquarePValue(observed, expected, "chi2_patch_area.csv", kAlpha), kAlpha);
}

}  // namespace radkit
