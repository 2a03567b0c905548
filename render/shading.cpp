#include "render/shading.h"

#include <algorithm>

#include "radiosity/radiosity_solution.h"

namespace radkit {

RadiosityLighting radiosityLighting(const PipelineResult& r) {
  RadiosityLighting l;
  l.radiosity = r.radiosity;
  l.emission = toVec3(r.system.emission);
  std::vector<Vec3> daylight(r.radiosity.size());
  if (r.daylight) {
    // Under a sky the system's emission holds the daylight's first reflection ρD as well; the
    // surfaces' own emission is what is left (the image modes estimate D itself directly).
    const std::vector<Vec3> rho = toVec3(r.system.reflectance);
    for (std::size_t i = 0; i < daylight.size(); ++i) {
      daylight[i] = r.daylight->sky[i] + r.daylight->sun[i];
      const Vec3 e = l.emission[i] - mul(rho[i], daylight[i]);
      l.emission[i] = {std::max(0.0, e.x), std::max(0.0, e.y), std::max(0.0, e.z)};
    }
  }
  Channels emission = makeChannels(int(l.emission.size()));
  for (std::size_t i = 0; i < l.emission.size(); ++i)
    for (int c = 0; c < 3; ++c) emission[c][i] = l.emission[i][c];
  const std::vector<Vec3> direct = irradiance(r.formFactors->matrix, emission);
  l.indirectIrradiance.resize(r.irradiance.size());
  for (std::size_t i = 0; i < r.irradiance.size(); ++i) {
    // r.irradiance is FB (+ D under a sky): FB − FE is the light the other surfaces reflect.
    const Vec3 h = r.irradiance[i] - daylight[i] - direct[i];
    l.indirectIrradiance[i] = {std::max(0.0, h.x), std::max(0.0, h.y), std::max(0.0, h.z)};
  }
  return l;
}

namespace {

/// Radiance the radiosity solution reflects from a surface point toward the viewer:
/// (B − E)/π, Lambertian (its emission is counted by light sampling instead).
Vec3 reflectedRadiosity(const SurfaceHit& hit, const RadiosityLighting& l) {
  if (!hit.bsdf) return {};
  return (l.radiosity[hit.patch] - l.emission[hit.patch]) / M_PI;
}

/// One camera sample: follow delta lobes, then at the first glossy or diffuse vertex add
/// direct light (MIS), the BSDF-sampled ray's emission (MIS) and glossy radiosity, and
/// the diffuse lobe's indirect light ρ_d/π · H_indirect.
Vec3 twoPassRadiance(const ShadingScene& scene, const RadiosityLighting& lighting, Vec3 o, Vec3 d,
                     Sampler& sampler, const TwoPassSettings& s, long long& rays) {
  Vec3 radiance, beta{1, 1, 1};
  for (int depth = 0; depth <= s.maxSpecularDepth; ++depth) {
    ++rays;
    std::optional<SurfaceHit> hit = scene.intersect(o, d);
    if (!hit) {  // the camera's ray, or a mirror's, sees the sky at full weight
      radiance += mul(beta, scene.escaped(d, 0, true));
      break;
    }
    radiance += mul(beta, scene.emitted(*hit));
    if (!hit->bsdf) break;
    const double u0 = sampler.get1D();
    const auto [u1, u2] = sampler.get2D();
    if (hit->bsdf->isDelta()) {
      std::optional<BsdfSample> bs = hit->bsdf->sample(hit->wo, u0, u1, u2);
      if (!bs) break;
      beta = mul(beta, bs->weight);
      d = hit->frame.toWorld(bs->wi);
      o = scene.spawn(*hit, d);
      continue;
    }
    radiance += mul(beta, scene.directLight(*hit, sampler, rays));
    if (scene.hasSky()) radiance += mul(beta, scene.skyLight(*hit, sampler, rays));
    const Vec3 diffuse = hit->bsdf->diffuseAlbedo();
    radiance += mul(beta, mul(diffuse, lighting.indirectIrradiance[hit->patch])) / M_PI;
    if (std::optional<BsdfSample> bs = hit->bsdf->sample(hit->wo, u0, u1, u2)) {
      const Vec3 wi = hit->frame.toWorld(bs->wi);
      ++rays;
      if (std::optional<SurfaceHit> next = scene.intersect(scene.spawn(*hit, wi), wi)) {
        const Vec3 le = scene.emitted(*next);
        if (maxComponent(le) > 0)
          radiance += mul(beta, mul(bs->weight, le)) *
                      powerHeuristic(bs->pdf, scene.lightPdf(*next, hit->point));
        // Only the non-diffuse lobes gather the solution; the diffuse lobe has H_indirect.
        const Vec3 glossy = hit->bsdf->eval(hit->wo, bs->wi) - diffuse / M_PI;
        if (maxComponent(glossy) > 0)
          radiance +=
              mul(beta, mul(glossy, reflectedRadiosity(*next, lighting))) * (bs->wi.z / bs->pdf);
      } else if (scene.hasSky()) {
        // Every lobe's share of the daylight, weighted against skyLight()'s sampling.
        radiance += mul(beta, mul(bs->weight, scene.escaped(wi, bs->pdf, false)));
      }
    }
    break;
  }
  return radiance;
}

}  // namespace

MonteCarloImage renderTwoPass(const ShadingScene& scene, const Camera& camera,
                              const RadiosityLighting& lighting, const TwoPassSettings& s) {
  PixelSampling sampling{s.width, s.height, s.samplesPerPixel, s.seed, 1, s.sampler};
  return renderCameraSamples(
      scene, camera, sampling,
      [&](const Vec3& origin, const Vec3& direction, Sampler& sampler, long long& rays) {
        return twoPassRadiance(scene, lighting, origin, direction, sampler, s, rays);
      });
}

}  // namespace radkit
