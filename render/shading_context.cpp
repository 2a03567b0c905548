#include "render/shading_context.h"

#include <algorithm>
#include <cmath>

namespace radkit {

std::unique_ptr<Bsdf> makeShadingBsdf(const Material& m, const BsdfSettings& settings, GlossyModel glossy) {
  if (glossy == GlossyModel::Phong && m.brdf == BrdfModel::CookTorrance) {
    // Walter et al. 2007, eq. 35 (Beckmann ↔ Phong), used for GGX: n = 2/α² − 2.
    const double alpha = std::max(m.roughness * m.roughness, 1e-3);
    const Vec3 f0 = m.f0 * (1 - m.metallic) + m.reflectance * m.metallic;
    return makePhongBsdf(m.diffuseAlbedo(), f0, std::max(0.0, 2 / (alpha * alpha) - 2));
  }
  if (glossy == GlossyModel::CookTorrance && m.brdf == BrdfModel::Phong) {
    const double alpha = std::sqrt(2 / (m.shininess + 2));
    return makeCookTorranceBsdf(m.reflectance, 0, std::sqrt(alpha), m.specular, settings);
  }
  return makeBsdf(m, settings);
}

ShadingScene::ShadingScene(const Scene& scene, const PatchMesh& mesh, const Visibility& rays,
                           const BsdfSettings& bsdf, GlossyModel glossy)
    : m_mesh(mesh), m_rays(rays), m_emitters(scene, mesh) {
  for (const Material& m : scene.materials) {
    m_bsdfs.push_back(makeShadingBsdf(m, bsdf, glossy));
    m_twoSided.push_back(m.twoSided);
    m_transmits.push_back(m.brdf == BrdfModel::Glass);
    m_emission.push_back(m.emission);
  }
  for (const Surface& s : scene.surfaces) m_material.push_back(s.material);
}

std::optional<SurfaceHit> ShadingScene::intersect(const Vec3& origin, const Vec3& dir, double tMin) const {
  std::optional<RayHit> ray = m_rays.closestHit(origin, dir, tMin);
  if (!ray) return std::nullopt;
  const Patch& p = m_mesh.patches[ray->patch];
  const int material = m_material[p.surface];
  SurfaceHit hit;
  hit.patch = ray->patch;
  hit.distance = ray->distance;
  hit.point = origin + dir * ray->distance;
  hit.front = dot(dir, p.normal) < 0;
  // Two-sided materials reflect alike on both sides: shade in the frame facing the viewer.
  // Glass keeps the front normal (its BSDF tells inside from outside by the sign of wo.z).
  const bool flip = !hit.front && m_twoSided[material] && !m_transmits[material];
  hit.normal = flip ? -p.normal : p.normal;
  hit.frame = Frame(hit.normal);
  hit.wo = hit.frame.toLocal(-dir);
  if (hit.front || flip || m_transmits[material]) hit.bsdf = m_bsdfs[material].get();
  return hit;
}

Vec3 ShadingScene::emitted(const SurfaceHit& hit) const {
  if (!hit.front) return {};
  // A Lambertian emitter of exitance E has radiance E/π in every direction.
  return m_emission[m_material[m_mesh.patches[hit.patch].surface]] / M_PI;
}

Vec3 ShadingScene::spawn(const SurfaceHit& hit, const Vec3& dir) const {
  return liftToward(hit.point, m_mesh.patches[hit.patch].normal, hit.point + dir, m_rays.epsilon());
}

Vec3 ShadingScene::directLight(const SurfaceHit& hit, Rng& rng, long long& rays) const {
  const double u0 = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
  if (m_emitters.empty() || !hit.bsdf || hit.bsdf->isDelta()) return {};
  const EmitterSample e = m_emitters.sample(u0, u1, u2);
  const Vec3 d = e.point - hit.point;
  const double dist2 = dot(d, d);
  if (!(dist2 > 0)) return {};
  const Vec3 wi = d / std::sqrt(dist2);
  const double cosLight = -dot(wi, e.normal);
  if (cosLight <= 0) return {};
  const Vec3 wiLocal = hit.frame.toLocal(wi);
  const Vec3 f = hit.bsdf->eval(hit.wo, wiLocal);
  if (maxComponent(f) <= 0) return {};
  ++rays;
  if (m_rays.occluded(hit.point, m_mesh.patches[hit.patch].normal, e.point, e.normal)) return {};
  // Area to solid angle: p_ω = p_A r² / cos θ_light (Veach 1997, eq. 8.10).
  const double pdfLight = e.pdfArea * dist2 / cosLight;
  const double weight = powerHeuristic(pdfLight, hit.bsdf->pdf(hit.wo, wiLocal));
  return mul(f, e.emission / M_PI) * (std::fabs(wiLocal.z) * weight / pdfLight);
}

double ShadingScene::lightPdf(const SurfaceHit& light) const {
  if (!light.front) return 0;
  const double cosLight = std::fabs(light.wo.z);
  if (cosLight <= 0) return 0;
  return m_emitters.pdfArea(light.patch) * light.distance * light.distance / cosLight;
}

}  // namespace radkit
