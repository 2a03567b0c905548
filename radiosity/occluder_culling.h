// OccluderCulling: decides cheaply, without rays, that nothing can block a patch pair.
#pragma once

#include <vector>

#include "geometry/patch_mesh.h"
#include "radiosity/patch_pairs.h"

namespace radkit {

/// A conservative "can anything block the segments between patches i and j?" test.
/// Every segment between the two patches lies in B, the union of their bounding boxes, so only
/// patches whose boxes overlap B can block. A planar surface whose plane leaves B on one side
/// cannot cross such a segment (it could only touch it at a lifted end point): that removes
/// the walls of a room and the surfaces of i and j themselves without looking at their
/// patches. The remaining surfaces are scanned patch by patch until one box overlaps B.
/// No BVH: the cost is O(surfaces) plus the patches of surfaces whose plane crosses B.
class OccluderCulling {
 public:
  OccluderCulling(const PatchMesh& mesh, const PatchTable& table);
  /// \brief False only when no patch other than i and j can intersect a segment from i to j.
  bool mayBeBlocked(int i, int j) const;
  /// \brief False only when mayBeBlocked(i, j) is false for every patch j of `surface` (the
  /// mesh's surface index): the test above on the box of patch i and the whole surface.
  /// Rows ask it once per surface, and the pairs of an unblockable surface skip their own.
  bool mayBeBlockedFromSurface(int i, int surface) const;
  /// Number of mesh surfaces (the range of `surface` above).
  int surfaceCount() const { return static_cast<int>(m_surfaceBounds.size()); }

 private:
  /// The test on a box holding every segment: patches other than i and j may block.
  bool mayBeBlocked(const Bounds3& box, int i, int j) const;
  struct SurfaceRecord {
    int begin = 0, end = 0;  ///< patch range
    Bounds3 bounds;
    bool planar = false;
    Vec3 normal;
    double offset = 0;
  };
  const PatchTable& m_table;
  std::vector<SurfaceRecord> m_surfaces;
  std::vector<Bounds3> m_surfaceBounds;  ///< by mesh surface index (empty for no patches)
};

}  // namespace radkit
