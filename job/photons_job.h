// `radkit photons` as one library call: photon mapping (Jensen 1996) of a scene, compared with
// radiosity: patches.csv, surfaces.csv, photonmap.png, caustics.png, comparison.csv,
// difference.png and report.json (docs/photon-mapping.md).
#pragma once

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

#include "experiments/photon_comparison.h"
#include "geometry/scene.h"
#include "geometry/scene_loader.h"
#include "geometry/subdivision.h"
#include "photon/estimate.h"
#include "photon/tracer.h"
#include "radiosity/radiosity_pipeline.h"

namespace radkit {

/// Patches when no mesh is given: patches.csv at a useful resolution, and the computed
/// radiosity comparison in a couple of seconds on the Cornell box.
constexpr int kDefaultPhotonPatches = 1000;

struct PhotonsJobSettings {
  std::string scene;
  LoadOptions load;
  std::string camera;                       ///< replaces the scene's (JobSettings::camera's form)
  std::optional<SubdivisionSettings> mesh;  ///< unset: kDefaultPhotonPatches patches
  PhotonSettings settings;
  std::string view = "gather";  ///< photonmap.png: "gather" (final gathering) or "map"
  int imageWidth = 256, imageHeight = 256;
  bool image = true;  ///< photonmap.png and caustics.png (and their gathering)
  /// A run folder to compare with (its surfaces.csv); empty: radiosity solved on the same
  /// mesh here, unless `radiosity` is false.
  std::string compare;
  bool radiosity = true;
  /// Random rays timed for the raw Embree reference, and a hundredth as many k-nearest
  /// queries; 0: none.
  long long benchRays = 1000000;
  std::string out;
};

struct PhotonsJobResult {
  std::string out;
  nlohmann::json report;                      ///< report.json as written
  std::vector<SurfaceEstimate> surfaces;      ///< the photon estimate per surface
  std::vector<SurfaceComparison> comparison;  ///< against radiosity, when compared
};

/// \brief Traces, estimates, compares and writes the run folder `out` (all or nothing).
/// \throws InputError for a bad scene, no emitter, or a comparison folder of another scene.
PhotonsJobResult runPhotonsJob(const PhotonsJobSettings& settings, const PipelineLog& log = {});

}  // namespace radkit
