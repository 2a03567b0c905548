// Next-event estimation by solid angle (Ureña, Fajardo & King 2013) against closed forms:
// the solid angle of a rectangle, the uniformity of the sampled directions, and the
// irradiance of a point facing a square light.
#include "render/spherical_rectangle.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "geometry/ray_scene.h"
#include "geometry/scene_loader.h"
#include "geometry/subdivision.h"
#include "render/shading_context.h"
#include "tests/common/test_util.h"
#include "util/sampling.h"

namespace radkit {
namespace {

/// Solid angle of the rectangle [0, a] × [0, b] at height h above the origin, one corner
/// straight above it (signed in a and b, so rectangles add and subtract).
double cornerSolidAngle(double a, double b, double h) {
  return std::atan(a * b / (h * std::sqrt(a * a + b * b + h * h)));
}
double rectangleSolidAngle(double x0, double x1, double y0, double y1, double h) {
  return cornerSolidAngle(x1, y1, h) - cornerSolidAngle(x0, y1, h) - cornerSolidAngle(x1, y0, h) +
         cornerSolidAngle(x0, y0, h);
}
/// Form factor from a point to a parallel rectangle [0, a] × [0, b] at height h, one corner
/// above it (Howell's catalogue, B-3), signed like cornerSolidAngle.
double cornerFormFactor(double a, double b, double h) {
  const double x = a / h, y = b / h, sx = std::sqrt(1 + x * x), sy = std::sqrt(1 + y * y);
  return (x / sx * std::atan(y / sx) + y / sy * std::atan(x / sy)) / (2 * M_PI);
}

TEST(SphericalRectangle, SolidAngleMatchesTheClosedForm) {
  for (double h : {0.01, 0.3, 1.0, 7.0})
    for (double x0 : {-0.4, 0.25}) {
      // The rectangle [x0, x0 + 1.3] × [−0.2, 0.5] in the plane z = ±h, seen from the origin.
      const double expected = rectangleSolidAngle(x0, x0 + 1.3, -0.2, 0.5, h);
      for (double side : {1.0, -1.0}) {
        SphericalRectangle r({0, 0, 0}, {x0, -0.2, side * h}, {1.3, 0, 0}, {0, 0.7, 0});
        EXPECT_NEAR(r.solidAngle(), expected, 1e-12 * expected) << h << " " << x0 << " " << side;
      }
    }
  // In the rectangle's plane it subtends nothing.
  EXPECT_EQ(SphericalRectangle({0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {0, 1, 0}).solidAngle(), 0);
}

TEST(SphericalRectangle, StatisticalUniformInSolidAngle) {
  // Samples counted in an 8 × 8 grid of sub-rectangles must follow the sub-rectangles' exact
  // solid angles: χ² with 63 degrees of freedom stays below 120 with probability 1 − 1e-5.
  // Points uniform by area instead give χ² ≈ 6·10⁴ here.
  const double x0 = -0.3, y0 = 0.2, w = 1.3, hgt = 0.9, h = 0.4;
  const Vec3 origin{0.1, -0.2, 0.3}, corner = origin + Vec3{x0, y0, h};
  SphericalRectangle r(origin, corner, {w, 0, 0}, {0, hgt, 0});
  const int grid = 8, n = 64000;
  std::vector<int> count(grid * grid, 0);
  Rng rng(7, 0, 0);
  for (int i = 0; i < n; ++i) {
    const double u = rng.uniform(), v = rng.uniform();
    const Vec3 p = r.sample(u, v);
    ASSERT_NEAR(p.z, corner.z, 1e-12);
    const double s = (p.x - corner.x) / w, t = (p.y - corner.y) / hgt;
    ASSERT_TRUE(s >= -1e-12 && s <= 1 + 1e-12 && t >= -1e-12 && t <= 1 + 1e-12) << s << " " << t;
    ++count[std::min(grid - 1, int(s * grid)) * grid + std::min(grid - 1, int(t * grid))];
  }
  double chi2 = 0;
  for (int a = 0; a < grid; ++a)
    for (int b = 0; b < grid; ++b) {
      const double omega = rectangleSolidAngle(x0 + w * a / grid, x0 + w * (a + 1) / grid,
                                               y0 + hgt * b / grid, y0 + hgt * (b + 1) / grid, h);
      const double expected = n * omega / r.solidAngle();
      chi2 += (count[a * grid + b] - expected) * (count[a * grid + b] - expected) / expected;
    }
  EXPECT_LT(chi2, 120);
}

TEST(SphericalRectangle, PatchRectangleRecognisesRectanglesOnly) {
  Vec3 corner, ex, ey;
  const Vec3 square[4] = {{0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}};
  ASSERT_TRUE(patchRectangle(square, 4, corner, ex, ey));
  EXPECT_NEAR(length(cross(ex, ey) - Vec3{0, 0, -1}), 0, 1e-15);  // keeps the orientation
  const Vec3 rhombus[4] = {{0, 0, 0}, {1, 0, 0}, {1.5, 1, 0}, {0.5, 1, 0}};
  EXPECT_FALSE(patchRectangle(rhombus, 4, corner, ex, ey));
  EXPECT_FALSE(patchRectangle(square, 3, corner, ex, ey));
}

TEST(LightSampling, StatisticalIrradianceOfASquareLight) {
  // A grey (ρ = 0.5) unit square facing a lamp (exitance 1) one unit above it: the light a
  // point reflects is ρ/π · F, F the point-to-square form factor. Next-event estimation plus
  // the BSDF-sampled ray's hits on the lamp, each weighted by the power heuristic with the
  // other's density (lightPdf from the point), must meet it within 4 standard errors with
  // either light sampling, and sampling by solid angle must have the smaller error.
  Scene scene = loadScene(test::dataPath("parallel-squares.json"));
  PatchMesh mesh = subdivide(scene, {0, 0});
  RayScene rays(mesh);
  for (const auto& [x, y] : {std::pair{0.5, 0.5}, std::pair{0.2, 0.7}, std::pair{0.03, 0.97}}) {
    const double f = cornerFormFactor(x, y, 1) + cornerFormFactor(1 - x, y, 1) +
                     cornerFormFactor(x, 1 - y, 1) + cornerFormFactor(1 - x, 1 - y, 1);
    const double exact = 0.5 / M_PI * f;
    double standardError[2];
    for (LightSampling mode : {LightSampling::Area, LightSampling::SolidAngle}) {
      ShadingScene shading(scene, mesh, rays, {}, GlossyModel::AsDeclared, mode);
      const std::optional<SurfaceHit> hit = shading.intersect({x, y, 0.5}, {0, 0, -1});
      ASSERT_TRUE(hit && hit->bsdf);
      std::unique_ptr<Sampler> sampler = makeSampler(SamplerType::Independent, 3, 0, 1);
      const int n = 20000;
      double sum = 0, sumSq = 0;
      long long cast = 0;
      for (int i = 0; i < n; ++i) {
        sampler->start(0, i);
        double l = shading.directLight(*hit, *sampler, cast).y;
        const double u0 = sampler->get1D();
        const auto [u1, u2] = sampler->get2D();
        if (const std::optional<BsdfSample> bs = hit->bsdf->sample(hit->wo, u0, u1, u2)) {
          const Vec3 wi = hit->frame.toWorld(bs->wi);
          if (const std::optional<SurfaceHit> lamp = shading.intersect(shading.spawn(*hit, wi), wi))
            l += bs->weight.y * shading.emitted(*lamp).y *
                 powerHeuristic(bs->pdf, shading.lightPdf(*lamp, hit->point));
        }
        sum += l, sumSq += l * l;
      }
      const double mean = sum / n, se = std::sqrt((sumSq / n - mean * mean) / (n - 1));
      standardError[int(mode)] = se;
      EXPECT_NEAR(mean, exact, 4 * se) << x << " " << y << " mode " << int(mode);
    }
    EXPECT_LT(standardError[int(LightSampling::SolidAngle)],
              0.8 * standardError[int(LightSampling::Area)])
        << x << " " << y;
  }
}

TEST(LightSampling, LightPdfIsTheDensityOfDirectLight) {
  // Over the directions to the lamp, lightPdf must integrate to 1: ∫ p dω = ∫ p cos θ'/r² dA,
  // estimated with points uniform on the unit lamp (area density 1).
  Scene scene = loadScene(test::dataPath("parallel-squares.json"));
  PatchMesh mesh = subdivide(scene, {0, 0});
  RayScene rays(mesh);
  for (LightSampling mode : {LightSampling::Area, LightSampling::SolidAngle}) {
    ShadingScene shading(scene, mesh, rays, {}, GlossyModel::AsDeclared, mode);
    const Vec3 from{0.2, 0.7, 0};
    Rng rng(11, 0, 0);
    const int n = 20000;
    double sum = 0, sumSq = 0;
    for (int i = 0; i < n; ++i) {
      const Vec3 target{rng.uniform(), rng.uniform(), 1};
      const Vec3 d = target - from;
      const double r = length(d);
      const std::optional<SurfaceHit> lamp = shading.intersect(from, d / r, 1e-9);
      ASSERT_TRUE(lamp && lamp->front);
      const double w = shading.lightPdf(*lamp, from) * (d.z / r) / (r * r);
      sum += w, sumSq += w * w;
    }
    const double mean = sum / n, se = std::sqrt((sumSq / n - mean * mean) / (n - 1));
    EXPECT_NEAR(mean, 1, 4 * se + 1e-12) << int(mode);
  }
}

}  // namespace
}  // namespace radkit
