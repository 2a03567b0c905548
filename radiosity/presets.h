// Named speed-accuracy presets: draft, balanced and reference are a few PipelineSettings changes
// chosen from the Pareto front of `radkit study` on the Cornell box (docs/speed-vs-accuracy.md);
// large picks hierarchical radiosity at its defaults, which wins from small scenes on and is
// the only method for meshes whose dense F does not fit (docs/hierarchical.md). The presets are
// a registry (util/registry.h) like every other named choice: a new one is one line in
// radiosity/presets.cpp, and the CLI's help, the job and Python find it there.
#pragma once

#include <string>
#include <vector>

#include "radiosity/radiosity_pipeline.h"
#include "util/registry.h"

namespace radkit {

/// One preset: the settings it fixes and the Cornell-box figures behind it.
class Preset {
 public:
  struct Row {
    int patches;
    int samples;
    double tolerance;
    const char* measured;  ///< from docs/speed-vs-accuracy.md or docs/hierarchical.md
    bool hierarchical;
  };
  Preset(std::string name, const Row& row) : m_name(std::move(name)), m_row(row) {}

  /// Whether it runs hierarchical radiosity (at its defaults) rather than the dense pipeline.
  bool hierarchical() const { return m_row.hierarchical; }
  /// \brief Overwrites the settings it fixes: mesh.targetPatches (and maxArea = 0),
  /// formFactors.method and samples, stopping.tolerance. A hierarchical preset changes no
  /// dense setting.
  void apply(PipelineSettings& settings) const;
  /// One line: what it sets and what it measured on the Cornell box.
  std::string describe() const;

 private:
  std::string m_name;
  Row m_row;
};

/// The presets: draft, balanced, reference (dense, fastest first), large (hierarchical).
const Registry<Preset>& presetRegistry();

/// \brief The preset names, in the registry's order.
std::vector<std::string> presetNames();
/// \brief The dense presets' names ("draft, balanced, reference"), for messages.
std::string densePresetNames();

/// \brief Whether the preset runs hierarchical radiosity (`--method hierarchical` at its
/// defaults) rather than the dense pipeline. \throws UnknownNameError (an invalid_argument)
/// for an unknown name, listing the known ones.
bool presetIsHierarchical(const std::string& name);

/// \brief Applies the preset (Preset::apply). Apply it first and the user's explicit options
/// after it, so they win. \throws UnknownNameError for an unknown name.
void applyPreset(const std::string& name, PipelineSettings& settings);

/// \brief Preset::describe. \throws UnknownNameError for an unknown name.
std::string describePreset(const std::string& name);

}  // namespace radkit
