// Daylight: sky and sun irradiance on patches against closed forms nobody on the team wrote
// (docs/daylight.md lists them with their sources), statistically where the estimate is
// Monte Carlo: replicate runs with different seeds give the standard error.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "atmosphere/atmosphere.h"
#include "daylight/daylight.h"
#include "daylight/sky.h"
#include "geometry/ray_scene.h"
#include "geometry/scene_loader.h"
#include "geometry/subdivision.h"
#include "radiosity/radiosity_pipeline.h"
#include "tests/common/statistics.h"
#include "tests/common/test_util.h"

namespace radkit {
namespace {

using test::TempDir;

constexpr double kDeg = M_PI / 180;

std::string vec(const Vec3& v) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "[%.17g, %.17g, %.17g]", v.x, v.y, v.z);
  return buf;
}

/// A 1 m square centred at the origin, tilted by `tiltDeg` from facing up (+z) towards +y.
std::string tiltedSquare(double tiltDeg) {
  const double t = tiltDeg * kDeg;
  const Vec3 u{1, 0, 0}, v{0, std::cos(t), -std::sin(t)};  // u × v = (0, sin t, cos t)
  auto p = [&](double a, double b) { return vec(u * a + v * b); };
  return R"({"name": "square", "material": "grey", "polygon": [)" + p(-0.5, -0.5) + ", " +
         p(0.5, -0.5) + ", " + p(0.5, 0.5) + ", " + p(-0.5, 0.5) + "]}";
}

Scene loadText(const TempDir& dir, const std::string& surfaces, const std::string& sky) {
  const std::string text =
      R"({"units": "m", "materials": {"grey": {"reflectance": [0.5, 0.5, 0.5]}},
    "surfaces": [)" +
      surfaces + R"(], "sky": )" + sky + "}";
  return loadScene(dir.file("scene.json", text));
}

/// Area-weighted means over the patches of surface `s` of one daylight computation.
struct SurfaceDaylight {
  Vec3 sky, sun;
  double skyViewFactor = 0;
};

SurfaceDaylight onSurface(const PatchMesh& mesh, const Daylight& d, int s) {
  SurfaceDaylight out;
  double area = 0;
  for (int i = mesh.surfaceBegin[s]; i < mesh.surfaceBegin[s + 1]; ++i) {
    const double a = mesh.patches[i].area;
    out.sky += d.sky[i] * a, out.sun += d.sun[i] * a;
    out.skyViewFactor += d.skyViewFactor[i] * a;
    area += a;
  }
  out.sky = out.sky / area, out.sun = out.sun / area, out.skyViewFactor /= area;
  return out;
}

/// Mean and standard error of a quantity over replicate seeds.
struct Replicates {
  double mean = 0, standardError = 0;
};

template <class F>
Replicates replicate(int runs, F value) {
  std::vector<double> v;
  for (int seed = 1; seed <= runs; ++seed) v.push_back(value(std::uint64_t(seed)));
  double mean = 0, ss = 0;
  for (double x : v) mean += x;
  mean /= runs;
  for (double x : v) ss += (x - mean) * (x - mean);
  return {mean, std::sqrt(ss / (runs - 1) / runs)};
}

/// |mean − expected| within z standard errors, the t critical value for `runs` − 1 degrees
/// of freedom at a 1e-4 two-sided level.
void expectAgrees(const Replicates& r, double expected, int runs, const std::string& what) {
  const double t = test::studentTCritical(1e-4, runs - 1);
  EXPECT_LE(std::fabs(r.mean - expected), t * r.standardError + 1e-12 * std::fabs(expected))
      << what << ": mean " << r.mean << " ± " << r.standardError << ", expected " << expected;
}

TEST(Daylight, UniformSkyOnAnOpenHorizontalPatchIsPiL) {
  // Every cosine-weighted direction of an upward patch sees the sky: E = πL exactly.
  TempDir dir;
  const Scene scene = loadText(dir, tiltedSquare(0),
                               R"({"type": "uniform", "radiance": [1, 2, 3], "samples": 64})");
  const PatchMesh mesh = subdivide(scene, {0, 4});
  const RayScene rays(mesh);
  const SkyModel sky(*scene.sky);
  const Daylight d = computeDaylight(mesh, rays, sky, 1);
  for (int i = 0; i < mesh.size(); ++i) {
    EXPECT_NEAR(d.sky[i].x, M_PI * 1, 1e-12);
    EXPECT_NEAR(d.sky[i].y, M_PI * 2, 1e-12);
    EXPECT_NEAR(d.sky[i].z, M_PI * 3, 1e-12);
    EXPECT_DOUBLE_EQ(d.skyViewFactor[i], 1.0);
  }
  EXPECT_NEAR(sky.horizontalSky().y, 2 * M_PI, 1e-12);
}

