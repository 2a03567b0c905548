// Per-patch data the form-factor methods read in their inner loops, and the cheap geometric
// relations between two patches (facing, coplanar, overlapping).
#pragma once

#include <vector>

#include "geometry/patch_mesh.h"

namespace radkit {

/// One patch, copied out of the PatchMesh into a compact record.
struct PatchInfo {
  Vec3 v[4];
  int count = 0;
  Vec3 normal;
  Vec3 centroid;
  double area = 0;
  double planeOffset = 0;  ///< n·p for points p in the plane
  Bounds3 bounds;
  Vec3 sphereCentre;  ///< bounding sphere (centroid, farthest vertex)
  double sphereRadius = 0;
  double split = 1;  ///< patchSplit(): area share of triangle (0,1,2)
  int surface = -1;
  bool parallelogram = false;  ///< a quad whose opposite edges are parallel and equal (1e-12)

  /// Signed distance of p from the patch plane (positive on the front side).
  double height(const Vec3& p) const { return dot(normal, p) - planeOffset; }
};

/// \brief The record of one planar patch (3 or 4 vertices, counter-clockwise about `normal`);
/// area and centroid from the vertices. Tests and tools build patches with it.
PatchInfo makePatchInfo(const Vec3* v, int count, const Vec3& normal);

/// How two patches sit towards each other, from one pass over their vertices' heights.
struct PairSides {
  bool facing = false;   ///< PatchTable::facing: F_ab can be non-zero
  bool inFront = false;  ///< inFrontOfEachOther (pair_rule.h): the tensor rules apply
};
/// \brief facing and inFrontOfEachOther of a pair together (each height computed once).
inline PairSides pairSides(const PatchInfo& a, const PatchInfo& b, double tolerance) {
  PairSides s;
  if (!(a.area > 0) || !(b.area > 0)) return s;
  bool bAhead = false, aAhead = false, bBehind = false, aBehind = false;
  for (int k = 0; k < b.count; ++k) {
    double h = a.height(b.v[k]);
    bAhead |= h > tolerance, bBehind |= h < -tolerance;
  }
  for (int k = 0; k < a.count; ++k) {
    double h = b.height(a.v[k]);
    aAhead |= h > tolerance, aBehind |= h < -tolerance;
  }
  s.facing = aAhead && bAhead;
  s.inFront = !aBehind && !bBehind;
  return s;
}

/// The patch table and the tolerance used for "on the plane" decisions.
class PatchTable {
 public:
  explicit PatchTable(const PatchMesh& mesh);
  int size() const { return static_cast<int>(m_patches.size()); }
  const PatchInfo& operator[](int i) const { return m_patches[i]; }
  /// Distances below this count as "on the plane": 1e-9 of the scene extent.
  double planeTolerance() const { return m_tolerance; }

  /// \brief True when some part of b lies strictly in front of a and some part of a strictly
  /// in front of b: only then can F_ab be non-zero (cos⁺ on both ends).
  bool facing(int a, int b) const;
  /// \brief True when both patches lie in one plane (either orientation).
  bool coplanar(int a, int b) const;
  /// \brief Area shared by two coplanar patches (0 when they merely touch).
  double overlapArea(int a, int b) const;

 private:
  std::vector<PatchInfo> m_patches;
  double m_tolerance = 0;
};

}  // namespace radkit
