#include "photon/image.h"

#include <tbb/parallel_for.h>

#include <cmath>
#include <optional>

#include "geometry/ray_scene.h"
#include "render/camera.h"
#include "render/shading_context.h"
#include "util/sampling.h"

namespace radkit {

namespace {

/// The render samplers' interface over one random stream (ShadingScene's estimators take it).
class RngSampler final : public Sampler {
 public:
  explicit RngSampler(Rng& rng) : m_rng(rng) {}
  void start(std::uint64_t, int) override {}
  double get1D() override { return m_rng.uniform(); }
  std::array<double, 2> get2D() override {
    const double a = m_rng.uniform();
    return {a, m_rng.uniform()};
  }

 private:
  Rng& m_rng;
};

/// The first non-delta point along a ray, after any mirror and glass bounces.
struct ShadedHit {
  SurfaceHit hit;
  Vec3 throughput;  ///< product of the delta lobes' weights on the way
};

class PhotonShader {
 public:
  PhotonShader(const PhotonScene& in, const PhotonSettings& s)
      : m_in(in), m_settings(s), m_shading(in.scene, in.mesh, in.rays, s.bsdf) {}

  /// Follows a ray through delta BSDFs to a hit on a non-delta BSDF. A ray that leaves the
  /// scene sets *escaped (when given) to the daylight it carries: weighted against
  /// skyLight()'s sampling when it left straight from a BSDF sample of density bsdfPdf ≥ 0,
  /// at full weight from the camera or after a mirror.
  std::optional<ShadedHit> findNonDelta(Vec3 origin, Vec3 dir, Rng& rng, Vec3* escaped = nullptr,
                                        double bsdfPdf = -1) const {
    Vec3 throughput{1, 1, 1};
    if (escaped) *escaped = {};
    for (int depth = 0; depth <= m_settings.maxSpecularDepth; ++depth) {
      std::optional<SurfaceHit> hit = m_shading.intersect(origin, dir);
      if (!hit && escaped && m_shading.hasSky()) {
        const bool mis = depth == 0 && bsdfPdf >= 0;
        *escaped = mul(throughput, m_shading.escaped(dir, mis ? bsdfPdf : 0, !mis));
      }
      if (!hit || !hit->bsdf) return std::nullopt;
      if (!hit->bsdf->isDelta()) return ShadedHit{*hit, throughput};
      const double u0 = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
      const std::optional<BsdfSample> s = hit->bsdf->sample(hit->wo, u0, u1, u2);
      if (!s) return std::nullopt;
      throughput = mul(throughput, s->weight);
      dir = hit->frame.toWorld(s->wi);
      origin = m_shading.spawn(*hit, dir);
    }
    return std::nullopt;
  }

  /// Radiance toward the camera at a non-delta hit, for the chosen view.
  Vec3 radiance(const ShadedHit& h, PhotonView view, Rng& rng) const {
    Vec3 l = m_shading.emitted(h.hit);
    if (view == PhotonView::GlobalMap) l += mapRadiance(m_in.global, h.hit);
    if (view == PhotonView::CausticMap || view == PhotonView::FinalGather)
      l += mapRadiance(m_in.caustic, h.hit);
    if (view == PhotonView::FinalGather) l += direct(h.hit, rng) + indirect(h.hit, rng);
    return mul(h.throughput, l);
  }

 private:
  /// Σ_p K(d_p) f(wo, ω_p) ΔΦ_p over the map's k nearest photons.
  Vec3 mapRadiance(const PhotonMap& map, const SurfaceHit& h) const {
    const Bsdf& f = *h.bsdf;
    return map
        .reflected(h.point, h.normal, m_settings.neighbours, m_settings.filter,
                   [&](const Vec3& incoming) { return f.eval(h.wo, h.frame.toLocal(incoming)); })
        .irradiance;
  }