TEST(Daylight, UniformSkyOnATiltedPatchIsPiLOnePlusCosOverTwo) {
  // A plane tilted by β sees the sky over (1 + cos β)/2 of its cosine-weighted hemisphere
  // (the ground is black): E = πL(1 + cos β)/2, sky view factor (1 + cos β)/2.
  const int runs = 12;
  for (double tilt : {30.0, 60.0, 90.0, 135.0}) {
    TempDir dir;
    const Scene scene = loadText(dir, tiltedSquare(tilt),
                                 R"({"type": "uniform", "radiance": 2, "samples": 65536})");
    const PatchMesh mesh = subdivide(scene, {0, 1});
    const RayScene rays(mesh);
    const SkyModel sky(*scene.sky);
    std::vector<SurfaceDaylight> results;
    const Replicates e = replicate(runs, [&](std::uint64_t seed) {
      results.push_back(onSurface(mesh, computeDaylight(mesh, rays, sky, seed), 0));
      return results.back().sky.y;
    });
    const double f = (1 + std::cos(tilt * kDeg)) / 2;
    expectAgrees(e, 2 * M_PI * f, runs, "irradiance at tilt " + std::to_string(tilt));
    EXPECT_LT(e.standardError, 1e-3 * 2 * M_PI);  // precise enough to catch a 1 % error
    double svf = 0;
    for (const SurfaceDaylight& r : results) svf += r.skyViewFactor / runs;
    EXPECT_NEAR(svf, f, 4 * e.standardError / (2 * M_PI));
  }
}

TEST(Daylight, CieOvercastSkyOnAnOpenHorizontalPatchIsSevenPiLzOverNine) {
  // CIE standard overcast sky L(θ) = L_z (1 + 2 cos θ)/3 (Moon and Spencer 1942, CIE S 011):
  // E = ∫ L cos θ dω = 7πL_z/9.
  const int runs = 12;
  TempDir dir;
  const Scene scene = loadText(
      dir, tiltedSquare(0), R"({"type": "cie-overcast", "zenith_radiance": 3, "samples": 1024})");
  const PatchMesh mesh = subdivide(scene, {0, 4});
  const RayScene rays(mesh);
  const SkyModel sky(*scene.sky);
  const Replicates e = replicate(runs, [&](std::uint64_t seed) {
    return onSurface(mesh, computeDaylight(mesh, rays, sky, seed), 0).sky.x;
  });
  expectAgrees(e, 7 * M_PI * 3 / 9, runs, "CIE overcast");
  EXPECT_LT(e.standardError, 1e-3 * 7 * M_PI * 3 / 9);
  EXPECT_NEAR(sky.horizontalSky().x, 7 * M_PI * 3 / 9, 1e-12);
  // Through the luminance key: 683 · Y(E) lux = 7π L_z/9 with L_z in cd/m².
  const Scene lux =
      loadText(dir, tiltedSquare(0), R"({"type": "cie-overcast", "zenith_luminance": 4093})");
  EXPECT_NEAR(683 * luminance(SkyModel(*lux.sky).horizontalSky()), 7 * M_PI * 4093 / 9, 1e-6);
}

TEST(Daylight, SunOnAnOpenPatchIsNormalIrradianceTimesMeanCosine) {
  // A disc of angular radius δ and uniform radiance, its centre at angle θ from the normal
  // (θ + δ < 90°): the mean of cos over the disc is cos θ (1 + cos δ)/2, so
  // E = E_n cos θ (1 + cos δ)/2.
  const int runs = 12;
  TempDir dir;
  const Scene scene = loadText(dir, tiltedSquare(20), R"({"type": "uniform", "radiance": 0,
      "sun": {"elevation": 50, "azimuth": 30, "irradiance": [100, 200, 300], "angular_radius": 5},
      "samples": 1, "sun_samples": 256})");
  const PatchMesh mesh = subdivide(scene, {0, 4});
  const RayScene rays(mesh);
  const SkyModel sky(*scene.sky);
  ASSERT_TRUE(sky.hasSun());
  const Vec3 normal{0, std::sin(20 * kDeg), std::cos(20 * kDeg)};
  const double cosTheta = dot(normal, sky.sunDirection());
  const double expected = 300 * cosTheta * (1 + std::cos(5 * kDeg)) / 2;
  const Replicates e = replicate(runs, [&](std::uint64_t seed) {
    return onSurface(mesh, computeDaylight(mesh, rays, sky, seed), 0).sun.z;
  });
  expectAgrees(e, expected, runs, "sun");
  EXPECT_LT(e.standardError, 1e-3 * expected);
  // Azimuth 30° east of north at elevation 50°, in x east, y north, z up.
  const Vec3 s = sky.sunDirection();
  EXPECT_NEAR(s.x, std::cos(50 * kDeg) * std::sin(30 * kDeg), 1e-12);
  EXPECT_NEAR(s.y, std::cos(50 * kDeg) * std::cos(30 * kDeg), 1e-12);
  EXPECT_NEAR(s.z, std::sin(50 * kDeg), 1e-12);
}

