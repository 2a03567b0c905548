// `radkit run --method hierarchical`: hierarchical radiosity with clustering, writing every
// output a dense run writes (the leaves are its patches) plus links.png.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "geometry/scene_loader.h"
#include "hierarchy/hierarchical.h"
#include "hierarchy/link_matrix.h"

namespace radkit::app {

struct HierarchicalOptions {
  std::string method = "dense";
  CLI::Option* methodOption = nullptr;  ///< --method, to tell a given one from the default
  HierarchicalSettings settings;
  std::string gather = "jacobi";
  std::string linkColour = "F";
  std::string daylightPer = "element";  ///< with a sky: daylight per leaf element or input face
  int checkLinks = 0;  ///< links to check against a Monte Carlo reference (0: none)
  /// Options that belong to the dense method only (rejected with --method hierarchical).
  std::vector<CLI::Option*> denseOnly;
};

void addHierarchicalOptions(CLI::App& run, HierarchicalOptions& options);

/// What the run command passes on: the scene, the output folder and the shared options.
struct HierarchicalJob {
  std::string scene, out, camera;
  LoadOptions load;
  HierarchicalSettings settings;
  LinkColour linkColour = LinkColour::FormFactor;
  bool noRender = false, photometric = false, smooth = false;
  int imageWidth = 512, imageHeight = 512;
  int checkLinks = 0;
  std::string preset;  ///< the --preset that chose this method, for report.json
};

/// Parses --gather and --link-colour, refuses dense-only options; throws CLI::ValidationError.
void finishHierarchicalOptions(HierarchicalOptions& options);

void runHierarchicalJob(HierarchicalJob job);

}  // namespace radkit::app
