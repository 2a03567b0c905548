#include "photon/tracer.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include "daylight/sky.h"
#include "geometry/ray_scene.h"
#include "render/shading_context.h"
#include "util/errors.h"
#include "util/sampling.h"

namespace radkit {

namespace {

/// Photons per block: the unit of parallel work, and of deterministic concatenation.
constexpr std::size_t kBlockSize = 4096;

struct BlockResult {
  std::vector<Photon> photons;
  Vec3 emittedPower;
  PhotonTraceStats stats;
};

Photon makePhoton(const Vec3& x, const Vec3& power, const Vec3& incoming, int patch,
                  std::size_t path, bool caustic) {
  Photon p;
  for (int c = 0; c < 3; ++c) {
    p.position[c] = float(x[c]);
    p.power[c] = float(power[c]);
  }
  p.setIncoming(incoming);
  p.patch = patch;
  p.path = std::uint32_t(path);
  p.caustic = caustic;
  return p;
}

/// Photons from a scene's sky and sun. A photon coming from direction ω starts on the
/// rectangle, across ω and R beyond the scene's centre (R its bounding-sphere radius), that
/// the scene's bounding box projects to, so every ray along −ω that can meet the scene crosses
/// it; it travels along −ω. A direction of density p_ω and a uniform point of the rectangle
/// (area A(ω)) carry Φ = L(ω) A(ω) / p_ω (the sun: E_n A(ω)), before dividing by the photons
/// allotted.
class SkySource {
 public:
  /// The sky and sampler the tracing's ShadingScene built (a physical sky's table is costly).
  SkySource(const SkyModel& sky, const SkySampler& sampler, const PatchMesh& mesh)
      : m_sky(sky), m_sampler(sampler) {
    Bounds3 b;
    for (const Vec3& v : mesh.vertices) b.extend(v);
    m_centre = (b.lo + b.hi) * 0.5;
    m_radius = 0.5 * length(b.hi - b.lo) * 1.01 + 1e-9;
    for (int k = 0; k < 8; ++k)
      m_corners[k] =
          Vec3{k & 1 ? b.hi.x : b.lo.x, k & 2 ? b.hi.y : b.lo.y, k & 4 ? b.hi.z : b.lo.z} -
          m_centre;
    // ∫ L(ω) A(ω) dω by the midpoint rule on 128 × 256 equal-area cells: each source's share
    // of the photons (their powers are exact whatever the shares).
    const int rows = 128, cols = 256;
    Vec3 integral;
    for (int r = 0; r < rows; ++r)
      for (int c = 0; c < cols; ++c) {
        const Vec3 w = localDirection(1 - 2 * (r + 0.5) / rows, 2 * kPi * (c + 0.5) / cols);
        integral += m_sky.radiance(w) * window(Frame(w)).area();
      }
    m_skyPower = integral * (4 * kPi / (double(rows) * cols));
    if (m_sky.hasSun())
      m_sunPower = m_sky.sunIrradiance() * window(Frame(m_sky.sunDirection())).area();
  }
  Vec3 skyPower() const { return m_skyPower; }
  Vec3 sunPower() const { return m_sunPower; }

  /// A photon from the sky (sun = false) or the sun's disc, its power before allotment.
  PhotonEmission emit(bool sun, double u0, double u1, double u2, double u3, double u4) const {
    Vec3 omega, radiancePerPdf;
    if (sun) {
      omega = Frame(m_sky.sunDirection()).toWorld(sampleUniformCone(m_sky.sunCosRadius(), u0, u1));
      radiancePerPdf = m_sky.sunIrradiance();  // (E_n/Ω) / (1/Ω)
    } else {
      double pdf;
      omega = m_sampler.sample(u0, u1, u2, pdf);
      radiancePerPdf = pdf > 0 ? m_sky.radiance(omega) / pdf : Vec3{};
    }
    const Frame frame(omega);
    const Window w = window(frame);
    PhotonEmission e;
    e.origin = m_centre + omega * m_radius +
               frame.toWorld(Vec3{w.x0 + u3 * (w.x1 - w.x0), w.y0 + u4 * (w.y1 - w.y0), 0});
    e.direction = e.normal = -omega;
    e.power = radiancePerPdf * w.area();
    return e;
  }