TEST(Daylight, RoofShadowsTheSunAndHidesTheSky) {
  // A floor under a larger roof: no sun, no sky overhead; only low sky through the sides.
  TempDir dir;
  const std::string floor = tiltedSquare(0);
  const std::string roof = R"({"name": "roof", "material": "grey", "polygon":
      [[-5, -5, 1], [-5, 5, 1], [5, 5, 1], [5, -5, 1]]})";
  const Scene scene = loadText(dir, floor + ", " + roof, R"({"type": "uniform", "radiance": 1,
      "sun": {"elevation": 60, "irradiance": 500}, "samples": 2048})");
  const PatchMesh mesh = subdivide(scene, {0, 2});
  const RayScene rays(mesh);
  const Daylight d = computeDaylight(mesh, rays, SkyModel(*scene.sky), 3);
  const SurfaceDaylight f = onSurface(mesh, d, 0);
  EXPECT_EQ(f.sun.x, 0.0);
  // The roof's edge is at least 4.5 m away and 1 m up: sky only below 1/4.5 rad of elevation,
  // a cosine-weighted share of at most sin²(atan(1/4.5)) = 0.047.
  EXPECT_LT(f.skyViewFactor, 0.047);
  EXPECT_GT(f.skyViewFactor, 0.0);
}

/// Oke (1988): the sky view factor at a point of a canyon's floor a from one wall and b from
/// the other, walls H high and infinitely long, is (a/√(a²+H²) + b/√(b²+H²))/2; at the middle
/// (a = b = W/2) it is cos(arctan(2H/W)).
double canyonSkyViewFactor(double a, double b, double h) {
  return (a / std::hypot(a, h) + b / std::hypot(b, h)) / 2;
}

TEST(Daylight, StreetCanyonSkyViewFactorThroughThePipeline) {
  // data/street-canyon.json: W = H = 10 m, walls 400 m long; the floor's centre square is
  // ±0.1 m. The walls' ends let through directions the infinite canyon would block only
  // below 2H/L = 0.05 rad of elevation and within W/L of the axis: a share below 1e-4.
  Scene scene = loadScene(test::dataPath("street-canyon.json"));
  scene.sky->samples = 4096;
  const int centre = 0;
  ASSERT_EQ(scene.surfaces[centre].name, "floor-centre");
  const double w = 10, h = 10, c = 0.1;
  double expected = 0;  // mean over the square of Oke's formula (it varies with x only)
  const int n = 1000;
  for (int k = 0; k < n; ++k) {
    const double x = -c + (k + 0.5) / n * 2 * c;
    expected += canyonSkyViewFactor(w / 2 + x, w / 2 - x, h) / n;
  }
  EXPECT_NEAR(expected, std::cos(std::atan(2 * h / w)), 1e-4);
  PipelineSettings settings;
  settings.mesh.targetPatches = 60;
  const int runs = 8;
  std::vector<double> balance;
  const Replicates svf = replicate(runs, [&](std::uint64_t seed) {
    settings.formFactors.seed = seed;
    const PipelineResult r = runPipeline(scene, settings);
    balance.push_back(r.energy.relativeImbalance);
    return r.surfaces[centre].skyViewFactor;
  });
  expectAgrees(svf, expected, runs, "canyon sky view factor");
  std::printf("canyon: sky view factor %.6f ± %.6f, Oke %.6f\n", svf.mean, svf.standardError,
              expected);
  EXPECT_LT(svf.standardError, 2e-3);
  for (double b : balance) EXPECT_LT(b, 1e-3);  // daylight in = absorbed + escaped
}

TEST(Daylight, SameSeedSameDaylight) {
  TempDir dir;
  const std::string roof = R"({"name": "roof", "material": "grey", "polygon":
      [[-1, -1, 1], [-1, 1, 1], [1, 1, 1], [1, -1, 1]]})";
  const Scene scene = loadText(dir, tiltedSquare(30) + ", " + roof, R"({"type": "cie-overcast",
      "zenith_radiance": 1, "sun": {"elevation": 30, "irradiance": 5}, "samples": 64})");
  const PatchMesh mesh = subdivide(scene, {0, 16});
  const RayScene rays(mesh);
  const SkyModel sky(*scene.sky);
  const Daylight a = computeDaylight(mesh, rays, sky, 9), b = computeDaylight(mesh, rays, sky, 9);
  const Daylight c = computeDaylight(mesh, rays, sky, 10);
  bool differs = false;
  for (int i = 0; i < mesh.size(); ++i) {
    EXPECT_EQ(a.sky[i], b.sky[i]);
    EXPECT_EQ(a.sun[i], b.sun[i]);
    differs = differs || a.sky[i] != c.sky[i];
  }
  EXPECT_TRUE(differs);
}

