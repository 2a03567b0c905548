#include "photon/tracer.h"

#include <tbb/parallel_for.h>

#include <chrono>
#include <limits>
#include <stdexcept>

#include "geometry/ray_scene.h"
#include "geometry/sampling.h"
#include "geometry/scene_loader.h"
#include "render/shading_context.h"

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

/// Context of one tracing run, shared read-only by every thread.
struct Tracer {
  const ShadingScene& shading;
  const Visibility& rays;
  const EmitterSampler& emitters;
  const PhotonSettings& settings;

  /// Follows photon `index` from its emitter until absorption, escape or the bounce cap.
  /// Every bounce samples the hit's BSDF, whatever its model.
  void trace(std::size_t index, BlockResult& out) const {
    Rng rng(settings.seed, index, 0);
    double u[5];
    for (double& v : u) v = rng.uniform();
    PhotonEmission e =
        samplePhotonEmission(emitters, settings.photons, u[0], u[1], u[2], u[3], u[4]);
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
  // Photons start only from emitting surfaces: under a "sky" the result would silently lack
  // the daylight.
  if (scene.sky)
    throw InputError(scene.file +
                     ": photons do not start from the \"sky\" yet, so photon mapping would "
                     "miss the daylight. Fix: solve daylight with `radkit run` or render it "
                     "with `radkit render --shading path-trace`");
  EmitterSampler emitters(scene, mesh);
  if (emitters.empty())
    throw InputError(scene.file +
                     ": no surface emits, so no photon can start. Fix: give a material an "
                     "\"emission\" above zero");
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
  if (emitters.empty())
    throw std::invalid_argument(
        "the scene has no emitters: photon mapping needs a surface whose material has "
        "\"emission\" > 0");
  if (settings.photons == 0 || settings.photons >= std::numeric_limits<std::uint32_t>::max())
    throw std::invalid_argument("photon count must lie in [1, 2^32 - 1)");
  const auto start = std::chrono::steady_clock::now();
  const ShadingScene shading(scene, mesh, rays, settings.bsdf);
  const Tracer tracer{shading, rays, emitters, settings};
  const std::size_t blocks = (settings.photons + kBlockSize - 1) / kBlockSize;
  std::vector<BlockResult> results(blocks);
  tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t b) {
    BlockResult& out = results[b];
    out.photons.reserve(kBlockSize * 2);
    const std::size_t end = std::min(settings.photons, (b + 1) * kBlockSize);
    for (std::size_t i = b * kBlockSize; i < end; ++i) tracer.trace(i, out);
  });
  // Concatenate in block order: the same photons in the same order for any thread count.
  PhotonTrace trace;
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
