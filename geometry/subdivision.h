// Patch subdivision: splits every surface into well-shaped patches (OpenMesh).
#pragma once

#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "geometry/patch_mesh.h"
#include "geometry/scene.h"
#include "util/errors.h"

namespace radkit {

/// Most patches subdivide makes: beyond this a mesh does not fit memory, and counts would
/// overflow int. A request for more throws TooManyPatches.
constexpr long long kMaxPatches = 10'000'000;

struct TooManyPatches : std::length_error {
  using std::length_error::length_error;
};

struct SubdivisionSettings {
  double maxArea = 0;     ///< every patch <= maxArea (scene units²); 0: no limit
  int targetPatches = 0;  ///< about this many patches in total; 0: no target
};

/// \brief Splits each surface into patches. With no limit, one patch per input face (quads
/// stay quads). Each face of a surface is split into a grid (quads) or into similar triangles
/// with the same count along every edge of that surface, so shared edges match and there are
/// no T-junctions inside a surface; a single-quad surface gets an n×m grid of near-square
/// patches. Patch areas sum to the surface area. Throws TooManyPatches when the settings
/// would need more than kMaxPatches patches, InputError when a surface's edge lengths overflow.
///
/// A target is spread by area: each surface's share is target × its area / total area. When
/// surfaces with more faces than their share (a fine imported mesh) would leave others with
/// under a quarter of theirs, those others get their share anyway, so a floor under a scanned
/// model is split finely enough to show its shadow; the total then exceeds the target, and a
/// warning naming the mesh goes to `warnings` (when given).
PatchMesh subdivide(const Scene& scene, const SubdivisionSettings& settings,
                    std::vector<std::string>* warnings = nullptr);

/// \brief subdivide() as jobs and front ends call it: each warning goes to `warn` (when set), and
///        TooManyPatches becomes the InputError of throwTooManyPatches.
PatchMesh subdivideScene(const Scene& scene, const SubdivisionSettings& settings,
                         const std::function<void(const std::string&)>& warn);

/// \brief The InputError for TooManyPatches: names the scene and the mesh setting that asked
///        for more patches than radkit meshes, and the fix.
[[noreturn]] void throwTooManyPatches(const Scene& scene, const SubdivisionSettings& settings);

}  // namespace radkit
