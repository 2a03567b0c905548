#include "render/photon_image.h"

#include <tbb/parallel_for.h>

#include <cmath>
#include <optional>

#include "geometry/ray_scene.h"
#include "geometry/sampling.h"
#include "render/camera.h"

namespace radkit {

namespace {

/// The first diffuse point along a ray, after any mirror and glass bounces.
struct DiffuseHit {
  Vec3 x, n;          ///< point and the normal on the side the ray arrived from
  int patch = -1;
  Vec3 throughput;    ///< product of the specular weights on the way
  int specularBounces = 0;
};

class PhotonShader {
 public:
  PhotonShader(const PhotonScene& in, const PhotonSettings& s)
      : m_in(in), m_settings(s), m_materials(patchMaterials(in.scene, in.mesh)) {}

  /// Follows a ray through specular surfaces to a diffuse front side (or two-sided) hit.
  std::optional<DiffuseHit> findDiffuse(Vec3 origin, Vec3 dir, Rng& rng) const {
    DiffuseHit h;
    h.throughput = {1, 1, 1};
    const double eps = m_in.rays.epsilon();
    for (int depth = 0; depth <= m_settings.maxSpecularDepth; ++depth) {
      std::optional<RayHit> hit = m_in.rays.closestHit(origin, dir, 0);
      if (!hit) return std::nullopt;
      const Patch& p = m_in.mesh.patches[hit->patch];
      const Material& m = *m_materials[hit->patch];
      const Vec3 x = origin + dir * hit->distance;
      const bool front = dot(dir, p.normal) < 0;
      if (!m.isSpecular()) {
        if (!front && !m.twoSided) return std::nullopt;
        h.x = x;
        h.n = front ? p.normal : -p.normal;
        h.patch = hit->patch;
        return h;
      }
      Vec3 weight;
      if (!scatterSpecular(m, p.normal, rng.uniform(), dir, weight)) return std::nullopt;
      h.throughput = mul(h.throughput, weight);
      ++h.specularBounces;
      origin = liftToward(x, p.normal, x + dir, eps);
    }
    return std::nullopt;
  }

  /// Radiance toward the camera at a diffuse hit, for the chosen view.
  Vec3 radiance(const DiffuseHit& h, PhotonView view, Rng& rng) const {
    const Material& m = *m_materials[h.patch];
    const Vec3 rho = m.diffuseAlbedo();
    Vec3 irradiance;
    const int k = m_settings.neighbours;
    if (view == PhotonView::GlobalMap) irradiance = m_in.global.irradiance(h.x, h.n, k, m_settings.filter).irradiance;
    if (view == PhotonView::CausticMap || view == PhotonView::FinalGather)
      irradiance = m_in.caustic.irradiance(h.x, h.n, k, m_settings.filter).irradiance;
    if (view == PhotonView::FinalGather) irradiance += direct(h, rng) + indirect(h, rng);
    return mul(h.throughput, m.emission / M_PI + mul(rho, irradiance) / M_PI);
  }

 private:
  /// H_direct = ∫_emitters L_e cos θ_x cos θ_e V / d² dA, estimated with M emitter samples
  /// of density p_A: (1/M) Σ (E/π) cos θ_x cos θ_e V / (d² p_A).
  Vec3 direct(const DiffuseHit& h, Rng& rng) const {
    const int count = m_settings.directRays;
    Vec3 sum;
    for (int s = 0; s < count; ++s) {
      const double u0 = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
      EmitterSample e = m_in.emitters.sample(u0, u1, u2);
      const Vec3 d = e.point - h.x;
      const double dist2 = dot(d, d);
      const Vec3 w = d / std::sqrt(dist2);
      const double cosX = dot(h.n, w), cosE = -dot(e.normal, w);
      if (cosX <= 0 || cosE <= 0) continue;
      if (m_in.rays.occluded(h.x, h.n, e.point, e.normal)) continue;
      sum += e.emission * (cosX * cosE / (M_PI * dist2 * e.pdfArea));
    }
    return count > 0 ? sum / count : Vec3{};
  }

  /// H_indirect = ∫ L_r cos θ dω ≈ (π/K) Σ L_r(y_k) with cosine-distributed rays (pdf cos θ/π);
  /// L_r(y) = ρ_y H_global(y)/π is the reflected radiance only: emission reaches x through
  /// direct() or, via mirrors and glass, through the caustic map.
  Vec3 indirect(const DiffuseHit& h, Rng& rng) const {
    const int count = m_settings.gatherRays;
    const Frame frame(h.n);
    const Vec3 origin = h.x + h.n * m_in.rays.epsilon();
    Vec3 sum;
    for (int g = 0; g < count; ++g) {
      const double u0 = rng.uniform(), u1 = rng.uniform();
      std::optional<DiffuseHit> y = findDiffuse(origin, frame.toWorld(sampleCosineHemisphere(u0, u1)), rng);
      if (!y) continue;
      const Vec3 hy = m_in.global.hasPrecomputed()
                          ? m_in.global.precomputedIrradiance(y->x, y->n)
                          : m_in.global.irradiance(y->x, y->n, m_settings.neighbours, m_settings.filter).irradiance;
      sum += mul(y->throughput, mul(m_materials[y->patch]->diffuseAlbedo(), hy));  // π · L_r(y)
    }
    return count > 0 ? sum / count : Vec3{};
  }

  const PhotonScene& m_in;
  const PhotonSettings& m_settings;
  std::vector<const Material*> m_materials;
};

}  // namespace

const char* viewName(PhotonView view) {
  switch (view) {
    case PhotonView::FinalGather: return "gather";
    case PhotonView::GlobalMap: return "map";
    case PhotonView::CausticMap: return "caustic";
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
      std::optional<DiffuseHit> h = shader.findDiffuse(cam.origin(), dir, rng);
      if (h) img.radiance[pixel] = shader.radiance(*h, view, rng);
    }
  });
  return img;
}

double photonImageExposure(const PhotonScene& in, const RadianceImage& image) {
  return autoExposure(image, in.scene, in.mesh);
}

}  // namespace radkit
