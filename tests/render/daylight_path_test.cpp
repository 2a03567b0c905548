// The path tracer under a scene's "sky" against closed forms: a Lambertian square of
// reflectance ρ under an unobstructed sky reflects L = ρE/π, with E the sky's irradiance on
// its plane (uniform sky L_s tilted by β: πL_s(1 + cos β)/2; CIE overcast sky on a horizontal
// plane: 7πL_z/9, Moon & Spencer 1942) plus the sun's E_n cos θ (docs/oracles.md).
#include "render/path_tracer.h"

#include "render/final_gather.h"
#include "render/shading.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "daylight/sky.h"
#include "geometry/ray_scene.h"
#include "geometry/scene_loader.h"
#include "geometry/subdivision.h"
#include "radiosity/radiosity_pipeline.h"
#include "radiosity/radiosity_solution.h"
#include "tests/common/test_util.h"

namespace radkit {
namespace {

constexpr double kDeg = M_PI / 180;

std::string daylightVec(const Vec3& v) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "[%.17g, %.17g, %.17g]", v.x, v.y, v.z);
  return buf;
}

/// A 1 m square of ρ = 0.5 centred at the origin, facing up (+z) tilted by `tiltDeg` towards
/// +y, under `sky` (a JSON object, given z up and y north).
Scene daylightSquare(const test::TempDir& dir, double tiltDeg, const std::string& sky) {
  const double t = tiltDeg * kDeg;
  const Vec3 u{1, 0, 0}, v{0, std::cos(t), -std::sin(t)};
  auto p = [&](double a, double b) { return daylightVec(u * a + v * b); };
  const std::string text =
      R"({"units": "m", "materials": {"grey": {"reflectance": [0.5, 0.5, 0.5]}},
      "surfaces": [{"name": "square", "material": "grey", "polygon": [)" +
      p(-0.5, -0.5) + ", " + p(0.5, -0.5) + ", " + p(0.5, 0.5) + ", " + p(-0.5, 0.5) +
      R"(]}], "sky": )" + sky.substr(0, sky.size() - 1) +
      R"(, "up": [0, 0, 1], "north": [0, 1, 0]}})";
  return loadScene(dir.file("square.json", text));
}

struct DaylightMean {
  Vec3 mean, standardError;
};

/// Radiance the path tracer sees along camera rays at the square's centre from 1 m in front
/// of it, n independent samples.
DaylightMean daylightSeen(const Scene& scene, double tiltDeg, int n, std::uint64_t seed) {
  const PatchMesh mesh = subdivide(scene, {1, 0});
  const RayScene rays(mesh);
  const ShadingScene shading(scene, mesh, rays, {});
  const double t = tiltDeg * kDeg;
  const Vec3 normal{0, std::sin(t), std::cos(t)};
  // Off the normal by 20°, so the camera is not in the way of anything (it is not in the scene).
  const Vec3 side = normalize(Vec3{1, 0, 0} * std::sin(20 * kDeg) + normal * std::cos(20 * kDeg));
  const Vec3 eye = side * 1.0;
  PathTraceSettings settings;
  auto sampler = makeSampler(SamplerType::Independent, seed, 0, n);
  Vec3 sum, sum2;
  long long rayCount = 0;
  for (int i = 0; i < n; ++i) {
    sampler->start(0, i);
    const Vec3 l = pathRadiance(shading, eye, -side, *sampler, settings, rayCount);
    sum += l, sum2 += mul(l, l);
  }
  DaylightMean m;
  m.mean = sum / n;
  const Vec3 var = (sum2 - mul(sum, m.mean)) / (n - 1);
  m.standardError = {std::sqrt(var.x / n), std::sqrt(var.y / n), std::sqrt(var.z / n)};
  return m;
}

TEST(DaylightPathTracer, StatisticalTiltedSquareUnderUniformSkyAndSun) {
  // L = ρ/π (πL_s(1 + cos β)/2 + E_n cos θ_sun), the sun 40° up in the south-east (azimuth
  // 135°), its normal irradiance per channel (300, 500, 700) W/m², the sky (10, 20, 40).
  test::TempDir dir;
  const std::string sky = R"({"type": "uniform", "radiance": [10, 20, 40],
      "sun": {"elevation": 40, "azimuth": 135, "irradiance": [300, 500, 700]}})";
  for (double tilt : {0.0, -60.0}) {  // flat, and tilted 60° to face the southern sky
    const Scene scene = daylightSquare(dir, tilt, sky);
    const SkyModel model(*scene.sky);
    const Vec3 normal{0, std::sin(tilt * kDeg), std::cos(tilt * kDeg)};
    const double cosSun = std::max(0.0, dot(normal, model.sunDirection()));
    ASSERT_GT(cosSun, 0.1);
    const double skyShare = (1 + std::cos(tilt * kDeg)) / 2;
    const Vec3 expected =
        (Vec3{10, 20, 40} * (M_PI * skyShare) + Vec3{300, 500, 700} * cosSun) * (0.5 / M_PI);
    const DaylightMean m = daylightSeen(scene, tilt, 40000, 7);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(m.mean[c], expected[c], 4 * m.standardError[c]) << "tilt " << tilt << " c " << c;
      EXPECT_LT(m.standardError[c], 0.01 * expected[c]);
    }
    // Teeth: the sun counted twice (NEE and escapes at full weight) or not at all lies far off.
    const double sunPart = 700 * cosSun * 0.5 / M_PI;
    EXPECT_GT(std::fabs(m.mean.z - (expected.z + sunPart)), 8 * m.standardError.z);
    EXPECT_GT(std::fabs(m.mean.z - (expected.z - sunPart)), 8 * m.standardError.z);
  }
}

