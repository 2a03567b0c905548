// RayScene: Embree 3 ray queries over a PatchMesh. The only code that knows Embree exists.
#pragma once

#include <memory>
#include <vector>

#include "geometry/patch_mesh.h"
#include "geometry/visibility.h"

namespace radkit {

/// How Embree tests rays against the patches. Robust (RTC_SCENE_FLAG_ROBUST) keeps rays from
/// slipping through the edges neighbouring patches share; Fast skips that care for about 15 %
/// less time per query and lets about one random ray in 10⁷ through, but 8 % of the rays aimed
/// exactly at an edge (tests/geometry/ray_scene_test.cpp, docs/images.md). The path tracer
/// uses it, whose rays are never aimed at edges and whose noise dwarfs that bias; form
/// factors and visibility stay Robust.
enum class RayRobustness { Robust, Fast };

/// Owns an Embree device and scene built from the patches (quads as quads). Movable, not
/// copyable. Every query is const and thread-safe. Embree stores and tests geometry in
/// float: hit distances are accurate to single precision, which is why ends are offset.
class RayScene final : public Visibility {
 public:
  /// \param threads Embree's build threads (0: all cores).
  explicit RayScene(const PatchMesh& mesh, int threads = 0,
                    RayRobustness robustness = RayRobustness::Robust);
  ~RayScene() override;
  RayScene(RayScene&&) noexcept;
  RayScene& operator=(RayScene&&) noexcept;
  RayScene(const RayScene&) = delete;
  RayScene& operator=(const RayScene&) = delete;

  bool occluded(const Vec3& from, const Vec3& nFrom, const Vec3& to,
                const Vec3& nTo) const override;
  bool occluded(const Vec3& from, const Vec3& to) const override;
  std::optional<RayHit> closestHit(
      const Vec3& origin, const Vec3& direction, double tMin,
      double tMax = std::numeric_limits<double>::infinity()) const override;
  double epsilon() const override;

  /// Raw occlusion query with no offsets: the benchmark's reference for Embree's own rate.
  bool occludedRaw(const Vec3& origin, const Vec3& direction, double tNear, double tFar) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

/// Tests every patch for every query: O(patches) per ray, exact double arithmetic. The oracle
/// for RayScene in tests and a reference for small scenes.
class BruteForceVisibility final : public Visibility {
 public:
  explicit BruteForceVisibility(const PatchMesh& mesh);
  bool occluded(const Vec3& from, const Vec3& nFrom, const Vec3& to,
                const Vec3& nTo) const override;
  bool occluded(const Vec3& from, const Vec3& to) const override;
  std::optional<RayHit> closestHit(
      const Vec3& origin, const Vec3& direction, double tMin,
      double tMax = std::numeric_limits<double>::infinity()) const override;
  double epsilon() const override { return m_epsilon; }

 private:
  const PatchMesh& m_mesh;
  double m_epsilon;
};

/// Lifts a surface point by eps along its normal, to the side that faces `toward`.
inline Vec3 liftToward(const Vec3& p, const Vec3& n, const Vec3& toward, double eps) {
  return dot(toward - p, n) >= 0 ? p + n * eps : p - n * eps;
}

}  // namespace radkit
