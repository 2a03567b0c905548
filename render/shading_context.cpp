#include "render/shading_context.h"

#include <tbb/parallel_for.h>

#include <chrono>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "render/camera.h"

namespace radkit {

LightSampling parseLightSampling(const std::string& name) {
  if (name == "area") return LightSampling::Area;
  if (name == "solid-angle") return LightSampling::SolidAngle;
  throw std::invalid_argument("unknown light sampling \"" + name + "\" (area or solid-angle)");
}

std::string lightSamplingName(LightSampling sampling) {
  return sampling == LightSampling::SolidAngle ? "solid-angle" : "area";
}

namespace {

/// The glossy lobe of `bsdf` drawn with the model `glossy` asks for, by Walter et al. 2007,
/// eq. 35 (Beckmann ↔ Phong, used for GGX): n = 2/α² − 2 and back, the specular reflectance
/// kept (ks = F0). Nothing when the BSDF has no such lobe or is of that model already.
std::unique_ptr<Bsdf> substitute(const Bsdf& bsdf, GlossyModel glossy,
                                 const BsdfSettings& settings) {
  using Family = Bsdf::GlossyLobe::Family;
  const std::optional<Bsdf::GlossyLobe> lobe = bsdf.glossyLobe();
  if (!lobe) return nullptr;
  if (glossy == GlossyModel::Phong && lobe->family == Family::Microfacet) {
    const double alpha = std::max(lobe->alpha, 1e-3);
    return makePhongBsdf(lobe->diffuse, lobe->specular, std::max(0.0, 2 / (alpha * alpha) - 2));
  }
  if (glossy == GlossyModel::CookTorrance && lobe->family == Family::Phong)
    return makeCookTorranceBsdf(lobe->diffuse, 0, std::sqrt(lobe->alpha), lobe->specular, settings);
  return nullptr;
}

}  // namespace

std::unique_ptr<Bsdf> makeShadingBsdf(const Material& m, const BsdfSettings& settings,
                                      GlossyModel glossy) {
  std::unique_ptr<Bsdf> bsdf = makeBsdf(m.bsdf, m.params, settings);
  std::unique_ptr<Bsdf> other = substitute(*bsdf, glossy, settings);
  return other ? std::move(other) : std::move(bsdf);
}

bool hasGlossyMaterial(const Scene& scene, const BsdfSettings& settings) {
  for (const Surface& s : scene.surfaces) {
    const Material& m = scene.materials[s.material];
    if (makeBsdf(m.bsdf, m.params, settings)->glossyLobe()) return true;
  }
  return false;
}

ShadingScene::ShadingScene(const Scene& scene, const PatchMesh& mesh, const Visibility& rays,
                           const BsdfSettings& bsdf, GlossyModel glossy, LightSampling light)
    : m_mesh(mesh), m_rays(rays), m_emitters(scene, mesh), m_lightSampling(light) {
  for (const Material& m : scene.materials) {
    m_bsdfs.push_back(makeShadingBsdf(m, bsdf, glossy));
    m_twoSided.push_back(m.twoSided);
    m_transmits.push_back(m_bsdfs.back()->transmits());
    m_emission.push_back(m.emission);
  }
  for (const Surface& s : scene.surfaces) m_material.push_back(s.material);
  if (scene.sky) {
    m_sky.emplace(*scene.sky);
    const SkyModel& sky = *m_sky;
    // Below the horizon the sky model gives the ground's glow, which rays also meet there.
    m_skySampler = std::make_unique<SkySampler>([&sky](const Vec3& d) { return sky.radiance(d); });
    if (sky.hasSun() && maxComponent(sky.sunIrradiance()) > 0) {
      // A disc of uniform radiance whose irradiance at normal incidence is E_n (the disc's
      // cos θ across it differs from 1 by < 1e-5 for the real sun).
      // Ω = 2π(1 − cos r) = 4π sin²(r/2), the latter exact for the tiniest discs too.
      const double half = sky.description().sunAngularRadiusDeg * M_PI / 360;
      m_sunSolidAngle = 4 * M_PI * std::sin(half) * std::sin(half);
      m_sunRadiance = sky.sunIrradiance() / m_sunSolidAngle;
    }
  }
}

std::optional<SurfaceHit> ShadingScene::intersect(const Vec3& origin, const Vec3& dir,
                                                  double tMin) const {
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
  return m_emission[m_material[m_mesh.patches[hit.patch].surface]] * (1 / M_PI);
}

Vec3 ShadingScene::spawn(const SurfaceHit& hit, const Vec3& dir) const {
  return liftToward(hit.point, m_mesh.patches[hit.patch].normal, hit.point + dir, m_rays.epsilon());
}

Vec3 ShadingScene::directLight(const SurfaceHit& hit, Sampler& sampler, long long& rays) const {
  const double u0 = sampler.get1DIfUsed(m_emitters.count() > 1);
  const auto [u1, u2] = sampler.get2D();
  if (m_emitters.empty() || !hit.bsdf || hit.bsdf->isDelta()) return {};
  EmitterSample e;
  // The light sample's density per steradian as a ratio, p_L = num/den, so that the estimator
  // below needs one division: by area num = p_A r² and den = cos θ_light (Veach 1997, eq.
  // 8.10); by solid angle num = the emitter's probability and den = Ω.
  double num = 0, den = 0;
  const int patch = m_lightSampling == LightSampling::SolidAngle ? m_emitters.pick(u0) : -1;
  const std::optional<SphericalRectangle> rect =
      patch >= 0 ? solidAngleSampling(patch, hit.point) : std::nullopt;
  if (rect) {
    e.patch = patch;
    e.point = rect->sample(u1, u2);
    e.normal = m_mesh.patches[e.patch].normal;
    e.emission = m_emission[m_material[m_mesh.patches[e.patch].surface]];
    num = m_emitters.probability(e.patch);
    den = rect->solidAngle();
  } else {
    e = m_emitters.sample(u0, u1, u2);
  }
  const Vec3 d = e.point - hit.point;
  const double dist2 = dot(d, d);
  if (!(dist2 > 0)) return {};
  const Vec3 wi = d * (1 / std::sqrt(dist2));
  const double cosLight = -dot(wi, e.normal);
  if (cosLight <= 0) return {};
  if (!rect) num = e.pdfArea * dist2, den = cosLight;
  const Vec3 wiLocal = hit.frame.toLocal(wi);
  const Vec3 f = hit.bsdf->eval(hit.wo, wiLocal);
  if (maxComponent(f) <= 0) return {};
  ++rays;
  if (m_rays.occluded(hit.point, m_mesh.patches[hit.patch].normal, e.point, e.normal)) return {};
  // f·L·cos θ·w/p_L with the power heuristic w = p_L²/(p_L² + p_B²) is f·L·cos θ·p_L/(p_L² +
  // p_B²), which is f·L·cos θ·num·den/(num² + p_B²·den²).
  const double pdfBsdf = hit.bsdf->pdf(hit.wo, wiLocal);
  const double scale =
      std::fabs(wiLocal.z) * num * den / (num * num + pdfBsdf * pdfBsdf * den * den) * (1 / M_PI);
  return mul(f, e.emission) * scale;
}

Vec3 ShadingScene::skyLight(const SurfaceHit& hit, Sampler& sampler, long long& rays) const {
  const double u0 = sampler.get1D();
  const auto [u1, u2] = sampler.get2D();
  const auto [v1, v2] = sampler.get2D();
  if (!m_sky || !hit.bsdf || hit.bsdf->isDelta()) return {};
  Vec3 sum;
  // One direction by the sky's radiance, one in the sun's disc (uniform in its solid angle):
  // each counts only if its ray leaves the scene.
  const auto add = [&](const Vec3& wi, double pdfLight, const Vec3& radiance) {
    const Vec3 wiLocal = hit.frame.toLocal(wi);
    const Vec3 f = hit.bsdf->eval(hit.wo, wiLocal);
    if (maxComponent(f) <= 0 || maxComponent(radiance) <= 0 || !(pdfLight > 0)) return;
    ++rays;
    if (m_rays.closestHit(spawn(hit, wi), wi, 0)) return;
    const double weight = powerHeuristic(pdfLight, hit.bsdf->pdf(hit.wo, wiLocal));
    sum += mul(f, radiance) * (std::fabs(wiLocal.z) * weight / pdfLight);
  };
  double pdfSky;
  const Vec3 wSky = m_skySampler->sample(u0, u1, u2, pdfSky);
  add(wSky, pdfSky, m_sky->radiance(wSky));
  if (m_sunSolidAngle > 0) {
    const Vec3 wSun =
        Frame(m_sky->sunDirection()).toWorld(sampleUniformCone(m_sky->sunCosRadius(), v1, v2));
    add(wSun, 1 / m_sunSolidAngle, m_sunRadiance);
  }
  return sum;
}

Vec3 ShadingScene::escaped(const Vec3& dir, double bsdfPdf, bool specular) const {
  if (!m_sky) return {};
  const Vec3 sky = m_sky->radiance(dir);
  Vec3 l = specular ? sky : sky * powerHeuristic(bsdfPdf, m_skySampler->pdf(dir));
  if (m_sunSolidAngle > 0 && dot(dir, m_sky->sunDirection()) >= m_sky->sunCosRadius())
    l += specular ? m_sunRadiance : m_sunRadiance * powerHeuristic(bsdfPdf, 1 / m_sunSolidAngle);
  return l;
}

double ShadingScene::lightPdf(const SurfaceHit& light, const Vec3& from) const {
  if (!light.front) return 0;
  const double cosLight = std::fabs(light.wo.z);
  if (cosLight <= 0) return 0;
  if (const std::optional<SphericalRectangle> rect = solidAngleSampling(light.patch, from))
    return m_emitters.probability(light.patch) / rect->solidAngle();
  return m_emitters.pdfArea(light.patch) * light.distance * light.distance / cosLight;
}

std::optional<SphericalRectangle> ShadingScene::solidAngleSampling(int patch,
                                                                   const Vec3& from) const {
  Vec3 corner, ex, ey;
  if (m_lightSampling != LightSampling::SolidAngle || !m_emitters.rectangle(patch, corner, ex, ey))
    return std::nullopt;
  SphericalRectangle rect(from, corner, ex, ey);
  if (!(rect.solidAngle() >= kMinSolidAngle)) return std::nullopt;
  return rect;
}

MonteCarloImage renderCameraSamples(const ShadingScene& scene, const Camera& camera,
                                    const PixelSampling& s, const CameraSampleRadiance& radiance) {
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
    std::unique_ptr<Sampler> sampler = makeSampler(s.sampler, s.seed, s.stream, n);
    for (int x = 0; x < s.width; ++x) {
      const std::size_t k = std::size_t(y) * s.width + x;
      Vec3 sum, sumSq;
      for (int i = 0; i < n; ++i) {
        sampler->start(k, i);
        const auto [jx, jy] = sampler->get2D();
        const Vec3 l = radiance(cam.origin(), cam.direction(x + jx, y + jy), *sampler, rowRays[y]);
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
  out.paths = (long long)(n)*s.width * s.height;
  for (long long r : rowRays) out.rays += r;
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace radkit
