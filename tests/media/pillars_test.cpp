// Light pillars (media/pillars.h, docs/pillars.md): tilt density and sampler, Schlick, the
// reflection geometry, the exact minimum-tilt point against brute force (and the original
// document's defect), the plate cross-section by brute force, and the closed form against the
// Monte Carlo reference.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>
#include <vector>

#include "media/pillars.h"
#include "tests/common/statistics.h"
#include "tests/common/test_util.h"
#include "util/sampling.h"

namespace radkit::media {
namespace {

constexpr double kPillarDeg = kPi / 180;

double pillarSimpson(const std::function<double(double)>& f, double a, double b, int n) {
  double s = f(a) + f(b);
  const double h = (b - a) / n;
  for (int i = 1; i < n; ++i) s += (i % 2 ? 4 : 2) * f(a + i * h);
  return s * h / 3;
}

TEST(Pillars, TiltDensityIntegratesToErfThreeOverRootTwo) {
  const PillarTilt tilt;
  const double integral =
      pillarSimpson([&](double b) { return pillarTiltDensity(b, tilt); }, 0, tilt.cut, 2000);
  // erf(3/√2) = 0.9973002039 (Abramowitz & Stegun 7.1; the 3σ rule; scipy.special.erf).
  EXPECT_NEAR(integral, 0.9973002039367398, 1e-10);
  EXPECT_NEAR(pillarTiltMass(tilt), 0.9973002039367398, 1e-14);
  // Defect (c): the exact Gaussian at the cut, √(2/π)/σ·e^{−4.5} = 0.30471 rad⁻¹.
  EXPECT_NEAR(pillarTiltDensity(tilt.cut, tilt), 0.30471145133496497, 1e-12);
  EXPECT_EQ(pillarTiltDensity(tilt.cut * 1.0001, tilt), 0.0);
  // D per steradian: ∫ D dω over the upper hemisphere is the same mass.
  const double overSphere = pillarSimpson(
      [&](double b) {
        return 2 * kPi * std::sin(b) * pillarNormalDensity({std::sin(b), 0, std::cos(b)}, tilt);
      },
      1e-9, tilt.cut, 4000);
  EXPECT_NEAR(overSphere, 0.9973002039367398, 1e-6);
}

TEST(Pillars, TiltSamplerInvertsTheCdfAndPassesChiSquare) {
  const PillarTilt tilt;
  const PillarTiltSampler sampler(tilt);
  const double mass = pillarTiltMass(tilt), scale = tilt.sigma * std::sqrt(2.0);
  for (double u : {0.0, 1e-9, 0.1, 0.5, 0.77, 0.999, 0.9999999})
    EXPECT_NEAR(std::erf(sampler.sample(u) / scale) / mass, u, 1e-10) << u;
  const int bins = 25, n = 200000;
  std::vector<double> observed(bins, 0), expected(bins, n / double(bins));
  Rng rng(5, 0, 0);
  for (int i = 0; i < n; ++i) {
    const double b = sampler.sample(rng.uniform());
    ASSERT_GE(b, 0);
    ASSERT_LE(b, tilt.cut);
    // Equal-probability bins from the exact CDF erf(β/(σ√2))/mass.
    observed[std::min(bins - 1, int(std::erf(b / scale) / mass * bins))] += 1;
  }
  EXPECT_GT(test::chiSquarePValue(observed, expected, "pillars_tilt", 1e-3), 1e-3);
}

TEST(Pillars, SchlickEndsAndIceRho0) {
  // Fresnel at normal incidence ((n − 1)/(n + 1))² (Hecht, Optics, §4.6); ice n = 1.31
  // (Warren & Brandt 2008, visible).
  const double rho0 = pillarRho0(1.31);
  EXPECT_NEAR(rho0, 0.0180094076, 1e-10);
  EXPECT_NEAR(PillarScene{}.rho0, rho0, 1e-15);
  EXPECT_DOUBLE_EQ(pillarSchlick(1, rho0), rho0);
  EXPECT_DOUBLE_EQ(pillarSchlick(0, rho0), 1.0);
}

TEST(Pillars, SchlickAntiderivativeMatchesQuadrature) {
  const double rho0 = pillarRho0(1.31);
  const auto R = [&](double th) { return pillarSchlick(std::cos(th), rho0); };
  // Defect (b): ∫₀^{π/2} R dθ = 0.195248 (scipy.integrate.quad), θ coefficient 7.751.
  const double exact =
      pillarSchlickAntiderivative(kPi / 2, rho0) - pillarSchlickAntiderivative(0, rho0);
  EXPECT_NEAR(exact, 0.19524820602994675, 1e-12);
  EXPECT_NEAR(exact, pillarSimpson(R, 0, kPi / 2, 2000), 1e-12);
  EXPECT_NEAR(rho0 + (1 - rho0) * 63 / 8, 7.751185, 1e-6);
  // ∫₀^{π/2} (1 − cos θ)⁵ dθ = 63π/16 − 12.2 = 0.1700211.
  EXPECT_NEAR(pillarSchlickAntiderivative(kPi / 2, 0) - 1, 63 * kPi / 16 - 12.2 - 1, 1e-12);
  for (double a : {0.1, 0.7, 1.2, 1.5})
    EXPECT_NEAR(pillarSchlickAntiderivative(a, rho0) - pillarSchlickAntiderivative(0, rho0),
                pillarSimpson(R, 0, a, 2000), 1e-12);
}

TEST(Pillars, HalfVectorObeysTheLawOfReflection) {
  Rng rng(3, 0, 0);
  for (int i = 0; i < 1000; ++i) {
    const Vec3 eye{0, 0, 1.7}, lamp{rng.uniform() * 400 - 200, rng.uniform() * 400 + 50, 6};
    const Vec3 p{rng.uniform() * 300 - 150, rng.uniform() * 300, rng.uniform() * 200 + 1};
    const Vec3 wi = normalize(lamp - p), wo = normalize(eye - p);
    const Vec3 h = pillarHalfVector(wi, wo);
    EXPECT_NEAR(length(pillarReflect(wi, h) - wo), 0, 1e-12);     // reflected
    EXPECT_NEAR(dot(cross(wi, wo), h), 0, 1e-12);                 // coplanar
    EXPECT_NEAR(angleBetween(wi, h), angleBetween(wo, h), 1e-7);  // equal angles
    EXPECT_NEAR(pillarRequiredTilt(wi, wo), std::acos(std::fabs(h.z)), 1e-7);
  }
}

/// Brute force: 40000 samples of the tilt along t, then golden section on the best bracket.
double pillarBruteMinimumTilt(const Vec3& eye, const Vec3& d, const Vec3& lamp, double t0,
                              double t1) {
  const int n = 40000;
  int best = 0;
  double bestTilt = 10;
  for (int i = 0; i <= n; ++i) {
    const double b = pillarTiltAlongRay(eye, d, lamp, t0 + (t1 - t0) * i / n);
    if (b < bestTilt) bestTilt = b, best = i;
  }
  double a = t0 + (t1 - t0) * std::max(0, best - 1) / n,
         c = t0 + (t1 - t0) * std::min(n, best + 1) / n;
  const double g = (std::sqrt(5.0) - 1) / 2;
  for (int it = 0; it < 200 && c - a > 1e-13 * (1 + c); ++it) {
    const double x1 = c - g * (c - a), x2 = a + g * (c - a);
    if (pillarTiltAlongRay(eye, d, lamp, x1) < pillarTiltAlongRay(eye, d, lamp, x2))
      c = x2;
    else
      a = x1;
  }
  return std::min(bestTilt, pillarTiltAlongRay(eye, d, lamp, 0.5 * (a + c)));
}

TEST(Pillars, MinimumTiltMatchesBruteForceOnAndOffThePlane) {
  Rng rng(9, 0, 0);
  for (int i = 0; i < 150; ++i) {
    const Vec3 eye{0, 0, 1.7};
    const double dist = 100 + 1400 * rng.uniform(), az = (rng.uniform() - 0.5) * 0.6;
    const Vec3 lamp{dist * std::sin(az), dist * std::cos(az), 5 + 5 * rng.uniform()};
    // A third of the rays in the eye–lamp vertical plane, the rest up to ±5° off it.
    const double off = i % 3 == 0 ? 0 : (rng.uniform() - 0.5) * 10 * kPillarDeg;
    const double el = (1 + 40 * rng.uniform()) * kPillarDeg;
    const Vec3 d{std::cos(el) * std::sin(az + off), std::cos(el) * std::cos(az + off),
                 std::sin(el)};
    const double t1 = 300 / d.z;
    const PillarRayPoint m = pillarMinimumTilt(eye, d, lamp, 0, t1);
    EXPECT_NEAR(m.tilt, pillarBruteMinimumTilt(eye, d, lamp, 0, t1), 1e-6) << i;
    EXPECT_NEAR(m.tilt, pillarTiltAlongRay(eye, d, lamp, m.t), 1e-9) << i;
  }
}

TEST(Pillars, FoundingClosedFormHalvesTheTiltOffThePlane) {
  // Eye 1.7 m above the ground at the origin, lamp 100 m north... here along +x, 5 m high;
  // view ray at elevation 20°, 1° in azimuth off the lamp.
  const Vec3 eye{0, 0, 1.7}, lamp{100, 0, 5};
  const double el = 20 * kPillarDeg, az = 1 * kPillarDeg;
  const Vec3 d{std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)};
  const PillarRayPoint old = pillarFoundingMinimumTilt(eye, d, lamp);
  const PillarRayPoint exact = pillarMinimumTilt(eye, d, lamp, 0, 1000);
  EXPECT_NEAR(old.tilt / kPillarDeg, 1.51, 0.005);
  EXPECT_NEAR(exact.tilt / kPillarDeg, 3.02, 0.005);
  EXPECT_NEAR(pillarBruteMinimumTilt(eye, d, lamp, 0, 1000), exact.tilt, 1e-6);
  EXPECT_NEAR(old.tilt / exact.tilt, 0.5, 0.01);
  // In the vertical plane the original point is exact: tilt 0 at the same t.
  const Vec3 d0{std::cos(el), 0, std::sin(el)};
  const PillarRayPoint old0 = pillarFoundingMinimumTilt(eye, d0, lamp);
  const PillarRayPoint exact0 = pillarMinimumTilt(eye, d0, lamp, 0, 1000);
  EXPECT_NEAR(old0.tilt, 0, 1e-9);
  EXPECT_NEAR(exact0.tilt, 0, 1e-9);
  EXPECT_NEAR(old0.t, exact0.t, 1e-6);
}

TEST(Pillars, TiltSegmentsEndAtTheCut) {
  Rng rng(4, 0, 0);
  const double cut = 5 * kPillarDeg;
  int segments = 0;
  for (int i = 0; i < 300; ++i) {
    const Vec3 eye{0, 0, 1.7}, lamp{rng.uniform() * 200 - 100, 200 + 800 * rng.uniform(), 7};
    const double az = std::atan2(lamp.x, lamp.y) + (rng.uniform() - 0.5) * 4 * kPillarDeg;
    const double el = (2 + 30 * rng.uniform()) * kPillarDeg;
    const Vec3 d{std::cos(el) * std::sin(az), std::cos(el) * std::cos(az), std::sin(el)};
    const double t1 = 300 / d.z;
    const std::vector<PillarRayPoint> s = pillarTiltSegments(eye, d, lamp, 0, t1, cut);
    for (std::size_t k = 0; k + 1 < s.size(); k += 2) {
      ++segments;
      for (const PillarRayPoint& p : {s[k], s[k + 1]}) {
        EXPECT_NEAR(pillarTiltAlongRay(eye, d, lamp, p.t), p.tilt, 1e-9);
        if (p.t > 0 && p.t < t1) {
          EXPECT_NEAR(p.tilt, cut, 1e-9);
        }
      }
      EXPECT_LE(pillarTiltAlongRay(eye, d, lamp, 0.5 * (s[k].t + s[k + 1].t)), cut);
    }
    // Dense check: inside a segment ⇔ tilt ≤ cut.
    for (int j = 0; j < 400; ++j) {
      const double t = t1 * (j + 0.5) / 400;
      bool inside = false;
      for (std::size_t k = 0; k + 1 < s.size(); k += 2) inside |= t >= s[k].t && t <= s[k + 1].t;
      EXPECT_EQ(inside, pillarTiltAlongRay(eye, d, lamp, t) <= cut) << i << " " << t;
    }
  }
  EXPECT_GT(segments, 50);
}

TEST(Pillars, ShadowIntervalMatchesRayBoxTests) {
  Rng rng(6, 0, 0);
  for (int i = 0; i < 200; ++i) {
    const Vec3 eye{0, 0, 1.7}, lamp{rng.uniform() * 100 - 50, 300, 4 + 6 * rng.uniform()};
    const Vec3 lo{rng.uniform() * 80 - 40, 80 + 150 * rng.uniform(), 0};
    const PillarBox box{
        lo, lo + Vec3{5 + 30 * rng.uniform(), 5 + 30 * rng.uniform(), 5 + 30 * rng.uniform()}};
    const Vec3 d = normalize({rng.uniform() - 0.5, 1, 0.05 + 0.4 * rng.uniform()});
    const double tMax = 400;
    double t0 = 0, t1 = -1;
    const bool any = pillarShadowInterval(lamp, eye, d, tMax, box, t0, t1);
    for (int j = 0; j < 500; ++j) {
      const double t = tMax * (j + 0.5) / 500;
      const Vec3 p = eye + d * t, w = lamp - p;
      const bool blocked = pillarRayBox(p, normalize(w), box, 0, length(w)) < 1e300;
      const bool predicted = any && t >= t0 && t <= t1;
      if (std::fabs(t - t0) > 1e-6 && std::fabs(t - t1) > 1e-6) {
        EXPECT_EQ(blocked, predicted) << i << " t=" << t << " [" << t0 << ", " << t1 << "]";
      }
    }
  }
}

PillarScene pillarTestScene() {
  PillarScene s;
  s.lamps.push_back({{-20, 300, 6}, {1, 0.6, 0.3}, 0.5});
  s.lamps.push_back({{15, 350, 8}, {0.8, 0.9, 1}, 0.5});
  s.boxes.push_back({{-40, 120, 0}, {-5, 135, 12}});
  s.plateDensity = 1e-3;
  s.extinction = 3e-4;
  s.slabTop = 45;  // a low slab: the view rays end near the pillars, few samples are wasted
  return s;
}

TEST(Pillars, ClosedFormMatchesBruteForceQuadratureInT) {
  const PillarScene s = pillarTestScene();
  PillarCamera c;
  c.width = 24, c.height = 16, c.fovDeg = 16, c.elevationDeg = 8, c.azimuthDeg = -0.3;
  int checked = 0;
  for (int y = 0; y < 16 && checked < 12; y += 3)
    for (int x = 0; x < 24 && checked < 12; ++x) {
      const Vec3 d = c.direction(x, y);
      double minTilt = 10;
      for (const PillarLamp& l : s.lamps)
        minTilt = std::min(minTilt, pillarMinimumTilt(c.eye, d, l.position, 0, 1e4).tilt);
      if (minTilt < 0.5 * kPillarDeg) continue;  // the 1/sin β peak needs the v substitution
      const Vec3 a = pillarRadianceClosed(s, c.eye, d);
      if (a.x == 0) continue;
      const Vec3 fine = pillarRadianceClosed(s, c.eye, d, {16, 0.125});
      const Vec3 brute = pillarRadianceBruteForce(s, c.eye, d, 200000);
      EXPECT_NEAR(a.x, fine.x, 1e-9 * fine.x);
      // Simpson across the jump of D at the cut is first order: 1e-4 relative.
      EXPECT_NEAR(a.x, brute.x, 1e-4 * brute.x) << x << "," << y;
      ++checked;
    }
  EXPECT_GT(checked, 10);
}

TEST(Pillars, PlateCrossSectionByBruteForce) {
  // Plates of unit area with normals from D, lit from ωi; histogram the reflected ωo weighted
  // by projected area × reflectance and compare with ∫_bin A·D(h)·R/4 dωo per bin.
  const PillarTilt tilt;
  const PillarTiltSampler sampler(tilt);
  const double rho0 = pillarRho0(1.31), mass = pillarTiltMass(tilt), ei = 25 * kPillarDeg;
  const Vec3 wi{std::cos(ei), 0, -std::sin(ei)};
  // ωo = (−cos e cos a, cos e sin a, sin e); the specular direction (e, a) = (−25°, 0) is a
  // bin corner.
  const int ne = 10, na = 8;
  const double e0 = -35 * kPillarDeg, de = 2 * kPillarDeg, a0 = -4 * kPillarDeg,
               da = 1 * kPillarDeg;
  const auto binOf = [&](const Vec3& wo, int& ie, int& ia) {
    const double e = std::asin(wo.z), a = std::atan2(wo.y, -wo.x);
    ie = int(std::floor((e - e0) / de)), ia = int(std::floor((a - a0) / da));
    return ie >= 0 && ie < ne && ia >= 0 && ia < na;
  };
  const int n = 1000000;
  std::vector<double> sum(ne * na, 0), sum2(ne * na, 0), count(ne * na, 0);
  Rng rng(8, 0, 0);
  for (int i = 0; i < n; ++i) {
    const double b = sampler.sample(rng.uniform()), phi = 2 * kPi * rng.uniform();
    const Vec3 m{std::sin(b) * std::cos(phi), std::sin(b) * std::sin(phi), std::cos(b)};
    const Vec3 wo = pillarReflect(wi, m);
    int ie, ia;
    if (!binOf(wo, ie, ia)) continue;
    const double c = std::fabs(dot(wi, m)), w = mass * c * pillarSchlick(c, rho0);
    sum[ie * na + ia] += w;
    sum2[ie * na + ia] += w * w;
    count[ie * na + ia] += 1;
  }
  // 16×16 Gauss-Legendre per bin (nodes from the 1-D rule on [−1, 1]).
  const double gx[8] = {0.0950125098376374, 0.2816035507792589, 0.4580167776572274,
                        0.6178762444026438, 0.7554044083550030, 0.8656312023878318,
                        0.9445750230732326, 0.9894009349916499};
  const double gw[8] = {0.1894506104550685, 0.1826034150449236, 0.1691565193950025,
                        0.1495959888165767, 0.1246289712555339, 0.0951585116824928,
                        0.0622535239386479, 0.0271524594117541};
  std::vector<double> x16, w16;
  for (int k = 0; k < 8; ++k) x16.push_back(-gx[k]), w16.push_back(gw[k]);
  for (int k = 0; k < 8; ++k) x16.push_back(gx[k]), w16.push_back(gw[k]);
  std::vector<double> expectedCounts(ne * na, 0);
  double chi = 0;
  int used = 0;
  for (int ie = 0; ie < ne; ++ie)
    for (int ia = 0; ia < na; ++ia) {
      double sigmaBin = 0, pdfBin = 0;
      for (int p = 0; p < 16; ++p)
        for (int q = 0; q < 16; ++q) {
          const double e = e0 + de * (ie + 0.5 + 0.5 * x16[p]);
          const double a = a0 + da * (ia + 0.5 + 0.5 * x16[q]);
          const Vec3 wo{-std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e)};
          const double dw = 0.25 * w16[p] * w16[q] * de * da * std::cos(e);
          const Vec3 h = pillarHalfVector(wi, wo);
          sigmaBin += pillarCrossSection(wi, wo, 1, tilt, rho0) * dw;
          // Unweighted: pdf(ωo) = D(h)/(mass · 4|ωo·h|).
          pdfBin += pillarNormalDensity(h, tilt) / (mass * 4 * std::fabs(dot(wo, h))) * dw;
        }
      const int k = ie * na + ia;
      expectedCounts[k] = pdfBin * n;
      if (count[k] < 100) continue;
      const double mean = sum[k] / n, se = std::sqrt((sum2[k] / n - mean * mean) / (n - 1));
      const double z = (mean - sigmaBin) / se;
      EXPECT_LT(std::fabs(z), 4.5) << ie << "," << ia << " " << mean << " vs " << sigmaBin;
      chi += z * z;
      ++used;
    }
  ASSERT_GT(used, 30);
  EXPECT_NEAR(chi / used, 1, 5 * std::sqrt(2.0 / used));
  EXPECT_GT(test::chiSquarePValue(count, expectedCounts, "pillars_cross_section", 1e-3), 1e-3);
}

