// The atmosphere model (atmosphere/) against outside oracles: the phase functions' normalisation
// and mean cosine, closed-form optical depths of exponential atmospheres, the λ⁻⁴ law, the sky's
// colours as observed (a blue zenith, a reddening sunset), and a brute-force volumetric path
// tracer that must agree with single scattering where single scattering is exact.
#include "atmosphere/atmosphere.h"

#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <string>
#include <vector>

#include "atmosphere/reference.h"
#include "atmosphere/shell.h"
#include "atmosphere/sky_image.h"
#include "phase/closed_form.h"
#include "tests/common/statistics.h"
#include "util/frame.h"
#include "util/sampling.h"

namespace radkit::atmosphere {
namespace {

/// ∫ over the sphere of f(cos θ)·cos^k θ: Simpson's rule in cos θ, times 2π.
template <class F>
double sphereMoment(const F& f, int k) {
  const int n = 200000;  // even
  double sum = 0;
  for (int i = 0; i <= n; ++i) {
    const double mu = -1 + 2.0 * i / n;
    const double w = (i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2);
    sum += w * f(mu) * std::pow(mu, k);
  }
  return 2 * kPi * sum * (2.0 / n) / 3;
}

TEST(Phase, IntegratesToOneOverTheSphere) {
  EXPECT_NEAR(sphereMoment([](double) { return isotropicPhase(); }, 0), 1, 1e-12);
  EXPECT_NEAR(sphereMoment(rayleighPhase, 0), 1, 1e-9);
  for (double g : {0.0, 0.5, 0.76, 0.9})
    EXPECT_NEAR(sphereMoment([g](double mu) { return cornetteShanksPhase(mu, g); }, 0), 1, 1e-6)
        << "Cornette-Shanks g = " << g;
  for (double g : {-0.6, 0.0, 0.3, 0.76, 0.9}) {
    const auto hg = [g](double mu) { return henyeyGreensteinPhase(mu, g); };
    EXPECT_NEAR(sphereMoment(hg, 0), 1, 1e-6) << "HG g = " << g;
    EXPECT_NEAR(sphereMoment(hg, 1), g, 1e-6) << "HG's mean cosine is g, g = " << g;
  }
  // Rayleigh is symmetric: no net forward scattering.
  EXPECT_NEAR(sphereMoment(rayleighPhase, 1), 0, 1e-12);
}

TEST(Phase, CornetteShanksWithoutAsymmetryIsRayleigh) {
  for (double mu = -1; mu <= 1; mu += 0.125)
    EXPECT_DOUBLE_EQ(cornetteShanksPhase(mu, 0), rayleighPhase(mu)) << mu;
}

TEST(Phase, StatisticalSamplingFollowsTheDensity) {
  // Directions sampled about an oblique axis, binned in cos θ (40) and in azimuth about the
  // axis (8), against the density integrated over each cell. Samples are exact (inverse CDF
  // or rejection), so χ² holds at any sample count.
  struct Case {
    std::string name;
    std::function<double(double)> density;
    std::function<double(Rng&)> sample;
  };
  const std::vector<Case> cases = {
      {"rayleigh", rayleighPhase, [](Rng& r) { return sampleRayleighCosine(r.uniform()); }},
      {"hg-0.5", [](double mu) { return henyeyGreensteinPhase(mu, 0.5); },
       [](Rng& r) { return sampleHenyeyGreensteinCosine(r.uniform(), 0.5); }},
      {"hg-minus-0.3", [](double mu) { return henyeyGreensteinPhase(mu, -0.3); },
       [](Rng& r) { return sampleHenyeyGreensteinCosine(r.uniform(), -0.3); }},
      {"cornette-shanks-0.76", [](double mu) { return cornetteShanksPhase(mu, 0.76); },
       [](Rng& r) { return sampleCornetteShanksCosine(r, 0.76); }},
      {"cornette-shanks-0.9", [](double mu) { return cornetteShanksPhase(mu, 0.9); },
       [](Rng& r) { return sampleCornetteShanksCosine(r, 0.9); }}};
  const double alpha = test::sidakAlpha(0.01, int(cases.size()));
  const Vec3 axis = normalize(Vec3{0.3, -0.5, 0.8});
  const Frame frame(axis);
  const int nMu = 40, nPhi = 8, n = 200000;
  for (const Case& c : cases) {
    std::vector<double> observed(nMu * nPhi, 0), expected(nMu * nPhi, 0);
    Rng rng(11, 0, 0);
    for (int i = 0; i < n; ++i) {
      const double mu = c.sample(rng);
      const Vec3 local = frame.toLocal(directionAround(axis, mu, rng.uniform()));
      double phi = std::atan2(local.y, local.x);
      if (phi < 0) phi += 2 * kPi;
      const int a = std::min(nMu - 1, int((local.z + 1) / 2 * nMu));
      const int b = std::min(nPhi - 1, int(phi / (2 * kPi) * nPhi));
      observed[a * nPhi + b] += 1;
    }
    for (int a = 0; a < nMu; ++a) {
      double cell = 0;  // Simpson in cos θ over the bin
      const int sub = 200;
      for (int k = 0; k <= sub; ++k) {
        const double mu = -1 + 2.0 * (a + double(k) / sub) / nMu;
        cell += (k == 0 || k == sub ? 1 : (k % 2 ? 4 : 2)) * c.density(mu);
      }
      cell *= (2.0 / nMu / sub) / 3 * (2 * kPi / nPhi);
      for (int b = 0; b < nPhi; ++b) expected[a * nPhi + b] = cell * n;
    }
    EXPECT_GT(test::chiSquarePValue(observed, expected, "phase-" + c.name + "-chi2.csv", alpha),
              alpha)
        << c.name;
  }
}

/// β H (e^{−h0/H} − e^{−h1/H}): the optical depth of an exponential layer between two
/// altitudes along the vertical (the curvature does not matter on a radial line).
double verticalDepth(double beta, double scaleHeight, double h0, double h1) {
  return beta * scaleHeight * (std::exp(-h0 / scaleHeight) - std::exp(-h1 / scaleHeight));
}

TEST(OpticalDepth, VerticalPathsMatchTheClosedForm) {
  for (double h0 : {0.0, 1500.0, 20000.0}) {
    AtmosphereParameters rayleighOnly;
    rayleighOnly.mieScattering = rayleighOnly.mieExtinction = 0;
    AtmosphereParameters mieOnly;
    mieOnly.rayleighScattering = {0, 0, 0};
    for (const AtmosphereParameters& p : {rayleighOnly, mieOnly}) {
      const Atmosphere air(p);
      const double top = p.topRadius - p.groundRadius;
      const Vec3 tau = air.opticalDepth(air.pointAtAltitude(h0), air.pointAtAltitude(top));
      for (int c = 0; c < 3; ++c) {
        const double exact =
            verticalDepth(p.rayleighScattering[c], p.rayleighScaleHeight, h0, top) +
            verticalDepth(p.mieExtinction, p.mieScaleHeight, h0, top);
        EXPECT_NEAR(tau[c], exact, 1e-6 * exact) << "h0 " << h0 << " channel " << c;
      }
      // Down the same line gives the same depth, and the transmittance to the top is e^{−τ}.
      const Vec3 down = air.opticalDepth(air.pointAtAltitude(top), air.pointAtAltitude(h0));
      const Vec3 t = air.transmittanceToTop(air.pointAtAltitude(h0), {0, 0, 1});
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(down[c], tau[c], 1e-12 * tau[c]);
        EXPECT_NEAR(t[c], std::exp(-tau[c]), 1e-12);
      }
    }
  }
}

TEST(OpticalDepth, ScalesWithTheRelativeDensity) {
  AtmosphereParameters p;
  p.relativeDensity = 1.7;
  const Atmosphere thick(p), standard;
  const Vec3 a = standard.pointAtAltitude(100), b = a + normalize(Vec3{1, 0, 0.2}) * 300e3;
  const Vec3 t1 = standard.opticalDepth(a, b), t17 = thick.opticalDepth(a, b);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(t17[c], 1.7 * t1[c], 1e-12 * t17[c]);
}

TEST(Rayleigh, CoefficientFollowsTheInverseFourthPowerAndTheDefaults) {
  // Air at 15 °C and 1013.25 hPa: n − 1 = 3.0e-4 in the visible, N = 2.545e25 m⁻³ (the
  // standard atmosphere, as in Bucholtz 1995 and Preetham et al. 1999).
  const double n = 1.0003, N = 2.545e25;
  const double b[3] = {rayleighCoefficient(kWavelengths[0], n, N),
                       rayleighCoefficient(kWavelengths[1], n, N),
                       rayleighCoefficient(kWavelengths[2], n, N)};
  EXPECT_NEAR(b[2] / b[0], std::pow(kWavelengths[0] / kWavelengths[2], 4), 1e-12);
  EXPECT_NEAR(b[1] / b[0], std::pow(kWavelengths[0] / kWavelengths[1], 4), 1e-12);
  // Bruneton and Neyret's defaults (5.8, 13.5, 33.1)·1e-6/m: within 1 % (0.1, 0.5, 0.04 %).
  const Vec3 defaults = AtmosphereParameters{}.rayleighScattering;
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(b[c], defaults[c], 0.01 * defaults[c]) << c;
}

TEST(Rayleigh, CoefficientGrowsLinearlyWithTheDensity) {
  // More air scatters more: n − 1 ∝ density (Lorentz-Lorenz) beats the 1/N of the formula.
  const double lambda = 550e-9, n = 1.0003, N = 2.545e25;
  const double b1 = rayleighCoefficient(lambda, n, N, 1);
  for (double rho : {0.01, 0.25, 0.5, 2.0, 4.0})
    EXPECT_NEAR(rayleighCoefficient(lambda, n, N, rho), rho * b1, 2e-3 * rho * b1) << rho;
  EXPECT_EQ(rayleighCoefficient(lambda, n, N, 0), 0);
}

TEST(Sky, ZenithRadianceGrowsWithTheDensity) {
  // Optically thin (red and green: τ < 0.3 up to twice the standard density): more air, more
  // light scattered toward the observer.
  const Vec3 sun = sunDirection(45, 180);
  Vec3 previous{0, 0, 0};
  for (double rho : {0.5, 1.0, 1.5, 2.0}) {
    AtmosphereParameters p;
    p.relativeDensity = rho;
    const Atmosphere air(p);
    const Vec3 l = air.skyRadiance(air.pointAtAltitude(1), {0, 0, 1}, sun);
    for (int c = 0; c < 3; ++c)
      EXPECT_GT(l[c], previous[c]) << "density " << rho << " channel " << c;
    previous = l;
  }
}

TEST(Transmittance, TheGroundBlocks) {
  const Atmosphere air;
  const Vec3 p = air.pointAtAltitude(1000);
  EXPECT_EQ(air.transmittanceToTop(p, normalize(Vec3{0.2, 0.1, -1})), Vec3(0, 0, 0));
  EXPECT_EQ(air.transmittanceToTop(air.pointAtAltitude(0), normalize(Vec3{1, 0, -1e-3})),
            Vec3(0, 0, 0));
  const Vec3 ground = air.pointAtAltitude(0);
  for (double elevation : {-10.0, -1.0, -0.1})
    EXPECT_EQ(air.sunIrradiance(ground, sunDirection(elevation, 90)), Vec3(0, 0, 0)) << elevation;
  const Vec3 low = air.sunIrradiance(ground, sunDirection(1, 90));
  const Vec3 high = air.sunIrradiance(ground, sunDirection(60, 90));
  for (int c = 0; c < 3; ++c) {
    EXPECT_GT(low[c], 0);
    EXPECT_GT(high[c], low[c]);
    EXPECT_LT(high[c], air.parameters().solarIrradiance[c]);
  }
  // The low sun is reddened: blue suffers the most.
  EXPECT_GT(low.x / high.x, low.z / high.z);
}

TEST(Sky, ZenithBluerThanHorizonWithTheSunHigh) {
  const Atmosphere air;
  const Vec3 eye = air.pointAtAltitude(1), sun = sunDirection(60, 180);
  const Vec3 zenith = air.skyRadiance(eye, {0, 0, 1}, sun);
  for (double azimuth : {0.0, 90.0, 180.0, 270.0}) {
    const Vec3 horizon = air.skyRadiance(eye, sunDirection(1, azimuth), sun);
    EXPECT_GT(zenith.z / zenith.x, horizon.z / horizon.x) << azimuth;
  }
  EXPECT_GT(zenith.z, zenith.x);  // a blue sky
}

TEST(Sky, HorizonReddensAsTheSunSets) {
  const Atmosphere air;
  const Vec3 eye = air.pointAtAltitude(1);
  double previous = 0;
  for (double elevation : {30.0, 15.0, 8.0, 4.0, 2.0}) {
    const Vec3 l = air.skyRadiance(eye, sunDirection(1, 250), sunDirection(elevation, 250));
    EXPECT_GT(l.x / l.z, previous) << elevation;
    previous = l.x / l.z;
  }
}

TEST(SkyImage, FisheyeIsFiniteAndNonNegative) {
  const Atmosphere air;
  SkyImageSettings s;
  s.width = s.height = 64;
  for (double elevation : {-5.0, 0.0, 5.0, 45.0, 90.0}) {
    const std::vector<Vec3> image = renderSky(air, sunDirection(elevation, 120), s);
    ASSERT_EQ(image.size(), 64u * 64u);
    for (const Vec3& v : image) {
      ASSERT_TRUE(isFinite(v)) << elevation;
      ASSERT_GE(v.x, 0);
      ASSERT_GE(v.y, 0);
      ASSERT_GE(v.z, 0);
    }
    EXPECT_GT(image[32 * 64 + 32].z, 0) << elevation;  // twilight still lights the zenith
  }
}

TEST(SkyImage, ProjectionsFollowTheirConventions) {
  SkyImageSettings s;
  s.width = s.height = 101;
  auto near = [](const std::optional<Vec3>& d, const Vec3& e, double tol) {
    return d && length(*d - e) < tol;
  };
  EXPECT_TRUE(near(pixelDirection(s, 50, 50), {0, 0, 1}, 1e-12));   // zenith at the centre
  EXPECT_TRUE(near(pixelDirection(s, 50, 0), {0, 1, 0}, 0.02));     // north at the top
  EXPECT_TRUE(near(pixelDirection(s, 0, 50), {1, 0, 0}, 0.02));     // east on the left
  EXPECT_TRUE(near(pixelDirection(s, 100, 50), {-1, 0, 0}, 0.02));  // west on the right
  EXPECT_FALSE(pixelDirection(s, 0, 0));                            // outside the circle
  s.projection = SkyProjection::Panorama;
  s.width = 200, s.height = 100;
  EXPECT_TRUE(near(pixelDirection(s, 50, 0), {0, 0, 1}, 0.02));     // top row: zenith
  EXPECT_TRUE(near(pixelDirection(s, 50, 49), {1, 0, 0}, 0.03));    // quarter width: east
  EXPECT_TRUE(near(pixelDirection(s, 100, 49), {0, -1, 0}, 0.03));  // middle: south
  s.projection = SkyProjection::Camera;
  s.cameraDirection = {0, 1, 0};
  s.width = s.height = 101;
  EXPECT_TRUE(near(pixelDirection(s, 50, 50), {0, 1, 0}, 1e-12));
  EXPECT_GT(pixelDirection(s, 100, 50)->x, 0.5);  // looking north, east is on the right
  EXPECT_GT(pixelDirection(s, 50, 0)->z, 0.5);    // and the sky at the top
}

TEST(Sky, MultipleScatteringTablesAreBuiltOnceUnderConcurrentUse) {
  // Many threads meet the lazily built tables at once; the result must equal a serial run's.
  const Atmosphere shared, serial;
  const Vec3 eye = shared.pointAtAltitude(1), sun = sunDirection(20, 100);
  std::vector<Vec3> parallel(256);
  tbb::parallel_for(0, 256, [&](int i) {
    parallel[std::size_t(i)] = shared.skyRadiance(eye, sunDirection(i % 90, 7.0 * i), sun);
  });
  for (int i = 0; i < 256; ++i)
    ASSERT_EQ(parallel[std::size_t(i)],
              serial.skyRadiance(eye, sunDirection(i % 90, 7.0 * i), sun));
}

TEST(Reference, IsDeterministicForASeed) {
  const Atmosphere air;
  const Vec3 eye = air.pointAtAltitude(1), sun = sunDirection(30, 180);
  const Vec3 dir = sunDirection(20, 40);
  const ReferenceEstimate a = referenceSkyRadiance(air, eye, dir, sun, 3000, 5);
  const ReferenceEstimate b = referenceSkyRadiance(air, eye, dir, sun, 3000, 5);
  const ReferenceEstimate c = referenceSkyRadiance(air, eye, dir, sun, 3000, 6);
  EXPECT_EQ(a.mean, b.mean);
  EXPECT_EQ(a.standardError, b.standardError);
  EXPECT_EQ(a.paths, 3000);
  EXPECT_NE(a.mean, c.mean);
}

TEST(Reference, StatisticalAgreesWithSingleScatteringInAThinAtmosphere) {
  // At 1 % of the air and a black ground, light scattered twice is below 1 % of the sky
  // (τ < 0.003 to the zenith in blue), under the reference's standard error here: single
  // scattering, marched finely, is then the exact answer. Four directions × three channels,
  // each within 4 standard errors.
  AtmosphereParameters p;
  p.relativeDensity = 0.01;
  p.groundAlbedo = 0;
  const Atmosphere air(p);
  const Vec3 eye = air.pointAtAltitude(1), sun = sunDirection(30, 180);
  const SkySettings fine{512, 128, false};
  for (const Vec3& dir :
       {Vec3{0, 0, 1}, sunDirection(40, 160), sunDirection(30, 0), sunDirection(60, 270)}) {
    const ReferenceEstimate r = referenceSkyRadiance(air, eye, dir, sun, 400000, 3);
    const Vec3 model = air.skyRadiance(eye, dir, sun, fine);
    for (int c = 0; c < 3; ++c) {
      EXPECT_GT(r.standardError[c], 0);
      EXPECT_LT(r.standardError[c], 0.1 * r.mean[c]);  // the check has teeth
      EXPECT_NEAR(model[c], r.mean[c], 4 * r.standardError[c])
          << "direction (" << dir.x << ", " << dir.y << ", " << dir.z << ") channel " << c;
    }
  }
}

TEST(Reference, GroundSeenThroughAVacuumIsLambertian) {
  // Without air the path tracer sees only the ground, lit by the sun alone: ρ/π·E·cos θ_sun,
  // for every path (the bounce escapes), so the estimate is exact and its error zero.
  AtmosphereParameters p;
  p.relativeDensity = 0;
  p.groundAlbedo = 0.8;
  const Atmosphere air(p);
  const Vec3 eye = air.pointAtAltitude(1000), sun = sunDirection(50, 30);
  const Vec3 dir = normalize(Vec3{0.3, 0.2, -1});
  const ReferenceEstimate r = referenceSkyRadiance(air, eye, dir, sun, 1000, 2);
  const Vec3 ground = eye + dir * distanceToSphereFromOutside(eye, dir, p.groundRadius);
  const double cosSun = dot(normalize(ground), sun);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(r.mean[c], 0.8 / kPi * p.solarIrradiance[c] * cosSun, 1e-12 * r.mean[c]) << c;
    EXPECT_NEAR(r.standardError[c], 0, 1e-12 * r.mean[c]);
  }
  EXPECT_EQ(air.skyRadiance(eye, dir, sun), Vec3(0, 0, 0));  // no air, no airlight
}

