#include "render/final_gather.h"

#include <optional>

namespace radkit {

namespace {

struct Gather {
  const ShadingScene& scene;
  const RadiosityLighting& lighting;
  const std::optional<SmoothRadiosity>& smooth;
  const FinalGatherSettings& settings;

  /// Radiance the solution says leaves y toward the gathering point, emission excluded
  /// (light sampling and the MIS-weighted hit count it): (B − E)/π, Lambertian.
  Vec3 reflected(const SurfaceHit& y) const {
    if (!y.bsdf) return {};
    const Vec3 b = smooth ? smooth->at(y.patch, y.point) : lighting.radiosity[y.patch];
    const Vec3 r = (b - lighting.emission[y.patch]) / M_PI;
    return {std::max(0.0, r.x), std::max(0.0, r.y), std::max(0.0, r.z)};
  }

  Vec3 radiance(Vec3 o, Vec3 d, Sampler& sampler, long long& rays) const {
    Vec3 radiance, beta{1, 1, 1};
    for (int depth = 0; depth <= settings.maxSpecularDepth; ++depth) {
      ++rays;
      std::optional<SurfaceHit> hit = scene.intersect(o, d);
      if (!hit) break;
      radiance += mul(beta, scene.emitted(*hit));
      if (!hit->bsdf) break;
      if (!hit->bsdf->isDelta()) radiance += mul(beta, scene.directLight(*hit, sampler, rays));
      const double u0 = sampler.get1D();
      const auto [u1, u2] = sampler.get2D();
      std::optional<BsdfSample> bs = hit->bsdf->sample(hit->wo, u0, u1, u2);
      if (!bs) break;
      const Vec3 wi = hit->frame.toWorld(bs->wi);
      if (bs->delta) {  // mirror or glass: follow it to the surface that gathers
        beta = mul(beta, bs->weight);
        o = scene.spawn(*hit, wi);
        d = wi;
        continue;
      }
      ++rays;
      if (std::optional<SurfaceHit> next = scene.intersect(scene.spawn(*hit, wi), wi)) {
        const Vec3 le = scene.emitted(*next);
        if (maxComponent(le) > 0)
          radiance += mul(beta, mul(bs->weight, le)) * powerHeuristic(bs->pdf, scene.lightPdf(*next));
        radiance += mul(beta, mul(bs->weight, reflected(*next)));
      }
      break;
    }
    return radiance;
  }
};

}  // namespace

MonteCarloImage renderFinalGather(const ShadingScene& scene, const Camera& camera, const RadiosityLighting& lighting,
                                  const FinalGatherSettings& s) {
  std::optional<SmoothRadiosity> smooth;
  if (s.smooth) smooth.emplace(scene.mesh(), lighting.radiosity, s.smoothing);
  const Gather gather{scene, lighting, smooth, s};
  PixelSampling sampling{s.width, s.height, s.samplesPerPixel, s.seed, 2, s.sampler};
  return renderCameraSamples(scene, camera, sampling,
                             [&](const Vec3& origin, const Vec3& direction, Sampler& sampler, long long& rays) {
                               return gather.radiance(origin, direction, sampler, rays);
                             });
}

}  // namespace radkit