  /// L_direct = ∫_emitters f L_e cos θ_x cos θ_e V / d² dA, estimated with M emitter samples
  /// of density p_A: (1/M) Σ f (E/π) cos θ_x cos θ_e V / (d² p_A).
  /// Under a "sky", each sample also estimates the sky and the sun (ShadingScene::skyLight,
  /// MIS against the gather rays, which take the other half where they leave the scene).
  Vec3 direct(const SurfaceHit& h, Rng& rng) const {
    const int count = m_settings.directRays;
    const Vec3 n = h.frame.n;
    Vec3 sum;
    for (int s = 0; s < count; ++s) {
      if (m_shading.hasSky()) {
        RngSampler sampler(rng);
        long long rays = 0;
        sum += m_shading.skyLight(h, sampler, rays);
      }
      if (m_in.emitters.empty()) continue;
      const double u0 = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
      EmitterSample e = m_in.emitters.sample(u0, u1, u2);
      const Vec3 d = e.point - h.point;
      const double dist2 = dot(d, d);
      const Vec3 w = d / std::sqrt(dist2);
      const double cosX = dot(n, w), cosE = -dot(e.normal, w);
      if (cosX <= 0 || cosE <= 0) continue;
      const Vec3 f = h.bsdf->eval(h.wo, h.frame.toLocal(w));
      if (maxComponent(f) <= 0) continue;
      if (m_in.rays.occluded(h.point, n, e.point, e.normal)) continue;
      sum += mul(f, e.emission) * (cosX * cosE / (M_PI * dist2 * e.pdfArea));
    }
    return count > 0 ? sum / count : Vec3{};
  }

  /// L_indirect = ∫ f L_r cos θ dω ≈ (1/K) Σ w_k L_r(y_k), rays drawn from the BSDF with
  /// weights w = f cos θ / pdf (ρ for a Lambertian surface). L_r(y) is y's reflected radiance
  /// from the global map only: emission reaches x through direct() or, via mirrors and glass,
  /// through the caustic map. Lambertian y read the precomputed irradiance when present.
  Vec3 indirect(const SurfaceHit& h, Rng& rng) const {
    const int count = m_settings.gatherRays;
    Vec3 sum;
    for (int g = 0; g < count; ++g) {
      const double u0 = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
      const std::optional<BsdfSample> s = h.bsdf->sample(h.wo, u0, u1, u2);
      if (!s || s->delta) continue;  // delta lobes of a mixed BSDF: light left to the maps
      const Vec3 dir = h.frame.toWorld(s->wi);
      Vec3 escaped;
      std::optional<ShadedHit> y =
          findNonDelta(m_shading.spawn(h, dir), dir, rng, &escaped, s->pdf);
      if (!y) {
        sum += mul(s->weight, escaped);
        continue;
      }
      const SurfaceHit& yh = y->hit;
      Vec3 ly;
      if (yh.bsdf->lambertian() && m_in.global.hasPrecomputed())
        ly = mul(yh.bsdf->diffuseAlbedo(), m_in.global.precomputedIrradiance(yh.point, yh.normal)) /
             M_PI;
      else
        ly = mapRadiance(m_in.global, yh);
      sum += mul(s->weight, mul(y->throughput, ly));
    }
    return count > 0 ? sum / count : Vec3{};
  }

  const PhotonScene& m_in;
  const PhotonSettings& m_settings;
  ShadingScene m_shading;
};

}  // namespace

const char* viewName(PhotonView view) {
  switch (view) {
    case PhotonView::FinalGather:
      return "gather";
    case PhotonView::GlobalMap:
      return "map";
    case PhotonView::CausticMap:
      return "caustic";
  }
  return "?";
}

RadianceImage renderPhotonImage(const PhotonScene& in, const Camera& camera, int width, int height,
                                PhotonView view, const PhotonSettings& settings) {
  const PinholeCamera cam(camera, width, height);
  const PhotonShader shader(in, settings);
  RadianceImage img;
  img.width = width;
  img.height = height;
  img.radiance.assign(std::size_t(width) * height, Vec3{});
  img.patch.assign(std::size_t(width) * height, -1);
  tbb::parallel_for(0, height, [&](int y) {
    for (int x = 0; x < width; ++x) {
      const std::size_t pixel = std::size_t(y) * width + x;
      Rng rng(settings.seed, pixel, 1);
      const double jx = rng.uniform(), jy = rng.uniform();
      const Vec3 dir = cam.direction(x + jx, y + jy);
      if (auto first = in.rays.closestHit(cam.origin(), dir, 0)) img.patch[pixel] = first->patch;
      Vec3 sky;  // what a camera ray that leaves the scene sees
      std::optional<ShadedHit> h = shader.findNonDelta(cam.origin(), dir, rng, &sky);
      img.radiance[pixel] = h ? shader.radiance(*h, view, rng) : sky;
    }
  });
  return img;
}

double photonImageExposure(const PhotonScene& in, const RadianceImage& image) {
  return autoExposure(image, in.scene, in.mesh);
}

}  // namespace radkit