TEST(Reference, StatisticalMultipleScatteringMovesTheModelTowardIt) {
  // Earth's air with the sun at 30°: single scattering lacks the orders ≥ 2 and falls short of
  // the path tracer by many standard errors in blue; Hillaire's term closes most of the gap.
  const Atmosphere air;
  const Vec3 eye = air.pointAtAltitude(1), sun = sunDirection(30, 180);
  const SkySettings single{128, 32, false}, both{128, 32, true};
  for (const Vec3& dir :
       {Vec3{0, 0, 1}, sunDirection(45, 90), sunDirection(10, 0), sunDirection(10, 180)}) {
    const ReferenceEstimate r = referenceSkyRadiance(air, eye, dir, sun, 20000, 9);
    const Vec3 ss = air.skyRadiance(eye, dir, sun, single);
    const Vec3 ms = air.skyRadiance(eye, dir, sun, both);
    EXPECT_LT(ss.z, r.mean.z - 5 * r.standardError.z) << dir.x << " " << dir.y << " " << dir.z;
    for (int c = 0; c < 3; ++c)
      EXPECT_LT(std::fabs(ms[c] - r.mean[c]), std::fabs(ss[c] - r.mean[c]))
          << dir.x << " " << dir.y << " " << dir.z << " channel " << c;
  }
}