TEST(Daylight, PhysicalSkyTableMatchesTheAtmosphere) {
  // The table's bilinear radiance against the atmosphere's own, away from the sun's disc,
  // and the open horizontal sky irradiance against a direct quadrature of the atmosphere.
  TempDir dir;
  const Scene scene = loadText(dir, tiltedSquare(0),
                               R"({"type": "physical", "sun": {"elevation": 35, "azimuth": 200}})");
  const SkyModel sky(*scene.sky);
  const atmosphere::Atmosphere air;
  const Vec3 eye = air.pointAtAltitude(0);
  const Vec3 sun = atmosphere::sunDirection(35, 200);
  double worst = 0;
  for (int i = 0; i < 40; ++i) {
    const double e = (1.5 + 2.2 * i) * kDeg, a = (17 + 37.3 * i) * kDeg;
    const Vec3 local{std::cos(e) * std::sin(a), std::cos(e) * std::cos(a), std::sin(e)};
    if (std::acos(dot(local, sun)) < 10 * kDeg) continue;
    const Vec3 direct = air.skyRadiance(eye, local, sun);
    const Vec3 table = sky.radiance(sky.toScene(local));
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::fabs(table[c] / direct[c] - 1));
  }
  EXPECT_LT(worst, 0.02);
  Vec3 e{0, 0, 0};  // midpoint rule, 48 × 96, on the atmosphere itself
  const int ne = 48, na = 96;
  for (int i = 0; i < ne; ++i)
    for (int j = 0; j < na; ++j) {
      const double el = (i + 0.5) / ne * M_PI / 2, az = (j + 0.5) / na * 2 * M_PI;
      const Vec3 local{std::cos(el) * std::sin(az), std::cos(el) * std::cos(az), std::sin(el)};
      e += air.skyRadiance(eye, local, sun) * (std::sin(el) * std::cos(el));
    }
  e = e * ((M_PI / 2) / ne * (2 * M_PI) / na);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(sky.horizontalSky()[c] / e[c], 1, 5e-3) << c;
  EXPECT_GT(sky.sunIrradiance().x, 0);
  EXPECT_NEAR(sky.horizontalSun().y, sky.sunIrradiance().y * std::sin(35 * kDeg), 1e-9);
}

TEST(Daylight, RefusesBadSkies) {
  TempDir dir;
  auto message = [&](const std::string& sky) {
    try {
      loadText(dir, tiltedSquare(0), sky);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("(loaded)");
  };
  EXPECT_NE(message(R"({"type": "cloudy"})").find("\"cloudy\""), std::string::npos);
  EXPECT_NE(message(R"({"type": "uniform", "radiance": -1})").find("negative"), std::string::npos);
  EXPECT_NE(message(R"({"type": "uniform", "radiance": 1, "up": [0, 1, 0], "north": [0, 2, 0]})")
                .find("parallel"),
            std::string::npos);
  EXPECT_NE(message(R"({"type": "physical"})").find("\"sun\""), std::string::npos);
  EXPECT_NE(
      message(R"({"type": "uniform", "radiance": 1, "sun": {"elevation": 95, "irradiance": 1}})")
          .find("elevation"),
      std::string::npos);
  EXPECT_NE(message(R"({"type": "uniform", "radiance": 1, "samples": 0})").find("samples"),
            std::string::npos);
  // A key the model does not read: the message names it and the keys the model does read.
  const std::string colour = message(R"({"type": "uniform", "radiance": 1, "colour": 3})");
  EXPECT_NE(colour.find("\"colour\", which uniform does not use"), std::string::npos) << colour;
  EXPECT_NE(colour.find("luminance, radiance"), std::string::npos) << colour;
  EXPECT_NE(message(R"({"type": "physical", "density": 0, "sun": {"elevation": 30}})")
                .find("\"density\" 0 is outside (0, 100]"),
            std::string::npos);
  EXPECT_NE(message(R"({"sun": {"elevation": 30}})").find("uniform, cie-overcast, physical"),
            std::string::npos);
  EXPECT_NE(message(R"({"type": "uniform", "radiance": 1})").find("(loaded)"), std::string::npos);
  for (const char* bad : {R"({"type": "cloudy"})", R"({"type": "physical"})"})
    EXPECT_NE(message(bad).find("scene.json"), std::string::npos);  // names the file
}

}  // namespace
}  // namespace radkit
