#include "render/photon_tracer.h"

#include <tbb/parallel_for.h>

#include <chrono>
#include <limits>
#include <stdexcept>

#include "geometry/ray_scene.h"
#include "geometry/sampling.h"
#include "render/specular.h"

namespace radkit {

namespace {

/// Photons per block: the unit of parallel work, and of deterministic concatenation.
constexpr std::size_t kBlockSize = 4096;

struct BlockResult {
  std::vector<Photon> photons;
  Vec3 emittedPower;
  PhotonTraceStats stats;
};

Photon makePhoton(const Vec3& x, const Vec3& power, int patch, std::size_t path, bool caustic) {
  Photon p;
  for (int c = 0; c < 3; ++c) {
    p.position[c] = float(x[c]);
    p.power[c] = float(power[c]);
  }
  p.patch = patch;
  p.path = std::uint32_t(path);
  p.caustic = caustic;
  return p;
}

/// Context of one tracing run, shared read-only by every thread.
struct Tracer {
  const PatchMesh& mesh;
  const Visibility& rays;
  const EmitterSampler& emitters;
  const PhotonSettings& settings;
  std::vector<const Material*> materials;

  /// Follows photon `index` from its emitter until absorption, escape or the bounce cap.
  void trace(std::size_t index, BlockResult& out) const {
    Rng rng(settings.seed, index, 0);
    double u[5];
    for (double& v : u) v = rng.uniform();
    PhotonEmission e = samplePhotonEmission(emitters, settings.photons, u[0], u[1], u[2], u[3], u[4]);
    out.emittedPower += e.power;
    ++out.stats.emitted;
    const double eps = rays.epsilon();
    Vec3 origin = e.origin + e.normal * eps, dir = e.direction, power = e.power;
    bool specularOnly = true;  // no diffuse bounce yet
    bool sawSpecular = false;
    for (int bounce = 0; bounce < settings.maxBounces; ++bounce) {
      ++out.stats.rays;
      std::optional<RayHit> hit = rays.closestHit(origin, dir, 0);
      if (!hit) {
        ++out.stats.escaped;
        return;
      }
      const Patch& patch = mesh.patches[hit->patch];
      const Material& m = *materials[hit->patch];
      const Vec3 x = origin + dir * hit->distance;
      const bool front = dot(dir, patch.normal) < 0;
      if (m.isSpecular()) {
        Vec3 weight{1, 1, 1};
        if (!scatterSpecular(m, patch.normal, rng.uniform(), dir, weight)) {
          ++out.stats.absorbed;
          return;
        }
        power = mul(power, weight);
        sawSpecular = true;
      } else {
        if (!front && !m.twoSided) {  // only the front side reflects (docs/formats.md)
          ++out.stats.absorbed;
          return;
        }
        const bool caustic = specularOnly && sawSpecular;
        out.photons.push_back(makePhoton(x, power, hit->patch, index, caustic));
        ++out.stats.stored;
        if (caustic) ++out.stats.caustic;
        // Russian roulette (Jensen 2001, §5.2): survive with p = max_c ρ_c and carry
        // Φ ρ/p, so every channel's expected reflected power is ρ_c Φ_c and none grows.
        const Vec3 rho = m.diffuseAlbedo();
        const double p = maxComponent(rho);
        if (!(rng.uniform() < p)) {
          ++out.stats.absorbed;
          return;
        }
        power = mul(power, rho) / p;
        const Frame frame(front ? patch.normal : -patch.normal);
        const double u0 = rng.uniform(), u1 = rng.uniform();
        dir = frame.toWorld(sampleCosineHemisphere(u0, u1));  // pdf cos θ/π: Lambertian
        specularOnly = false;
      }
      origin = liftToward(x, patch.normal, x + dir, eps);
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

std::vector<const Material*> patchMaterials(const Scene& scene, const PatchMesh& mesh) {
  std::vector<const Material*> m(mesh.size());
  for (int i = 0; i < mesh.size(); ++i)
    m[i] = &scene.materials[scene.surfaces[mesh.patches[i].surface].material];
  return m;
}

PhotonEmission samplePhotonEmission(const EmitterSampler& emitters, std::size_t photons, double u0, double u1,
                                    double u2, double u3, double u4) {
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

double photonEmissionPdf(const EmitterSampler& emitters, int patch, const Vec3& normal, const Vec3& direction) {
  return emitters.pdfArea(patch) * cosineHemispherePdf(Frame(normal).toLocal(direction));
}

bool scatterSpecular(const Material& m, const Vec3& n, double u, Vec3& direction, Vec3& weight) {
  const Vec3 wo = -direction;  // toward where the photon came from
  const double cosO = dot(wo, n);
  const bool front = cosO > 0;
  const Vec3 side = front ? n : -n;  // the normal on the photon's side
  if (m.brdf == BrdfModel::Mirror) {
    if (!front && !m.twoSided) return false;
    direction = reflect(wo, side);
    weight = m.specular;
    return true;
  }
  // Glass: the front side faces index 1. Reflect with probability F, else refract; the
  // ratio F/F (or (1−F)/(1−F)) leaves the weight at one (Jensen 2001, §5.2).
  const double eta = front ? m.ior : 1 / m.ior;  // n_transmitted / n_incident
  const double f = fresnelDielectric(cosO, m.ior);
  Vec3 transmitted;
  if (u < f || !refract(wo, side, eta, transmitted)) direction = reflect(wo, side);
  else direction = transmitted;
  weight = {1, 1, 1};
  return true;
}

PhotonTrace tracePhotons(const Scene& scene, const PatchMesh& mesh, const Visibility& rays,
                         const EmitterSampler& emitters, const PhotonSettings& settings) {
  if (emitters.empty())
    throw std::invalid_argument("the scene has no emitters: photon mapping needs a surface whose material has "
                                "\"emission\" > 0");
  if (settings.photons == 0 || settings.photons >= std::numeric_limits<std::uint32_t>::max())
    throw std::invalid_argument("photon count must lie in [1, 2^32 - 1)");
  const auto start = std::chrono::steady_clock::now();
  const Tracer tracer{mesh, rays, emitters, settings, patchMaterials(scene, mesh)};
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
  trace.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return trace;
}

}  // namespace radkit
