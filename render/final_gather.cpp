#include "render/final_gather.h"

#include <algorithm>
#include <optional>

#include "radiosity/form_factor_storage.h"

namespace radkit {

GatherGuide::GatherGuide(const FormFactorMatrix& f, const RadiosityLighting& l)
    : m_start(matrixSize(f) + 1, 0) {
  std::vector<double> weight;
  int row = -1;
  auto closeRow = [&] {
    double total = 0;
    for (double w : weight) total += w;
    double running = 0;
    for (double w : weight) m_cdf.push_back(float((running += w) / total));
    if (!weight.empty()) m_cdf.back() = 1;
    weight.clear();
  };
  forEachNonZero(f, [&](int i, int j, double fij) {
    while (row < i) {
      closeRow();
      m_start[++row] = m_source.size();
    }
    const double w = fij * std::max(0.0, luminance(l.radiosity[j] - l.emission[j]));
    if (!(w > 0)) return;
    m_source.push_back(j);
    weight.push_back(w);
  });
  closeRow();
  while (row < int(m_start.size()) - 1) m_start[++row] = m_source.size();
}

int GatherGuide::pick(int receiver, double u, double& probability) const {
  const auto begin = m_cdf.begin() + std::ptrdiff_t(m_start[receiver]),
             end = m_cdf.begin() + std::ptrdiff_t(m_start[receiver + 1]);
  const auto k = std::min(std::upper_bound(begin, end, float(u)), end - 1);
  probability = *k - (k == begin ? 0.0f : *(k - 1));
  return m_source[std::size_t(k - m_cdf.begin())];
}

double GatherGuide::probability(int receiver, int source) const {
  const auto begin = m_source.begin() + std::ptrdiff_t(m_start[receiver]),
             end = m_source.begin() + std::ptrdiff_t(m_start[receiver + 1]);
  const auto k = std::lower_bound(begin, end, source);
  if (k == end || *k != source) return 0;
  const std::size_t c = std::size_t(k - m_source.begin());
  return m_cdf[c] - (k == begin ? 0.0f : m_cdf[c - 1]);
}

namespace {

struct Gather {
  const ShadingScene& scene;
  const RadiosityLighting& lighting;
  const std::optional<SmoothRadiosity>& smooth;
  const FinalGatherSettings& settings;
  const GatherGuide* guide;

  /// Radiance the solution says leaves point y of patch j toward the gathering point,
  /// emission excluded (light sampling and the MIS-weighted hit count it): (B − E)/π.
  Vec3 reflected(int j, const Vec3& y) const {
    const Vec3 b = smooth ? smooth->at(j, y) : lighting.radiosity[j];
    const Vec3 r = (b - lighting.emission[j]) / M_PI;
    return {std::max(0.0, r.x), std::max(0.0, r.y), std::max(0.0, r.z)};
  }
  Vec3 reflected(const SurfaceHit& y) const {
    return y.bsdf ? reflected(y.patch, y.point) : Vec3{};
  }

  /// Solid-angle density of the guide choosing the front-side point `y` seen from `x`'s patch.
  double guidePdf(int receiver, const SurfaceHit& y) const {
    if (!guide || !y.front || guide->empty(receiver)) return 0;
    const double cosY = std::fabs(y.wo.z);
    if (cosY <= 0) return 0;
    return guide->probability(receiver, y.patch) / scene.mesh().patches[y.patch].area * y.distance *
           y.distance / cosY;
  }

  /// The guided sample: a source patch by the guide, a point on it, a shadow ray.
  Vec3 guided(const SurfaceHit& x, Sampler& sampler, long long& rays) const {
    const double u0 = sampler.get1D();
    const auto [u1, u2] = sampler.get2D();
    if (!guide || guide->empty(x.patch)) return {};
    double probability = 0;
    const int j = guide->pick(x.patch, u0, probability);
    if (!(probability > 0)) return {};
    const PatchMesh& mesh = scene.mesh();
    const Patch& p = mesh.patches[j];
    Vec3 v[4];
    for (int c = 0; c < p.vertexCount; ++c) v[c] = mesh.vertex(p, c);
    const Vec3 y = samplePatchUniform(v, p.vertexCount, u1, u2);
    const Vec3 d = y - x.point;
    const double dist2 = dot(d, d);
    if (!(dist2 > 0)) return {};
    const Vec3 wi = d / std::sqrt(dist2);
    const double cosY = -dot(wi, p.normal);
    if (cosY <= 0) return {};
    const Vec3 wiLocal = x.frame.toLocal(wi);
    const Vec3 f = x.bsdf->eval(x.wo, wiLocal);
    const Vec3 l = reflected(j, y);
    if (maxComponent(f) <= 0 || maxComponent(l) <= 0) return {};
    ++rays;
    if (scene.rays().occluded(x.point, mesh.patches[x.patch].normal, y, p.normal)) return {};
    const double pdf = probability / p.area * dist2 / cosY;
    return mul(f, l) *
           (std::fabs(wiLocal.z) * powerHeuristic(pdf, x.bsdf->pdf(x.wo, wiLocal)) / pdf);
  }

  Vec3 radiance(Vec3 o, Vec3 d, Sampler& sampler, long long& rays) const {
    Vec3 radiance, beta{1, 1, 1};
    for (int depth = 0; depth <= settings.maxSpecularDepth; ++depth) {
      ++rays;
      std::optional<SurfaceHit> hit = scene.intersect(o, d);
      if (!hit) {  // the camera's ray, or a mirror's, sees the sky at full weight
        radiance += mul(beta, scene.escaped(d, 0, true));
        break;
      }
      radiance += mul(beta, scene.emitted(*hit));
      if (!hit->bsdf) break;
      if (!hit->bsdf->isDelta()) {
        radiance += mul(beta, scene.directLight(*hit, sampler, rays));
        if (scene.hasSky()) radiance += mul(beta, scene.skyLight(*hit, sampler, rays));
        radiance += mul(beta, guided(*hit, sampler, rays));
      }
      const double u0 = sampler.get1DIfUsed(hit->bsdf->choosesLobe());
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
          radiance += mul(beta, mul(bs->weight, le)) *
                      powerHeuristic(bs->pdf, scene.lightPdf(*next, hit->point));
        const double w = guide ? powerHeuristic(bs->pdf, guidePdf(hit->patch, *next)) : 1.0;
        radiance += mul(beta, mul(bs->weight, reflected(*next))) * w;
      } else if (scene.hasSky()) {
        radiance += mul(beta, mul(bs->weight, scene.escaped(wi, bs->pdf, false)));
      }
      break;
    }
    return radiance;
  }
};

}  // namespace

MonteCarloImage renderFinalGather(const ShadingScene& scene, const Camera& camera,
                                  const RadiosityLighting& lighting, const FinalGatherSettings& s,
                                  const GatherGuide* guide) {
  std::optional<SmoothRadiosity> smooth;
  if (s.smooth) smooth.emplace(scene.mesh(), lighting.radiosity, s.smoothing);
  const Gather gather{scene, lighting, smooth, s, guide};
  PixelSampling sampling{s.width, s.height, s.samplesPerPixel, s.seed, 2, s.sampler};
  return renderCameraSamples(
      scene, camera, sampling,
      [&](const Vec3& origin, const Vec3& direction, Sampler& sampler, long long& rays) {
        return gather.radiance(origin, direction, sampler, rays);
      });
}

}  // namespace radkit