TEST(DaylightPathTracer, StatisticalOvercastSkyOnAHorizontalSquare) {
  // CIE overcast, L(θ) = L_z(1 + 2 cos θ)/3: E = 7πL_z/9 on an open horizontal plane, so a
  // ρ = 0.5 square reflects L = 0.5 · 7L_z/9 (a uniform sky of the same zenith radiance would
  // give 0.5 L_z, 29 % more).
  test::TempDir dir;
  const double Lz = 30;
  const Scene scene = daylightSquare(dir, 0, R"({"type": "cie-overcast", "zenith_radiance": 30})");
  const DaylightMean m = daylightSeen(scene, 0, 40000, 8);
  const double expected = 0.5 * 7 * Lz / 9;
  EXPECT_NEAR(m.mean.y, expected, 4 * m.standardError.y);
  EXPECT_LT(m.standardError.y, 0.01 * expected);
  EXPECT_GT(std::fabs(m.mean.y - 0.5 * Lz), 8 * m.standardError.y);
}

TEST(DaylightPathTracer, EscapingCameraRaysSeeTheSkyAndTheSunsDisc) {
  test::TempDir dir;
  const Scene scene = daylightSquare(dir, 0, R"({"type": "uniform", "radiance": [1, 2, 3],
      "sun": {"elevation": 30, "azimuth": 90, "irradiance": 1000}})");
  const PatchMesh mesh = subdivide(scene, {1, 0});
  const RayScene rays(mesh);
  const ShadingScene shading(scene, mesh, rays, {});
  const SkyModel model(*scene.sky);
  auto sampler = makeSampler(SamplerType::Independent, 1, 0, 1);
  sampler->start(0, 0);
  long long count = 0;
  const Vec3 eye{0, 0, 5};
  const Vec3 away = normalize(Vec3{-1, 0.2, 0.5});
  const Vec3 sky = pathRadiance(shading, eye, away, *sampler, {}, count);
  EXPECT_EQ(sky, (Vec3{1, 2, 3}));
  // The disc's radiance E_n/Ω, Ω = 2π(1 − cos r).
  const Vec3 sun = pathRadiance(shading, eye, model.sunDirection(), *sampler, {}, count);
  const double solidAngle = 2 * M_PI * (1 - model.sunCosRadius());
  EXPECT_NEAR(sun.x, 1 + 1000 / solidAngle, 1e-9 * sun.x);
}