TEST(Reference, StatisticalHorizontalIrradianceOfAThinSky) {
  // The reference's irradiance estimator against the model's hemisphere quadrature, where
  // single scattering is exact (as above).
  AtmosphereParameters p;
  p.relativeDensity = 0.01;
  p.groundAlbedo = 0;
  const Atmosphere air(p);
  const Vec3 eye = air.pointAtAltitude(1), sun = sunDirection(40, 0);
  const ReferenceEstimate r = referenceHorizontalIrradiance(air, eye, sun, 400000, 4);
  SkySettings s{128, 32, false};
  // The model's irradiance by the midpoint rule on the same cos²θ and azimuth grid as
  // modelHorizontalIrradiance, written out here to keep the test independent of it.
  Vec3 e{0, 0, 0};
  const int rings = 48, columns = 96;
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < columns; ++j)
      e += air.skyRadiance(
          eye, localDirection(std::sqrt((i + 0.5) / rings), 2 * kPi * (j + 0.5) / columns), sun, s);
  e = e * (kPi / (rings * columns));
  for (int c = 0; c < 3; ++c) {
    EXPECT_LT(r.standardError[c], 0.1 * r.mean[c]) << c;
    EXPECT_NEAR(e[c], r.mean[c], 4 * r.standardError[c]) << c;
  }
}

}  // namespace
}  // namespace radkit::atmosphere
