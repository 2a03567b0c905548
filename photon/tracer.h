// Photon tracing (Jensen 1996; Jensen 2001, ch. 5): photons leave the emitters in proportion
// to emitted power, are stored at every hit on a non-delta BSDF with their incoming direction,
// and scatter by sampling the hit's BSDF (mirrors, glass, glossy and diffuse lobes alike);
// Russian roulette on the sampled weight ends their paths.
#pragma once

#include <cstdint>
#include <vector>

#include "bsdf/bsdf.h"
#include "geometry/patch_mesh.h"
#include "geometry/scene.h"
#include "geometry/visibility.h"
#include "photon/map.h"
#include "render/emitters.h"
#include "util/errors.h"

namespace radkit {

/// Every setting of a photon-mapping run: tracing, estimates and images.
struct PhotonSettings {
  std::size_t photons = 200000;  ///< photons emitted (paths), >= 1
  std::uint64_t seed = 1;        ///< photon i uses the random stream (seed, i, 0)
  int maxBounces = 256;          ///< path length cap (a hall of mirrors never absorbs)
  int neighbours = 100;          ///< k of the k-nearest-photon irradiance estimate
  IrradianceFilter filter = IrradianceFilter::Epanechnikov;
  int gatherRays = 64;        ///< final-gathering rays per pixel; 0 shows the map directly
  int directRays = 4;         ///< shadow rays per pixel toward the emitters (final gathering)
  int precomputeStride = 4;   ///< irradiance precomputed at every n-th photon for gathering
  int maxSpecularDepth = 16;  ///< mirror/glass bounces followed by camera and gather rays
  BsdfSettings bsdf;          ///< how the materials' BSDFs are built (Cook-Torrance's G)
};

/// Counts of one tracing run.
struct PhotonTraceStats {
  std::size_t emitted = 0;    ///< paths started
  std::size_t stored = 0;     ///< photons stored (diffuse hits)
  std::size_t caustic = 0;    ///< of which L S+ D (the caustic map)
  std::size_t escaped = 0;    ///< paths that left the scene
  std::size_t absorbed = 0;   ///< paths ended by Russian roulette or a back face
  std::size_t truncated = 0;  ///< paths cut at maxBounces
  std::size_t rays = 0;       ///< closest-hit queries
  double seconds = 0;
};

/// All diffuse hits, ordered by path index (so per-path sums are contiguous runs).
struct PhotonTrace {
  std::vector<Photon> photons;
  Vec3 emittedPower;  ///< Σ of the emitted photons' powers (double), scene units² · W/m²
  /// The power the sources send: the emitters' plus, under a "sky", the sky's and the sun's
  /// through the windows photons start from (∫ L(ω) A(ω) dω by quadrature, and E_n A(ω_sun));
  /// emittedPower's expectation.
  Vec3 sourcePower;
  Vec3 skyPower;  ///< of which the sky and the sun (0 without a "sky")
  PhotonTraceStats stats;
};

/// A photon leaving an emitter.
struct PhotonEmission {
  int patch = -1;
  Vec3 origin, normal, direction;
  Vec3 power;  ///< scene units² · W/m² per channel
};

/// \brief Samples photon `index`'s start: a point on an emitter chosen in proportion to
/// power (EmitterSampler, u0..u2) and a cosine-distributed direction about its front normal
/// (u3, u4). Power = E/(N · p_A): with L_e = E/π and p_ω = cos θ/π the weight
/// L_e cos θ/(N p_A p_ω) reduces to this, which is totalPower/N exactly when every emitter
/// has the same colour (then p_A = Y(E)/Σ A Y(E)). Requires !emitters.empty().
PhotonEmission samplePhotonEmission(const EmitterSampler& emitters, std::size_t photons, double u0,
                                    double u1, double u2, double u3, double u4);
/// \brief Density of samplePhotonEmission per unit area and steradian: p_A(patch) · cos θ/π.
double photonEmissionPdf(const EmitterSampler& emitters, int patch, const Vec3& normal,
                         const Vec3& direction);

/// \brief The emitting surfaces photons start from (empty for a scene lit only by its "sky").
/// \throws InputError naming the scene file when no surface emits and there is no sky.
EmitterSampler photonEmitters(const Scene& scene, const PatchMesh& mesh);

/// \brief Traces settings.photons paths in parallel (TBB) over blocks of photons; the result
/// depends only on the scene and the settings, not on the thread count.
/// Under a "sky", photons also start from the sky and the sun's disc: from the rectangle, across
/// the direction they come from, that the scene's bounding box projects to, the directions
/// drawn by the sky's radiance (SkySampler) or uniform in the sun's disc; each source gets
/// photons in proportion to its power. Throws std::invalid_argument when the scene has no emitters
/// and no sky, or photons is 0 or ≥ 2³².
PhotonTrace tracePhotons(const Scene& scene, const PatchMesh& mesh, const Visibility& rays,
                         const EmitterSampler& emitters, const PhotonSettings& settings);

}  // namespace radkit
