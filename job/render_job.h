// `radkit render` as one library call: one camera image of a scene by one image mode of the
// integrator registry (radiosity, two-pass Phong or Cook-Torrance, path tracing, photon
// mapping, final gathering), written as PNG (tone mapped), PFM or OpenEXR (linear radiance),
// and optionally its errors per surface against reference renders.
#pragma once

#include <string>
#include <vector>

#include "geometry/scene.h"
#include "geometry/scene_loader.h"
#include "integrators/integrator.h"
#include "render/hdr_io.h"
#include "render/image_comparison.h"

namespace radkit {

struct RenderJobSettings {
  std::string scene;
  LoadOptions load;
  /// Replaces the scene's camera (JobSettings::camera's form); neither: one that looks into
  /// the scene from its most front-facing side (automaticCamera).
  std::string camera;
  std::string shading = "path-trace";  ///< an integratorRegistry() name
  RenderSettings render;               ///< its camera is the job's (above)
  std::string out;                     ///< .png, .pfm or .exr
  double exposure = 0;  ///< PNG: radiance multiplier before tone mapping; 0: automatic
  ToneCurve tonemap = ToneCurve::Srgb;
  /// Reference renders (PFM) of the same size: each region's error against their mean, their
  /// own noise subtracted when there are two or more.
  std::vector<std::string> references;
  std::string report;  ///< with references: the errors as JSON here
};

struct RenderJobResult {
  std::string sceneName, sceneFile;
  RenderResult mode;
  double seconds = 0;               ///< the render's
  std::string format;               ///< of the file written: "png", "pfm" or "exr"
  double exposure = 0;              ///< the PNG's
  std::vector<RegionError> errors;  ///< against the references: all, surfaces, each surface, edges
};

/// \brief Renders and writes the image (and the report). Every file name and every reference
/// is checked before the render. \throws InputError naming the option for a bad one.
RenderJobResult runRenderJob(const RenderJobSettings& settings, const PipelineLog& log = {});

}  // namespace radkit