/// Per-pixel z = (Y_mc − Y_model)/SE over pixels with ≥ 30 hits, and z of each column's sum
/// (SE √ΣSE²) over columns with ≥ 50 hits, which covers the faint wings too.
struct PillarZ {
  double meanZ2 = 0, maxAbsZ = 0, maxAbsColumnZ = 0;
  int pixels = 0, columns = 0;
};

PillarZ pillarZScores(const PillarScene& s, const PillarCamera& c, const PillarImage& model,
                      const PillarImage& mc) {
  PillarZ r;
  for (int x = 0; x < c.width; ++x) {
    double sumM = 0, sumC = 0, var = 0;
    long long hits = 0;
    for (int y = 0; y < c.height; ++y) {
      const std::size_t i = std::size_t(y) * c.width + x;
      const Vec3 d = c.direction(x, y);
      double minTilt = 10;
      for (const PillarLamp& l : s.lamps)
        minTilt = std::min(
            minTilt,
            pillarMinimumTilt(c.eye, d, l.position, 0, pillarViewRayEnd(s, c.eye, d)).tilt);
      // The point-light limit needs β_min ≫ the lamps' angular radius (0.1°): D ∝ 1/sin β.
      if (minTilt < 1 * kPillarDeg) continue;
      const double ym = luminance(mc.radiance[i]), yc = luminance(model.radiance[i]);
      sumM += ym, sumC += yc, var += mc.standardError[i] * mc.standardError[i];
      hits += mc.hits[i];
      if (mc.hits[i] < 30) continue;
      const double z = (ym - yc) / mc.standardError[i];
      r.meanZ2 += z * z;
      r.maxAbsZ = std::max(r.maxAbsZ, std::fabs(z));
      ++r.pixels;
    }
    if (hits < 50) continue;
    r.maxAbsColumnZ = std::max(r.maxAbsColumnZ, std::fabs(sumM - sumC) / std::sqrt(var));
    ++r.columns;
  }
  if (r.pixels) r.meanZ2 /= r.pixels;
  return r;
}

