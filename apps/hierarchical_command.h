// `radkit run --method hierarchical`: the options of hierarchical radiosity with clustering;
// the job itself is the library's (job/job.h).
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "hierarchy/hierarchical.h"

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

/// Parses --gather and --daylight-per into the settings; throws CLI::ValidationError.
void finishHierarchicalOptions(HierarchicalOptions& options);

}  // namespace radkit::app