/// Mean and standard error of a render's image mean over 16 seeds (the spread of the seeds'
/// means: Sobol samples within a pixel are not independent).
template <class Render>
DaylightMean daylightOverSeeds(Render render) {
  std::vector<Vec3> means;
  for (std::uint64_t seed = 1; seed <= 16; ++seed) {
    const MonteCarloImage img = render(seed);
    Vec3 m;
    for (const Vec3& v : img.image.radiance) m += v / double(img.image.radiance.size());
    means.push_back(m);
  }
  DaylightMean out;
  for (const Vec3& m : means) out.mean += m / double(means.size());
  Vec3 spread;
  for (const Vec3& m : means) spread += mul(m - out.mean, m - out.mean);
  const double k = double(means.size());
  out.standardError = {std::sqrt(spread.x / (k - 1) / k), std::sqrt(spread.y / (k - 1) / k),
                       std::sqrt(spread.z / (k - 1) / k)};
  return out;
}

TEST(DaylightImageModes, StatisticalFinalGatherAndTwoPassMeetTheClosedForm) {
  // The flat square under the uniform sky and sun again, through the radiosity solution: the
  // final gather and the two-pass modes estimate the daylight at the visible point themselves
  // (sky and sun by next-event estimation, escaping BSDF samples by MIS), and the square's
  // own B = ρD (counted in the system's emission) must not come back as reflected light.
  // Error bars from 16 seeds' spread (Sobol samples of a pixel are not independent).
  test::TempDir dir;
  const Scene scene = daylightSquare(dir, 0, R"({"type": "uniform", "radiance": [10, 20, 40],
      "sun": {"elevation": 40, "azimuth": 135, "irradiance": [300, 500, 700]}})");
  const SkyModel model(*scene.sky);
  const double expected = (20 * M_PI + 500 * model.sunDirection().z) * 0.5 / M_PI;
  PipelineSettings ps;
  ps.mesh.maxArea = 0.1;
  const PipelineResult r = runPipeline(scene, ps);
  const RadiosityLighting lighting = radiosityLighting(r);
  for (std::size_t i = 0; i < lighting.emission.size(); ++i) {
    EXPECT_EQ(lighting.emission[i], Vec3{}) << i;            // not ρD: the square does not emit
    EXPECT_EQ(lighting.indirectIrradiance[i], Vec3{}) << i;  // nothing else to reflect light
  }
  const ShadingScene shading(scene, r.mesh, *r.rays, {});
  Camera camera;
  camera.position = {0, 0, 1};
  camera.lookAt = {0, 0, 0};
  camera.up = {0, 1, 0};
  camera.fovDeg = 30;  // sees only the square (±0.27 m of its centre)
  for (int mode = 0; mode < 2; ++mode) {
    const DaylightMean m = daylightOverSeeds([&](std::uint64_t seed) {
      if (mode == 0) {
        FinalGatherSettings s;
        s.width = s.height = 8, s.samplesPerPixel = 16, s.seed = seed;
        return renderFinalGather(shading, camera, lighting, s);
      }
      TwoPassSettings s;
      s.width = s.height = 8, s.samplesPerPixel = 16, s.seed = seed;
      return renderTwoPass(shading, camera, lighting, s);
    });
    const double mean = m.mean.y, se = m.standardError.y;
    EXPECT_NEAR(mean, expected, 4 * se) << (mode ? "two-pass" : "final gather");
    EXPECT_LT(se, 0.01 * expected);
    // Teeth: the daylight's reflection counted twice (once as emission) lies far off.
    EXPECT_GT(std::fabs(mean - 2 * expected), 8 * se);
  }
}