 private:
  struct Window {
    double x0 = 0, x1 = 0, y0 = 0, y1 = 0;
    double area() const { return (x1 - x0) * (y1 - y0); }
  };
  /// The bounding box's projection on the plane across frame.n, in the frame's (s, t).
  Window window(const Frame& frame) const {
    Window w{INFINITY, -INFINITY, INFINITY, -INFINITY};
    for (const Vec3& c : m_corners) {
      const Vec3 l = frame.toLocal(c);
      w.x0 = std::min(w.x0, l.x), w.x1 = std::max(w.x1, l.x);
      w.y0 = std::min(w.y0, l.y), w.y1 = std::max(w.y1, l.y);
    }
    return w;
  }

  const SkyModel& m_sky;
  const SkySampler& m_sampler;
  Vec3 m_centre, m_corners[8];
  double m_radius = 0;
  Vec3 m_skyPower, m_sunPower;
};

/// Context of one tracing run, shared read-only by every thread.
struct Tracer {
  const ShadingScene& shading;
  const Visibility& rays;
  const EmitterSampler& emitters;
  const PhotonSettings& settings;
  const SkySource* sky;  ///< null without a "sky"
  /// Chances a photon starts from the emitting surfaces, the sky, the sun (sum 1).
  double pSurfaces = 1, pSky = 0, pSun = 0;

