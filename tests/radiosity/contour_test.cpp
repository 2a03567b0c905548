// Lambert's contour formula against the disk closed forms and the closure of an enclosure.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "radiosity/contour.h"
#include "test_scenes.h"
#include "util/sampling.h"

namespace radkit {
namespace {
std::vector<Vec3> regularPolygon(const Vec3& centre, double radius, int sides, bool ccwUp) {
  std::vector<Vec3> p;
  for (int k = 0; k < sides; ++k) {
    double phi = 2 * M_PI * k / sides * (ccwUp ? 1 : -1);
    p.push_back(centre + Vec3{std::cos(phi), std::sin(phi), 0} * radius);
  }
  return p;
}
}  // namespace

TEST(Contour, Construct) {
  // A square straddling the plane z = 0 keeps its upper half, with two new vertices.
  std::vector<Vec3> square = {{0, 0, -1}, {1, 0, -1}, {1, 0, 1}, {0, 0, 1}};
  Vec3 out[8];
  int m = clipToHalfSpace(square.data(), 4, {0, 0, 0}, {0, 0, 1}, out);
  ASSERT_EQ(m, 4);
  for (int k = 0; k < m; ++k) EXPECT_GE(out[k].z, 0.0);
  EXPECT_EQ(clipToHalfSpace(square.data(), 4, {0, 0, 2}, {0, 0, 1}, out), 0);
  EXPECT_EQ(pointToPolygonFormFactor({0, 0, 2}, {0, 0, 1}, square), 0.0);
}

// Differential element on the axis of a parallel disk: F = R²/(R²+h²). The inscribed N-gon lies
// between the disks of radius R cos(π/N) and R, and the projected solid angle grows with the
// polygon, so the analytic values for those two radii bracket the polygon's exact value.
TEST(Contour, ExactDiskOnAxis) {
  EXPECT_NEAR(test::diskOnAxis(1, 1), 0.5, 1e-15);
  for (double h : {0.25, 1.0, 3.0}) {
    for (int sides : {64, 1024}) {
      double f = pointToPolygonFormFactor({0, 0, 0}, {0, 0, 1},
                                          regularPolygon({0, 0, h}, 1.0, sides, false));
      double inner = test::diskOnAxis(std::cos(M_PI / sides), h), outer = test::diskOnAxis(1, h);
      EXPECT_GE(f, inner - 1e-15) << "h=" << h << " N=" << sides;
      EXPECT_LE(f, outer + 1e-15) << "h=" << h << " N=" << sides;
    }
  }
}

TEST(Contour, ExactDiskOffAxis) {
  EXPECT_NEAR(test::diskOffAxis(1, 1, 0.5), 0.4379826327, 1e-10);
  for (double l : {0.5, 2.0}) {
    const int sides = 2048;
    double f =
        pointToPolygonFormFactor({l, 0, 0}, {0, 0, 1}, regularPolygon({0, 0, 1}, 1.0, sides, true));
    double inner = test::diskOffAxis(std::cos(M_PI / sides), 1, l);
    EXPECT_GE(f, inner - 1e-15);
    EXPECT_LE(f, test::diskOffAxis(1, 1, l) + 1e-15);
  }
}

// A point inside the unit cube sees the six faces; whatever its normal, the projected solid
// angles of the faces sum to π (F sums to 1). Most faces straddle its tangent plane, so this
// checks the clipping; the unclipped sum does not close.
TEST(Contour, ExactClosureWithClipping) {
  test::MeshBuilder cube = test::cubeInterior(1);
  const PatchMesh& mesh = cube.mesh();
  Rng rng(3, 0, 0);
  double worstUnclipped = 0;
  for (int trial = 0; trial < 50; ++trial) {
    Vec3 x{0.1 + 0.8 * rng.uniform(), 0.1 + 0.8 * rng.uniform(), 0.1 + 0.8 * rng.uniform()};
    Vec3 n = normalize(Vec3{rng.uniform() - 0.5, rng.uniform() - 0.5, rng.uniform() - 0.5});
    double sum = 0, unclipped = 0;
    for (const Patch& p : mesh.patches) {
      std::vector<Vec3> poly = mesh.polygon(p);
      sum += pointToPolygonFormFactor(x, n, poly);
      unclipped += unclippedContourFormFactor(x, n, poly.data(), int(poly.size()));
    }
    EXPECT_NEAR(sum, 1.0, 1e-12);
    worstUnclipped = std::max(worstUnclipped, std::fabs(unclipped - 1));
  }
  EXPECT_GT(worstUnclipped, 1e-2);
}

// The projected solid angle does not depend on the polygon's orientation or starting vertex.
TEST(Contour, ExactOrientationIndependent) {
  std::vector<Vec3> a = regularPolygon({0.3, -0.2, 1}, 0.7, 7, true);
  std::vector<Vec3> b(a.rbegin(), a.rend());
  Vec3 n = normalize(Vec3{0.2, 0.1, 1});
  EXPECT_NEAR(pointToPolygonFormFactor({0, 0, 0}, n, a), pointToPolygonFormFactor({0, 0, 0}, n, b),
              1e-15);
}

}  // namespace radkit

namespace radkit {
// The contour sum runs branch-free over the edges with its own atan2 (contour.cpp); against
// the same sum with the C library's atan2, on polygons of 3 to 12 vertices seen from random
// points in front, many of them close to an edge or a vertex where angles near 0 and π and
// both sides of tan(π/8) occur.
TEST(Contour, VectorisedSumMatchesLibraryAtan2) {
  Rng rng(41, 0, 0);
  double worst = 0;
  int nearEdge = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const int sides = 3 + int(rng.uniform() * 10);
    std::vector<Vec3> polygon;
    for (int k = 0; k < sides; ++k) {
      double phi = 2 * M_PI * (k + 0.8 * rng.uniform()) / sides, r = 0.5 + rng.uniform();
      polygon.push_back({r * std::cos(phi), r * std::sin(phi), 0});
    }
    Vec3 x{2 * rng.uniform() - 1, 2 * rng.uniform() - 1, std::pow(10.0, -6 * rng.uniform())};
    if (trial % 4 == 0) {  // just above a point of an edge
      const Vec3 &a = polygon[0], &b = polygon[1];
      double t = rng.uniform();
      x = a + (b - a) * t + Vec3{0, 0, 1e-9 + 1e-3 * rng.uniform()};
      ++nearEdge;
    }
    Vec3 n = normalize(Vec3{rng.uniform() - 0.5, rng.uniform() - 0.5, -1.5});  // sees z = 0
    // Terms of both signs cancel: compare against the sum of their magnitudes.
    double reference = 0, scale = 0;
    for (int k = 0; k < sides; ++k) {
      Vec3 a = polygon[k] - x, b = polygon[(k + 1) % sides] - x, c = cross(a, b);
      double len = length(c);
      if (!(len > 0)) continue;
      double term = std::atan2(len, dot(a, b)) * dot(n, c) / len;
      reference += term, scale += std::fabs(term);
    }
    reference = std::fabs(reference) / (2 * M_PI), scale /= 2 * M_PI;
    double f = unclippedContourFormFactor(x, n, polygon.data(), sides);
    ASSERT_TRUE(std::isfinite(f));
    worst = std::max(worst, std::fabs(f - reference) / scale);
  }
  EXPECT_LT(worst, 1e-13);
  EXPECT_EQ(nearEdge, 1000);
  std::printf("largest difference from the library atan2, relative to the terms: %.2e\n", worst);
}
}  // namespace radkit
