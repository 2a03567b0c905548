// The path tracer against exact answers: the furnace (L = E / (π(1 − ρ))), determinism per
// seed, error bars that shrink as 1/√n. The Cornell box comparison with radiosity is in
// shading_cornell_test.cpp, beside the two-pass modes that share its radiosity solutions.
#include "render/path_tracer.h"

#include "render/final_gather.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cmath>

#include "geometry/ray_scene.h"
#include "geometry/scene_loader.h"
#include "geometry/subdivision.h"
#include "tests/common/test_util.h"

namespace radkit {
namespace {

/// Mean radiance over an image and its standard error from the per-pixel variances.
struct RegionMean {
  Vec3 mean, standardError;
  int pixels = 0;
};

RegionMean regionMean(const MonteCarloImage& img, const std::vector<bool>& inside) {
  RegionMean r;
  Vec3 variance;
  for (std::size_t k = 0; k < inside.size(); ++k)
    if (inside[k]) r.mean += img.image.radiance[k], variance += img.varianceOfMean[k], ++r.pixels;
  r.mean = r.mean / r.pixels;
  r.standardError = {std::sqrt(variance.x) / r.pixels, std::sqrt(variance.y) / r.pixels,
                     std::sqrt(variance.z) / r.pixels};
  return r;
}

Camera furnaceCamera() {
  Camera c;
  c.position = {0.5, 0.5, 0.5};
  c.lookAt = {0.5, 1, 0.6};
  c.up = {0, 0, 1};
  c.fovDeg = 100;
  return c;
}

/// The furnace's mean radiance over 16 seeds (16 × 16 pixels, s's samples) is 2/π within 4
/// standard errors estimated from the seeds' spread, and that error is below 1 %.
void expectFurnaceMean(const ShadingScene& shading, PathTraceSettings s, const std::string& what) {
  std::vector<double> means;
  for (std::uint64_t seed = 1; seed <= 16; ++seed) {
    s.seed = seed;
    means.push_back(
        regionMean(renderPathTraced(shading, furnaceCamera(), s), std::vector<bool>(256, true))
            .mean.y);
  }
  double mean = 0, spread = 0;
  for (double m : means) mean += m / means.size();
  for (double m : means) spread += (m - mean) * (m - mean);
  const double se = std::sqrt(spread / (means.size() - 1) / means.size());
  EXPECT_NEAR(mean, 2 / M_PI, 4 * se) << what;
  EXPECT_LT(se, 0.01 * mean) << what;
}

TEST(PathTracer, StatisticalFurnace) {
  // Closed cube, E = 1, ρ = 0.5 everywhere: L = E / (π (1 − ρ)) = 2/π in every direction.
  // Every path's estimate is random only through roulette and light sampling, so the image
  // mean must meet 2/π within 4 standard errors; quadrupling spp halves the error bar.
  Scene scene = loadScene(test::dataPath("furnace.json"));
  PatchMesh mesh = subdivide(scene, {0.1, 0});
  RayScene rays(mesh);
  ShadingScene shading(scene, mesh, rays, {});
  PathTraceSettings s;
  s.width = s.height = 24;
  s.samplesPerPixel = 8;
  RegionMean small =
      regionMean(renderPathTraced(shading, furnaceCamera(), s), std::vector<bool>(24 * 24, true));
  s.samplesPerPixel = 32;
  s.seed = 2;
  RegionMean big =
      regionMean(renderPathTraced(shading, furnaceCamera(), s), std::vector<bool>(24 * 24, true));
  EXPECT_NEAR(big.mean.y, 2 / M_PI, 4 * big.standardError.y);
  EXPECT_NEAR(small.mean.y, 2 / M_PI, 4 * small.standardError.y);
  EXPECT_LT(big.standardError.y, 0.02 * big.mean.y);
  EXPECT_NEAR(small.standardError.y / big.standardError.y, 2.0, 0.3);
}

TEST(PathTracer, StatisticalFurnaceForEverySampler) {
  // The furnace again, with each sampler: 16 renders with independent seeds give image means
  // whose spread is the honest error bar (stratified and Sobol samples of a pixel are not
  // independent, so per-pixel variances would misstate it). t with 15 degrees of freedom
  // exceeds 4 with probability 0.001 per sampler.
  Scene scene = loadScene(test::dataPath("furnace.json"));
  PatchMesh mesh = subdivide(scene, {0.1, 0});
  RayScene rays(mesh);
  ShadingScene shading(scene, mesh, rays, {});
  for (SamplerType type : {SamplerType::Independent, SamplerType::Stratified, SamplerType::Sobol}) {
    PathTraceSettings s;
    s.width = s.height = 16;
    s.samplesPerPixel = 8;
    s.sampler = type;
    expectFurnaceMean(shading, s, samplerName(type));
  }
}

TEST(PathTracer, StatisticalFurnaceWithSolidAngleLightSampling) {
  // Every wall of the furnace emits and is cut into rectangles, so next-event estimation
  // samples them by solid angle (or by area where they subtend too little) and the hits on
  // them are weighted with lightPdf from the previous vertex: a density that disagreed
  // with the sampling would move the mean off 2/π. Error bars from 16 seeds, as above.
  Scene scene = loadScene(test::dataPath("furnace.json"));
  PatchMesh mesh = subdivide(scene, {0.1, 0});
  RayScene rays(mesh);
  ShadingScene shading(scene, mesh, rays, {}, GlossyModel::AsDeclared, LightSampling::SolidAngle);
  PathTraceSettings s;
  s.width = s.height = 16;
  s.samplesPerPixel = 8;
  expectFurnaceMean(shading, s, "solid angle");
}

TEST(FinalGather, StatisticalFurnace) {
  // The furnace's exact radiosity, B = 2 and E = 1 on every patch: emission 1/π, direct light
  // ρ·E/π and the gathered (B − E)/π·ρ must add up to 2/π, flat or smooth lookups alike,
  // with or without the guide.
  // Error bars from 16 seeds, as above.
  Scene scene = loadScene(test::dataPath("furnace.json"));
  PatchMesh mesh = subdivide(scene, {0.1, 0});
  RayScene rays(mesh);
  ShadingScene shading(scene, mesh, rays, {});
  RadiosityLighting lighting;
  lighting.radiosity.assign(mesh.size(), Vec3{2, 2, 2});
  lighting.emission.assign(mesh.size(), Vec3{1, 1, 1});
  // The guide only needs form factors of this mesh; any solution's will do.
  PipelineSettings ps;
  ps.mesh.maxArea = 0.1;
  const PipelineResult r = runPipeline(scene, ps);
  ASSERT_EQ(r.mesh.size(), mesh.size());
  const GatherGuide guide(r.formFactors->matrix, lighting);
  for (int variant = 0; variant < 3; ++variant) {
    FinalGatherSettings s;
    s.width = s.height = 16;
    s.samplesPerPixel = 4;
    s.smooth = variant != 0;
    std::vector<double> means;
    for (std::uint64_t seed = 1; seed <= 16; ++seed) {
      s.seed = seed;
      const MonteCarloImage img =
          renderFinalGather(shading, furnaceCamera(), lighting, s, variant == 2 ? &guide : nullptr);
      means.push_back(regionMean(img, std::vector<bool>(256, true)).mean.y);
    }
    double mean = 0, spread = 0;
    for (double m : means) mean += m / means.size();
    for (double m : means) spread += (m - mean) * (m - mean);
    const double se = std::sqrt(spread / (means.size() - 1) / means.size());
    EXPECT_NEAR(mean, 2 / M_PI, 4 * se) << "variant " << variant << " (flat, smooth, guided)";
    EXPECT_LT(se, 0.01 * mean);
  }
}

TEST(PathTracer, ConstructDeterministicPerSeed) {
  // Pixels draw from their own streams: the same seed gives the same image with one thread
  // or all of them; another seed gives another image.
  Scene scene = loadScene(test::dataPath("cornell-box.json"));
  PatchMesh mesh = subdivide(scene, {0, 0});
  RayScene rays(mesh);
  ShadingScene shading(scene, mesh, rays, {});
  PathTraceSettings s;
  s.width = s.height = 16;
  s.samplesPerPixel = 2;
  MonteCarloImage a = renderPathTraced(shading, *scene.camera, s);
  MonteCarloImage b;
  tbb::task_arena one(1);
  one.execute([&] { b = renderPathTraced(shading, *scene.camera, s); });
  EXPECT_EQ(a.image.radiance, b.image.radiance);
  EXPECT_EQ(a.rays, b.rays);
  s.seed = 99;
  EXPECT_NE(renderPathTraced(shading, *scene.camera, s).image.radiance, a.image.radiance);
  EXPECT_EQ(a.paths, 16 * 16 * 2);
}

}  // namespace
}  // namespace radkit
