// Named speed-accuracy presets: draft, balanced and reference are a few PipelineSettings changes
// chosen from the Pareto front of `radkit study` on the Cornell box (docs/speed-vs-accuracy.md);
// large picks hierarchical radiosity at its defaults, which wins from small scenes on and is
// the only method for meshes whose dense F does not fit (docs/hierarchical.md).
#pragma once

#include <string>
#include <vector>

#include "radiosity/radiosity_pipeline.h"

namespace radkit {

/// \brief The preset names: "draft", "balanced", "reference" (dense, fastest first), "large".
std::vector<std::string> presetNames();

/// \brief Whether the preset runs hierarchical radiosity (`--method hierarchical` at its
/// defaults) rather than the dense pipeline. \throws std::invalid_argument for an unknown name.
bool presetIsHierarchical(const std::string& name);

/// \brief Overwrites the settings a preset fixes: mesh.targetPatches (and maxArea = 0),
/// formFactors.method and samples, stopping.tolerance. Everything else is left alone.
/// Apply the preset first and the user's explicit options after it, so they win. A
/// hierarchical preset changes no dense setting.
/// \throws std::invalid_argument for an unknown name, listing the known ones.
void applyPreset(const std::string& name, PipelineSettings& settings);

/// \brief One line: what the preset sets and what it measured on the Cornell box.
/// \throws std::invalid_argument for an unknown name.
std::string describePreset(const std::string& name);

}  // namespace radkit
