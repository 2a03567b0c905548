// Integrators: the image modes of `radkit render` as a library, one registry row per mode
// (util/registry.h). An integrator turns a scene, a camera and the settings below into a
// radiance image; the command line, and any other front end, only fills the settings.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "bsdf/bsdf.h"
#include "geometry/subdivision.h"
#include "photon/tracer.h"
#include "radiosity/radiosity_pipeline.h"
#include "render/camera.h"
#include "render/path_tracer.h"
#include "render/radiosity_image.h"
#include "render/sampler.h"
#include "render/shading_context.h"
#include "render/smooth_radiosity.h"
#include "util/registry.h"

namespace radkit {

/// The image every integrator makes: its size, samples and random streams.
struct FilmSettings {
  int width = 512, height = 512;
  int samplesPerPixel = 16;  ///< Monte Carlo modes; photon-map's passes come from photonPasses
  std::uint64_t seed = 1;
  SamplerType sampler = SamplerType::Sobol;
};

/// Everything an integrator may read; each reads its own part.
struct RenderSettings {
  FilmSettings film;
  Camera camera;
  BsdfSettings bsdf;
  /// Solid angle lowers the Cornell box's error by 3 % at equal samples but costs 30 % more
  /// time (docs/images.md), so area is the default.
  LightSampling light = LightSampling::Area;
  /// The patches: of the radiosity solution (radiosity, two-pass and final-gather modes) or
  /// the modes' own mesh. Neither given: kDefaultRenderPatches for the modes that need
  /// patches, the scene's surfaces whole for path tracing.
  SubdivisionSettings mesh;
  FormFactorSettings formFactors;  ///< the radiosity solution's
  std::vector<SolverChoice> solvers{SolverChoice{}};
  SolverSettings stopping;
  int rouletteDepth = PathTraceSettings{}.rouletteDepth;
  int maxDepth = PathTraceSettings{}.maxDepth;
  std::size_t photons = 200000;
  int gatherRays = PhotonSettings{}.gatherRays;  ///< photon-map's final gathering rays per pixel
  int photonPasses = 1;  ///< photon-map: passes averaged, each its own camera stream
  bool smooth = false;   ///< radiosity: interpolate between patches
  SmoothSettings smoothing;
  bool guided = true;  ///< final-gather: form-factor-guided gather samples
  PipelineLog log;     ///< the radiosity solution's progress
  /// Each warning as it is found (subdivision's, a two-pass mode without glossy materials);
  /// RenderResult::warnings has them too.
  std::function<void(const std::string&)> warning;
};

/// The radiosity mesh of the modes that need patches when none is given: surface radiosities
/// on the Cornell box lie within 0.1 % of a 2 000-patch run, in about 3 s on two cores.
constexpr int kDefaultRenderPatches = 1000;

/// An integrator's image, with the pixels that show an emitter and the surface at each pixel.
struct RenderResult {
  RadianceImage image;
  std::string what;                   ///< one line: patches, paths, rays, time
  std::vector<bool> emits;            ///< pixels that see an emitter (exposure leaves them out)
  std::vector<int> surfaces;          ///< the surface each pixel centre sees, −1 for none
  std::vector<std::string> warnings;  ///< what the mode found doubtful
};

class Integrator {
 public:
  virtual ~Integrator() = default;
  /// \brief Throws InputError for settings the scene cannot take, TooManyPatches when the
  ///        mesh would exceed radkit's patch limit.
  virtual RenderResult render(const Scene& scene, const RenderSettings& settings) const = 0;
};

/// \brief Every image mode (integrators/registry.cpp): radiosity, phong, cook-torrance,
///        path-trace, photon-map, final-gather.
const Registry<Integrator>& integratorRegistry();

/// \brief The image of the integrator `shading` names: a registry name, optionally followed by
/// the mode's own parameters, "name:key=value;key=value". \throws ParamError for an unknown
/// name or a parameter the mode does not read.
RenderResult renderImage(const std::string& shading, const Scene& scene,
                         const RenderSettings& settings);

}  // namespace radkit
