#include "render/path_tracer.h"

#include <algorithm>

namespace radkit {

Vec3 pathRadiance(const ShadingScene& scene, const Vec3& origin, const Vec3& dir, Sampler& sampler,
                  const PathTraceSettings& settings, long long& rays) {
  Vec3 radiance, beta{1, 1, 1};
  Vec3 o = origin, d = dir;
  double bsdfPdf = 0;    // density of the direction that led to the current vertex
  Vec3 from;             // the previous vertex (light sampling's pdf depends on it)
  bool specular = true;  // the camera ray, or a delta lobe: no light sampling competed
  for (int depth = 0; depth < settings.maxDepth; ++depth) {
    ++rays;
    std::optional<SurfaceHit> hit = scene.intersect(o, d);
    if (!hit) {
      // Left the scene: daylight, weighted against skyLight()'s sampling.
      if (scene.hasSky()) radiance += mul(beta, scene.escaped(d, bsdfPdf, specular));
      break;
    }
    // Emission found by the BSDF-sampled ray, weighted against light sampling.
    const Vec3 le = scene.emitted(*hit);
    if (maxComponent(le) > 0) {
      const double w = specular ? 1.0 : powerHeuristic(bsdfPdf, scene.lightPdf(*hit, from));
      radiance += mul(beta, le) * w;
    }
    if (!hit->bsdf) break;  // the back of a one-sided surface absorbs
    if (!hit->bsdf->isDelta()) {
      radiance += mul(beta, scene.directLight(*hit, sampler, rays));
      if (scene.hasSky()) radiance += mul(beta, scene.skyLight(*hit, sampler, rays));
    }

    const double u0 = sampler.get1DIfUsed(hit->bsdf->choosesLobe());
    const auto [u1, u2] = sampler.get2D();
    std::optional<BsdfSample> s = hit->bsdf->sample(hit->wo, u0, u1, u2);
    if (!s) break;
    beta = mul(beta, s->weight);
    bsdfPdf = s->pdf;
    specular = s->delta;
    d = hit->frame.toWorld(s->wi);
    o = scene.spawn(*hit, d);
    from = hit->point;

    // Russian roulette (Arvo & Kirk 1990): continue with probability q = min(1, max β),
    // dividing β by q keeps the estimator unbiased.
    if (depth + 1 >= settings.rouletteDepth) {
      const double q = std::min(1.0, maxComponent(beta));
      if (sampler.get1D() >= q) break;
      beta = beta / q;
    }
  }
  return radiance;
}

MonteCarloImage renderPathTraced(const ShadingScene& scene, const Camera& camera,
                                 const PathTraceSettings& s) {
  PixelSampling sampling{s.width, s.height, s.samplesPerPixel, s.seed, 0, s.sampler};
  return renderCameraSamples(
      scene, camera, sampling,
      [&](const Vec3& origin, const Vec3& direction, Sampler& sampler, long long& rays) {
        return pathRadiance(scene, origin, direction, sampler, s, rays);
      });
}

}  // namespace radkit