  /// Follows photon `index` from its emitter until absorption, escape or the bounce cap.
  /// Every bounce samples the hit's BSDF, whatever its model.
  void trace(std::size_t index, BlockResult& out) const {
    Rng rng(settings.seed, index, 0);
    double u[5];
    for (double& v : u) v = rng.uniform();
    PhotonEmission e;
    if (sky) {
      // The source by its share of the power; the photon's power divided by that chance.
      const double pick = rng.uniform();
      const double n = double(settings.photons);
      if (pick < pSurfaces) {
        e = samplePhotonEmission(emitters, settings.photons, u[0], u[1], u[2], u[3], u[4]);
        e.power = e.power / pSurfaces;
      } else {
        const bool sun = pSun > 0 && (pick >= pSurfaces + pSky || !(pSky > 0));
        e = sky->emit(sun, u[0], u[1], u[2], u[3], u[4]);
        e.power = e.power / (n * (sun ? pSun : pSky));
      }
    } else {
      e = samplePhotonEmission(emitters, settings.photons, u[0], u[1], u[2], u[3], u[4]);
    }
    out.emittedPower += e.power;
    ++out.stats.emitted;
    Vec3 origin = e.origin + e.normal * rays.epsilon(), dir = e.direction, power = e.power;
    bool specularOnly = true;  // no non-delta bounce yet
    bool sawSpecular = false;
    for (int bounce = 0; bounce < settings.maxBounces; ++bounce) {
      ++out.stats.rays;
      std::optional<SurfaceHit> hit = shading.intersect(origin, dir);
      if (!hit) {
        ++out.stats.escaped;
        return;
      }
      if (!hit->bsdf) {  // only the front of a one-sided surface reflects (docs/formats.md)
        ++out.stats.absorbed;
        return;
      }
      const Bsdf& bsdf = *hit->bsdf;
      if (!bsdf.isDelta()) {
        const bool caustic = specularOnly && sawSpecular;
        out.photons.push_back(makePhoton(hit->point, power, -dir, hit->patch, index, caustic));
        ++out.stats.stored;
        if (caustic) ++out.stats.caustic;
      }
      const double u0 = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
      const std::optional<BsdfSample> s = bsdf.sample(hit->wo, u0, u1, u2);
      if (!s) {
        ++out.stats.absorbed;
        return;
      }
      // Power is not radiance: the 1/η² of refraction does not apply to it (Veach 1997, §5.2).
      const Vec3 weight = s->weight / s->radianceScale;
      // Russian roulette (Jensen 2001, §5.2): survive with p = min(1, max_c weight_c) and
      // carry Φ·weight/p, so every channel's expected power is Φ_c·weight_c and none grows
      // where the BSDF absorbs (p = max_c ρ_c for a Lambertian surface).
      const double p = std::min(1.0, maxComponent(weight));
      if (p < 1 && !(rng.uniform() < p)) {
        ++out.stats.absorbed;
        return;
      }
      power = mul(power, weight) / p;
      if (s->delta)
        sawSpecular = true;
      else
        specularOnly = false;
      dir = hit->frame.toWorld(s->wi);
      origin = shading.spawn(*hit, dir);
    }
    ++out.stats.truncated;
  }
};

void addStats(PhotonTraceStats& a, const PhotonTraceStats& b) {
  a.emitted += b.emitted;
  a.stored += b.stored;
  a.caustic += b.caustic;
  a.escaped += b.escaped;
  a.absorbed += b.absorbed;
  a.truncated += b.truncated;
  a.rays += b.rays;
}

}  // namespace

EmitterSampler photonEmitters(const Scene& scene, const PatchMesh& mesh) {
  EmitterSampler emitters(scene, mesh);
  if (emitters.empty() && !scene.sky)
    throw InputError(scene.file +
                     ": no surface emits and there is no \"sky\", so no photon can start. "
                     "Fix: give a material an \"emission\" above zero, or the scene a \"sky\"");
  return emitters;
}

PhotonEmission samplePhotonEmission(const EmitterSampler& emitters, std::size_t photons, double u0,
                                    double u1, double u2, double u3, double u4) {
  EmitterSample s = emitters.sample(u0, u1, u2);
  PhotonEmission e;
  e.patch = s.patch;
  e.origin = s.point;
  e.normal = s.normal;
  e.direction = Frame(s.normal).toWorld(sampleCosineHemisphere(u3, u4));
  // Φ = L_e cos θ / (N p_A p_ω) with L_e = E/π and p_ω = cos θ/π: E/(N p_A).
  e.power = s.emission / (double(photons) * s.pdfArea);
  return e;
}

double photonEmissionPdf(const EmitterSampler& emitters, int patch, const Vec3& normal,
                         const Vec3& direction) {
  return emitters.pdfArea(patch) * cosineHemispherePdf(Frame(normal).toLocal(direction));
}

PhotonTrace tracePhotons(const Scene& scene, const PatchMesh& mesh, const Visibility& rays,
                         const EmitterSampler& emitters, const PhotonSettings& settings) {
  if (emitters.empty() && !scene.sky)
    throw std::invalid_argument(
        "the scene has no emitters and no sky: photon mapping needs a surface whose material "
        "has \"emission\" > 0, or a \"sky\"");
  if (settings.photons == 0 || settings.photons >= std::numeric_limits<std::uint32_t>::max())
    throw std::invalid_argument("photon count must lie in [1, 2^32 - 1)");
  const auto start = std::chrono::steady_clock::now();
  const ShadingScene shading(scene, mesh, rays, settings.bsdf);
  std::optional<SkySource> sky;
  Tracer tracer{shading, rays, emitters, settings, nullptr};
  PhotonTrace trace;
  trace.sourcePower = emitters.empty() ? Vec3{} : emitters.totalPower();
  if (shading.sky()) {
    sky.emplace(*shading.sky(), *shading.skySampler(), mesh);
    tracer.sky = &*sky;
    trace.skyPower = sky->skyPower() + sky->sunPower();
    trace.sourcePower += trace.skyPower;
    // Shares by the channels' mean power.
    const auto mean = [](const Vec3& v) { return (v.x + v.y + v.z) / 3; };
    const double total = mean(trace.sourcePower);
    if (!(total > 0))
      throw std::invalid_argument(scene.file + ": neither the emitters nor the sky send any light");
    tracer.pSky = mean(sky->skyPower()) / total;
    tracer.pSun = mean(sky->sunPower()) / total;
    tracer.pSurfaces = emitters.empty() ? 0.0 : 1 - tracer.pSky - tracer.pSun;
  }
  const std::size_t blocks = (settings.photons + kBlockSize - 1) / kBlockSize;
  std::vector<BlockResult> results(blocks);
  tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t b) {
    BlockResult& out = results[b];
    out.photons.reserve(kBlockSize * 2);
    const std::size_t end = std::min(settings.photons, (b + 1) * kBlockSize);
    for (std::size_t i = b * kBlockSize; i < end; ++i) tracer.trace(i, out);
  });
  // Concatenate in block order: the same photons in the same order for any thread count.
  std::size_t total = 0;
  for (const BlockResult& r : results) total += r.photons.size();
  trace.photons.reserve(total);
  for (BlockResult& r : results) {
    trace.photons.insert(trace.photons.end(), r.photons.begin(), r.photons.end());
    trace.emittedPower += r.emittedPower;
    addStats(trace.stats, r.stats);
    std::vector<Photon>().swap(r.photons);
  }
  trace.stats.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return trace;
}

}  // namespace radkit