TEST(DaylightImageModes, StatisticalFinalGatherAndTwoPassMatchThePathTracerInACorner) {
  // A 1 m floor (ρ = 0.5) and a 1 m wall (ρ = 0.8) along its north edge, under the overcast
  // sky and a sun in the south: the floor is lit by the sky, the sun and the wall's reflection
  // of both. The final gather reads that reflection from the radiosity solution, (B − E)/π,
  // the two-pass mode as ρ/π (FB − FE); both must agree with the path tracer within 4
  // combined standard errors (the solution's discretisation error, 0.01 m² patches, stayed
  // below them: 67.039 ± 0.050, guided 67.084 ± 0.028, two-pass 67.050 ± 0.023, against
  // 67.050 ± 0.042). Leaving the daylight's reflection ρD in E, as the system's emission has
  // it, drops the wall's reflected daylight: 59.106 ± 0.018.
  test::TempDir dir;
  const std::string text = R"({"units": "m", "materials": {
      "floor": {"reflectance": [0.5, 0.5, 0.5]}, "wall": {"reflectance": [0.8, 0.8, 0.8]}},
      "surfaces": [
        {"name": "floor", "material": "floor", "polygon": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]]},
        {"name": "wall", "material": "wall", "polygon": [[0,1,0],[1,1,0],[1,1,1],[0,1,1]]}],
      "sky": {"type": "cie-overcast", "zenith_radiance": 30, "up": [0, 0, 1],
              "north": [0, 1, 0], "sun": {"elevation": 50, "azimuth": 180, "irradiance": 400}}})";
  const Scene scene = loadScene(dir.file("corner.json", text));
  PipelineSettings ps;
  ps.mesh.maxArea = 0.01;
  const PipelineResult r = runPipeline(scene, ps);
  const RadiosityLighting lighting = radiosityLighting(r);
  const ShadingScene shading(scene, r.mesh, *r.rays, {});
  const GatherGuide guide(r.formFactors->matrix, lighting);
  Camera camera;
  camera.position = {0.5, -0.6, 0.9};
  camera.lookAt = {0.5, 0.55, 0.3};
  camera.up = {0, 0, 1};
  camera.fovDeg = 40;  // the floor and the wall fill the view
  const DaylightMean pt = daylightOverSeeds([&](std::uint64_t seed) {
    PathTraceSettings s;
    s.width = s.height = 12, s.samplesPerPixel = 32, s.seed = seed;
    return renderPathTraced(shading, camera, s);
  });
  for (int guided = 0; guided < 2; ++guided) {
    const DaylightMean fg = daylightOverSeeds([&](std::uint64_t seed) {
      FinalGatherSettings s;
      s.width = s.height = 12, s.samplesPerPixel = 32, s.seed = seed;
      return renderFinalGather(shading, camera, lighting, s, guided ? &guide : nullptr);
    });
    const double se = std::hypot(fg.standardError.y, pt.standardError.y);
    EXPECT_NEAR(fg.mean.y, pt.mean.y, 4 * se) << "guided " << guided;
  }
  RadiosityLighting systemEmission = lighting;
  systemEmission.emission = toVec3(r.system.emission);
  const DaylightMean wrong = daylightOverSeeds([&](std::uint64_t seed) {
    FinalGatherSettings s;
    s.width = s.height = 12, s.samplesPerPixel = 32, s.seed = seed;
    return renderFinalGather(shading, camera, systemEmission, s);
  });
  const DaylightMean twoPass = daylightOverSeeds([&](std::uint64_t seed) {
    TwoPassSettings s;
    s.width = s.height = 12, s.samplesPerPixel = 32, s.seed = seed;
    return renderTwoPass(shading, camera, lighting, s);
  });
  EXPECT_NEAR(twoPass.mean.y, pt.mean.y,
              4 * std::hypot(twoPass.standardError.y, pt.standardError.y));
  EXPECT_GT(pt.mean.y - wrong.mean.y, 8 * std::hypot(wrong.standardError.y, pt.standardError.y));
}

}  // namespace
}  // namespace radkit
