#include "radiosity/presets.h"

#include "util/format.h"

namespace radkit {

namespace {

// The rows (hand-written, pbrt-v4 style). Each dense row is a point on or next to the Pareto
// front of `radkit study data/cornell-box.json --max-seconds 900` (docs/speed-vs-accuracy.md):
// errors against its 16 000-patch reference, seconds on the 2-core development machine.
constexpr Preset::Row kDraft{
    1000, 16, 1e-4, "Cornell box: ~2.4 s, surface error 1.4e-2, patch error 4.5e-3", false};
constexpr Preset::Row kBalanced{
    4000, 16, 1e-6, "Cornell box: ~19 s, surface error 4.1e-3, patch error 1.5e-3", false};
constexpr Preset::Row kReference{
    16000, 16, 1e-9, "Cornell box: ~280 s and 2 GiB (dense F), the study's reference", false};
// Hierarchical radiosity at its defaults (epsilon 1e-4): on the Cornell box it matches the
// balanced preset's surface errors in a seventh of the time and memory; its bytes grow with the
// input faces, not their square (docs/hierarchical.md, "Cost and scaling").
constexpr Preset::Row kLarge{
    0, 16, 1e-6,
    "hierarchical radiosity (radkit run --method hierarchical, epsilon 1e-4): Cornell box ~1.2 "
    "s, the "
    "balanced preset's surface errors; a million input triangles ~50 s and 1.2 GiB",
    true};

/// A registry entry's create function for one row; presets take no parameters.
template <const char* Name, const Preset::Row& R>
std::unique_ptr<Preset> create(Params&) {
  return std::make_unique<Preset>(Name, R);
}
constexpr char kDraftName[] = "draft", kBalancedName[] = "balanced", kReferenceName[] = "reference",
               kLargeName[] = "large";

}  // namespace

const Registry<Preset>& presetRegistry() {
  static const Registry<Preset> registry(
      "preset", {
                    {kDraftName, create<kDraftName, kDraft>, "dense, fastest", ""},
                    {kBalancedName, create<kBalancedName, kBalanced>, "dense", ""},
                    {kReferenceName, create<kReferenceName, kReference>, "dense, finest", ""},
                    {kLargeName, create<kLargeName, kLarge>, "hierarchical", ""},
                });
  return registry;
}

void Preset::apply(PipelineSettings& settings) const {
  if (m_row.hierarchical) return;
  settings.mesh.maxArea = 0;
  settings.mesh.targetPatches = m_row.patches;
  settings.formFactors.method = "point-polygon";
  settings.formFactors.samples = m_row.samples;
  settings.stopping.tolerance = m_row.tolerance;
}

std::string Preset::describe() const {
  if (m_row.hierarchical) return m_name + ": " + m_row.measured;
  return m_name + ": about " + std::to_string(m_row.patches) +
         " patches, point-polygon K = " + std::to_string(m_row.samples) + ", tolerance " +
         formatValue("%.0e", m_row.tolerance) + "; " + m_row.measured;
}

std::vector<std::string> presetNames() { return presetRegistry().names(); }

std::string densePresetNames() {
  std::string names;
  for (const std::string& name : presetNames())
    if (!presetIsHierarchical(name)) names += (names.empty() ? "" : ", ") + name;
  return names;
}

bool presetIsHierarchical(const std::string& name) {
  return presetRegistry().make(name, {})->hierarchical();
}

void applyPreset(const std::string& name, PipelineSettings& settings) {
  presetRegistry().make(name, {})->apply(settings);
}

std::string describePreset(const std::string& name) {
  return presetRegistry().make(name, {})->describe();
}

}  // namespace radkit