TEST(Pillars, MonteCarloAgreesWithTheClosedFormAndCatchesWrongModels) {
  // A broader tilt (σ = 4°, cut 3σ) widens the pillars to several pixels; the estimator does
  // not depend on σ. Lamps of 0.5 m at 300–350 m: 0.1° angular radius.
  PillarScene s = pillarTestScene();
  s.tilt.sigma = 4 * kPillarDeg;
  s.tilt.cut = 12 * kPillarDeg;
  PillarCamera c;
  c.width = 24, c.height = 16, c.fovDeg = 16, c.elevationDeg = 8, c.azimuthDeg = -0.3;
  const PillarImage closed = pillarRenderClosed(s, c);
  const PillarImage mc = pillarRenderMonteCarlo(s, c, 100000, 11);
  const PillarZ z = pillarZScores(s, c, closed, mc);
  ASSERT_GE(z.pixels, 20);
  ASSERT_GE(z.columns, 6);
  EXPECT_LT(z.maxAbsZ, 4.0);
  EXPECT_LT(z.maxAbsColumnZ, 4.0);
  EXPECT_NEAR(z.meanZ2, 1, 4 * std::sqrt(2.0 / z.pixels));
  // No signal where the closed form has none (outside the ≤ cut segments).
  for (std::size_t i = 0; i < closed.radiance.size(); ++i) {
    if (closed.radiance[i].x == 0) {
      EXPECT_EQ(mc.hits[i], 0) << i;
    }
  }
  // The same comparison must fail for a missing 1/4 and for R ≡ ρ0 (Schlick's angular term
  // dropped); ρ0 = 0.04 (n = 1.5) is printed: at these grazing angles R barely depends on ρ0.
  PillarImage times4 = closed;
  for (Vec3& v : times4.radiance) v *= 4;
  const PillarZ z4 = pillarZScores(s, c, times4, mc);
  EXPECT_GT(z4.meanZ2, 50);
  PillarScene flat = s;
  flat.rho0 = 1;  // R ≡ 1 …
  PillarImage noFresnel = pillarRenderClosed(flat, c);
  for (Vec3& v : noFresnel.radiance) v *= s.rho0;  // … scaled to R ≡ ρ0
  const PillarZ zr = pillarZScores(s, c, noFresnel, mc);
  EXPECT_GT(zr.meanZ2, 10);
  PillarScene glass = s;
  glass.rho0 = pillarRho0(1.5);
  const PillarZ zg = pillarZScores(s, c, pillarRenderClosed(glass, c), mc);
  std::printf(
      "MC vs closed: %d px mean z² %.3f max |z| %.2f, %d columns max |z| %.2f; "
      "×4: mean z² %.0f; R≡ρ0: %.0f; ρ0 = 0.04: %.2f (column max |z| %.2f); %.2f s\n",
      z.pixels, z.meanZ2, z.maxAbsZ, z.columns, z.maxAbsColumnZ, z4.meanZ2, zr.meanZ2, zg.meanZ2,
      zg.maxAbsColumnZ, mc.seconds);
}

