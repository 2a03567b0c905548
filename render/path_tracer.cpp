#include "render/path_tracer.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>

#include "render/camera.h"

namespace radkit {

Vec3 pathRadiance(const ShadingScene& scene, const Vec3& origin, const Vec3& dir, Rng& rng,
                  const PathTraceSettings& settings, long long& rays) {
  Vec3 radiance, beta{1, 1, 1};
  Vec3 o = origin, d = dir;
  double bsdfPdf = 0;      // density of the direction that led to the current vertex
  bool specular = true;    // the camera ray, or a delta lobe: no light sampling competed
  for (int depth = 0; depth < settings.maxDepth; ++depth) {
    ++rays;
    std::optional<SurfaceHit> hit = scene.intersect(o, d);
    if (!hit) break;
    // Emission found by the BSDF-sampled ray, weighted against light sampling.
    const Vec3 le = scene.emitted(*hit);
    if (maxComponent(le) > 0) {
      const double w = specular ? 1.0 : powerHeuristic(bsdfPdf, scene.lightPdf(*hit));
      radiance += mul(beta, le) * w;
    }
    if (!hit->bsdf) break;  // the back of a one-sided surface absorbs
    if (!hit->bsdf->isDelta()) radiance += mul(beta, scene.directLight(*hit, rng, rays));

    const double u0 = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
    std::optional<BsdfSample> s = hit->bsdf->sample(hit->wo, u0, u1, u2);
    if (!s) break;
    beta = mul(beta, s->weight);
    bsdfPdf = s->pdf;
    specular = s->delta;
    d = hit->frame.toWorld(s->wi);
    o = scene.spawn(*hit, d);

    // Russian roulette (Arvo & Kirk 1990): continue with probability q = min(1, max β),
    // dividing β by q keeps the estimator unbiased.
    if (depth + 1 >= settings.rouletteDepth) {
      const double q = std::min(1.0, maxComponent(beta));
      if (rng.uniform() >= q) break;
      beta = beta / q;
    }
  }
  return radiance;
}

MonteCarloImage renderPathTraced(const ShadingScene& scene, const Camera& camera, const PathTraceSettings& s) {
  const auto start = std::chrono::steady_clock::now();
  const PinholeCamera cam(camera, s.width, s.height);
  const int n = std::max(1, s.samplesPerPixel);
  MonteCarloImage out;
  RadianceImage& img = out.image;
  img.width = s.width;
  img.height = s.height;
  img.radiance.assign(std::size_t(s.width) * s.height, Vec3{});
  img.patch.assign(img.radiance.size(), -1);
  out.varianceOfMean.assign(img.radiance.size(), Vec3{});
  std::vector<long long> rowRays(s.height, 0);

  tbb::parallel_for(0, s.height, [&](int y) {
    for (int x = 0; x < s.width; ++x) {
      const std::size_t k = std::size_t(y) * s.width + x;
      Rng rng(s.seed, k, 0);
      Vec3 sum, sumSq;
      for (int i = 0; i < n; ++i) {
        const double jx = rng.uniform(), jy = rng.uniform();
        const Vec3 l = pathRadiance(scene, cam.origin(), cam.direction(x + jx, y + jy), rng, s, rowRays[y]);
        sum += l;
        sumSq += mul(l, l);
      }
      const Vec3 mean = sum / n;
      img.radiance[k] = mean;
      // Unbiased sample variance s² = (Σl² − n·mean²)/(n − 1); the mean's variance is s²/n.
      if (n > 1) {
        const Vec3 v = (sumSq - mul(mean, mean) * n) / (double(n - 1) * n);
        out.varianceOfMean[k] = {std::max(0.0, v.x), std::max(0.0, v.y), std::max(0.0, v.z)};
      }
      if (auto hit = scene.rays().closestHit(cam.origin(), cam.direction(x + 0.5, y + 0.5), 0.0))
        img.patch[k] = hit->patch;
    }
  });
  out.paths = (long long)(n) * s.width * s.height;
  for (long long r : rowRays) out.rays += r;
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace radkit
