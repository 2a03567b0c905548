#include "radiosity/presets.h"
#include "util/format.h"

#include <stdexcept>

namespace radkit {

namespace {

/// One row of the table: the settings a preset fixes and the Cornell-box figures behind it.
struct Preset {
  const char* name;
  int patches;
  int samples;
  double tolerance;
  const char* measured;  ///< from docs/speed-vs-accuracy.md or docs/hierarchical.md
  bool hierarchical = false;
};

// The one table (hand-written, pbrt-v4 style). Each row is a point on or next to the Pareto
// front of `radkit study data/cornell-box.json --max-seconds 900` (docs/speed-vs-accuracy.md):
// errors against its 16 000-patch reference, seconds on the 2-core development machine.
constexpr Preset kPresets[] = {
    {"draft", 1000, 16, 1e-4, "Cornell box: ~2.4 s, surface error 1.4e-2, patch error 4.5e-3"},
    {"balanced", 4000, 16, 1e-6, "Cornell box: ~19 s, surface error 4.1e-3, patch error 1.5e-3"},
    {"reference", 16000, 16, 1e-9,
     "Cornell box: ~280 s and 2 GiB (dense F), the study's reference"},
    // Hierarchical radiosity at its defaults (epsilon 1e-4): on the Cornell box it matches the
    // balanced preset's surface errors in a seventh of the time and memory; its bytes grow
    // with the input faces, not their square (docs/hierarchical.md, "Cost and scaling").
    {"large", 0, 16, 1e-6,
     "hierarchical radiosity (--method hierarchical, epsilon 1e-4): Cornell box ~1.2 s, the "
     "balanced preset's surface errors; a million input triangles ~50 s and 1.2 GiB",
     true},
};

const Preset& findPreset(const std::string& name) {
  for (const Preset& p : kPresets)
    if (name == p.name) return p;
  std::string known;
  for (const Preset& p : kPresets) known += std::string(known.empty() ? "" : ", ") + p.name;
  throw std::invalid_argument("unknown preset '" + name + "'; known presets: " + known);
}

}  // namespace

std::vector<std::string> presetNames() {
  std::vector<std::string> names;
  for (const Preset& p : kPresets) names.emplace_back(p.name);
  return names;
}

bool presetIsHierarchical(const std::string& name) { return findPreset(name).hierarchical; }

void applyPreset(const std::string& name, PipelineSettings& settings) {
  const Preset& p = findPreset(name);
  if (p.hierarchical) return;
  settings.mesh.maxArea = 0;
  settings.mesh.targetPatches = p.patches;
  settings.formFactors.method = "point-polygon";
  settings.formFactors.samples = p.samples;
  settings.stopping.tolerance = p.tolerance;
}

std::string describePreset(const std::string& name) {
  const Preset& p = findPreset(name);
  if (p.hierarchical) return std::string(p.name) + ": " + p.measured;
  return std::string(p.name) + ": about " + std::to_string(p.patches) +
         " patches, point-polygon K = " + std::to_string(p.samples) + ", tolerance " +
         formatValue("%.0e", p.tolerance) + "; " + p.measured;
}

}  // namespace radkit