TEST(Pillars, NightSceneIsValidAndRendersDeterministically) {
  const PillarScene s = pillarNightScene();
  EXPECT_NO_THROW(pillarValidate(s));
  EXPECT_EQ(s.lamps.size(), 5u);
  PillarCamera c;
  c.width = 16, c.height = 10;
  const PillarImage a = pillarRenderMonteCarlo(s, c, 200, 3),
                    b = pillarRenderMonteCarlo(s, c, 200, 3);
  EXPECT_EQ(a.radiance, b.radiance);
  PillarScene bad = s;
  bad.boxes.push_back({s.lamps[0].position - Vec3{1, 1, 1}, s.lamps[0].position + Vec3{1, 1, 1}});
  EXPECT_THROW(pillarValidate(bad), std::invalid_argument);
}

}  // namespace
}  // namespace radkit::media

namespace radkit::media {
namespace {

TEST(PillarsCli, WritesBothImagesAndRefusesBadSettingsLeavingNothing) {
  test::TempDir dir;
  const std::string small = "pillars --size 16 10 --samples 40 --seed 2 --out ";
  test::RunResult r = test::runRadkit(small + dir.path("a"), 600);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (const char* f : {"pillars-closed.pfm", "pillars-closed.png", "pillars-mc.pfm",
                        "pillars-mc.png", "pillars-difference.png", "report.json"})
    EXPECT_TRUE(std::filesystem::exists(dir.path("a") + "/" + f)) << f;
  // The same seed gives the same Monte Carlo image.
  r = test::runRadkit(small + dir.path("b"), 600);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  std::ifstream fa(dir.path("a") + "/pillars-mc.pfm", std::ios::binary),
      fb(dir.path("b") + "/pillars-mc.pfm", std::ios::binary);
  const std::string ia((std::istreambuf_iterator<char>(fa)), {}),
      ib((std::istreambuf_iterator<char>(fb)), {});
  EXPECT_FALSE(ia.empty());
  EXPECT_EQ(ia, ib);
  // Refusals: a lamp larger than the street allows (the scene's validation, with its fix),
  // and options outside their ranges or not numbers. None leaves an output folder.
  const struct {
    std::string args, says;
  } bad[] = {
      {"--lamp-radius 6", "Fix:"},
      {"--slab-top 5", "--slab-top"},
      {"--sigma-tilt nan", "--sigma-tilt"},
      {"--cut 0", "--cut"},
      {"--size 4 4", "--size"},
      {"--plate-density -1", "--plate-density"},
  };
  int k = 0;
  for (const auto& b : bad) {
    const std::string out = dir.path("bad" + std::to_string(k++));
    r = test::runRadkit("pillars --size 16 10 --samples 4 " + b.args + " --out " + out, 600);
    EXPECT_NE(r.exitCode, 0) << b.args;
    EXPECT_NE(r.output.find(b.says), std::string::npos) << b.args << ": " << r.output;
    EXPECT_FALSE(std::filesystem::exists(out)) << b.args;
  }
}

}  // namespace
}  // namespace radkit::media
