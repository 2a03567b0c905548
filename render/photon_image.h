// Camera images from photon maps: final gathering (Jensen 1996, §3.3; Jensen 2001, ch. 9)
// and the direct visualisation of the global and caustic maps.
#pragma once

#include "geometry/patch_mesh.h"
#include "geometry/scene.h"
#include "geometry/visibility.h"
#include "render/emitters.h"
#include "render/photon_map.h"
#include "render/photon_tracer.h"
#include "render/radiosity_image.h"

namespace radkit {

/// What a photon image shows at the first diffuse point x a camera ray reaches (through
/// mirrors and glass), with ρ the diffuse albedo and E the emission of x:
enum class PhotonView {
  /// L = E/π + ρ/π (H_direct + H_caustic + H_indirect): direct light by shadow rays toward the
  /// emitters, caustics from the caustic map, indirect light by K cosine-distributed gather
  /// rays that read the global map's (reflected) radiance where they land.
  FinalGather,
  /// L = E/π + ρ/π H_global(x): the global map's k-nearest estimate at x, no gathering.
  GlobalMap,
  /// L = E/π + ρ/π H_caustic(x): only light that reached x through mirrors or glass.
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
