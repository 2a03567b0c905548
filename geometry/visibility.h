// Visibility: the two ray questions the rest of radkit asks of the geometry.
// RayScene answers them with Embree; BruteForceVisibility is the test oracle.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>

#include "util/vec3.h"

namespace radkit {

/// First surface hit along a ray.
struct RayHit {
  int patch = -1;       ///< patch index in the PatchMesh the scene was built from
  double distance = 0;  ///< along the (unit) ray direction, in scene units
};

class Visibility {
 public:
  virtual ~Visibility() = default;

  /// \brief Is the segment between two surface points blocked by any patch?
  /// \param from a point on a surface with unit normal nFrom (either orientation)
  /// \param to   a point on a surface with unit normal nTo (either orientation)
  /// Both ends are lifted off their surfaces by epsilon() toward the other end (the second
  /// toward the lifted first, so coplanar ends go to the same side), so a point on a patch
  /// never hits its own patch, even at grazing angles. Thread-safe.
  virtual bool occluded(const Vec3& from, const Vec3& nFrom, const Vec3& to,
                        const Vec3& nTo) const = 0;

  /// \brief Is the open segment (from, to) blocked? Ends pulled in by epsilon() along it.
  virtual bool occluded(const Vec3& from, const Vec3& to) const = 0;

  /// \brief First hit along origin + t·direction for t in (tMin, tMax); direction unit.
  virtual std::optional<RayHit> closestHit(
      const Vec3& origin, const Vec3& direction, double tMin,
      double tMax = std::numeric_limits<double>::infinity()) const = 0;

  /// Offset (scene units) used to keep ray ends off their own surfaces, scaled to the scene.
  virtual double epsilon() const = 0;
};

/// The scene-relative ray offset: a fixed fraction of the scene's extent (bounding-box
/// diagonal or largest absolute coordinate, whichever is larger). Embree tests in single
/// precision (relative error ~6e-8 of a coordinate), so 1e-6 of the extent stays clear of
/// rounding in millimetre and kilometre scenes alike while moving points negligibly.
constexpr double kRayEpsilonRelative = 1e-6;
double rayEpsilon(const Bounds3& sceneBounds);

}  // namespace radkit
