// Scene loading: JSON scenes (docs/formats.md) and OBJ/MTL files given directly as the scene.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "geometry/scene.h"

namespace radkit {

/// A problem with the user's input: the message names the file, the element and the fix.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Warnings collected while loading (non-planar polygons split, self-intersections, ...).
struct LoadReport {
  std::vector<std::string> warnings;
};

/// \brief Loads a scene file: `.json`, or `.obj` (with its MTL) as a whole scene.
/// Mesh surfaces (OBJ, PLY, OFF, STL) are read relative to the scene file. The result is
/// validated (see validation.h): every error throws InputError, warnings go to `report`.
Scene loadScene(const std::string& path, LoadReport* report = nullptr);

}  // namespace radkit
