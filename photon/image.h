// Camera images from photon maps: final gathering (Jensen 1996, §3.3; Jensen 2001, ch. 9)
// and the direct visualisation of the global and caustic maps.
#pragma once

#include "geometry/patch_mesh.h"
#include "geometry/scene.h"
#include "geometry/visibility.h"
#include "photon/map.h"
#include "photon/tracer.h"
#include "render/emitters.h"
#include "render/radiosity_image.h"

namespace radkit {

/// What a photon image shows at the first non-delta point x a camera ray reaches (through
/// mirrors and glass), with f its BSDF and E its emission; on a Lambertian surface f = ρ/π
/// and each photon sum is ρ/π times an irradiance estimate:
enum class PhotonView {
  /// L = E/π + L_direct + L_caustic + L_indirect: direct light by shadow rays toward the
  /// emitters weighted by f, caustics from the caustic map, indirect light by K gather rays
  /// drawn from the BSDF that read the global map's reflected radiance where they land.
  FinalGather,
  /// L = E/π + Σ_global f ΔΦ K: the global map's k-nearest estimate at x, no gathering.
  GlobalMap,
  /// L = E/π + Σ_caustic f ΔΦ K: only light that reached x through mirrors or glass.
  CausticMap,
};

const char* viewName(PhotonView view);

/// What a photon image reads; everything must outlive the call.
struct PhotonScene {
  const Scene& scene;
  const PatchMesh& mesh;
  const Visibility& rays;
  const EmitterSampler& emitters;
  const PhotonMap& global;
  const PhotonMap& caustic;
};

/// \brief Renders one jittered camera ray per pixel (stream (seed, pixel, 1)); parallel over
/// rows, deterministic. FinalGather uses the global map's precomputed irradiance when
/// present (PhotonMap::precomputeIrradiance), else its k-nearest estimate. Radiance in
/// W/m²/sr; `patch` holds the patch seen (directly) at each pixel.
RadianceImage renderPhotonImage(const PhotonScene& in, const Camera& camera, int width, int height,
                                PhotonView view, const PhotonSettings& settings);

/// \brief The exposure render.png would use: autoExposure over the pixels that do not see an
/// emitter directly.
double photonImageExposure(const PhotonScene& in, const RadianceImage& image);

}  // namespace radkit
