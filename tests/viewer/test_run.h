// A small run folder written the way `radkit run` writes one: three patches in front of the
// camera (two red on the left, one green on the right), a 3×3 F, two solver runs.
#pragma once

#include <string>

#include "util/vec3.h"

namespace radkit::viewer::test {

struct TestRun {
  /// Camera at (0, 0, 3) looking at the origin, +y up, 40° vertical field of view.
  static constexpr double kCameraDistance = 3, kFovDeg = 40;
  /// Left surface x in [-1, -0.05] (patch 0: y in [-0.5, 0], patch 1: y in [0, 0.5]);
  /// right surface x in [0.05, 1], y in [-0.5, 0.5] (patch 2); all at z = 0 facing the camera.
  static const Vec3 kRadiosity[3];
  static const double kFormFactors[3][3];
};

/// \brief Writes radiosity.vtp (through output/run_files.h), report.json, formfactors.mtx,
/// convergence.csv and surfaces.csv into `folder` (which must exist).
/// \param rightFacesAway wind the right patch the other way, so the camera sees its back
void writeTestRun(const std::string& folder, bool rightFacesAway = false);

/// Pixel (x from the left, y from the top) where the test camera sees world point p on z = 0.
void projectToPixel(const Vec3& p, int width, int height, double& x, double& y);

}  // namespace radkit::viewer::test
