// Surface-level plane test, then patch bounding boxes.
#include "radiosity/occluder_culling.h"

#include <cmath>

namespace radkit {

OccluderCulling::OccluderCulling(const PatchMesh& mesh, const PatchTable& table) : m_table(table) {
  double tol = table.planeTolerance();
  m_surfaceBounds.resize(mesh.surfaceBegin.empty() ? 0 : mesh.surfaceBegin.size() - 1);
  for (std::size_t s = 0; s + 1 < mesh.surfaceBegin.size(); ++s) {
    SurfaceRecord r;
    r.begin = mesh.surfaceBegin[s];
    r.end = mesh.surfaceBegin[s + 1];
    if (r.begin >= r.end) continue;
    r.normal = table[r.begin].normal;
    r.offset = table[r.begin].planeOffset;
    r.planar = true;
    for (int k = r.begin; k < r.end; ++k) {
      const PatchInfo& p = table[k];
      r.bounds.extend(p.bounds);
      for (int v = 0; v < p.count && r.planar; ++v)
        r.planar = std::fabs(dot(r.normal, p.v[v]) - r.offset) <= tol;
    }
    m_surfaceBounds[s] = r.bounds;
    m_surfaces.push_back(r);
  }
}

bool OccluderCulling::mayBeBlocked(int i, int j) const {
  Bounds3 box = m_table[i].bounds;
  box.extend(m_table[j].bounds);
  return mayBeBlocked(box, i, j);
}

bool OccluderCulling::mayBeBlockedFromSurface(int i, int surface) const {
  // Every pair box (i, j in surface) lies inside this box, and both tests below only get
  // easier on a smaller box (a plane keeps it on one side, no patch box overlaps it). The
  // surface's own patches are not excluded: when its plane does not dismiss them they
  // overlap the box and the answer is "maybe", left to the pairs.
  Bounds3 box = m_table[i].bounds;
  box.extend(m_surfaceBounds[surface]);
  return mayBeBlocked(box, i, -1);
}

bool OccluderCulling::mayBeBlocked(const Bounds3& box, int i, int j) const {
  Vec3 centre = (box.lo + box.hi) * 0.5, half = (box.hi - box.lo) * 0.5;
  double tol = m_table.planeTolerance();
  for (const SurfaceRecord& s : m_surfaces) {
    if (!s.bounds.overlaps(box)) continue;
    if (s.planar) {
      // Box–plane test: B lies on one closed side when |n·c − d| >= Σ |n_a| h_a.
      double radius = std::fabs(s.normal.x) * half.x + std::fabs(s.normal.y) * half.y +
                      std::fabs(s.normal.z) * half.z;
      if (std::fabs(dot(s.normal, centre) - s.offset) >= radius - tol) continue;
    }
    for (int k = s.begin; k < s.end; ++k)
      if (k != i && k != j && m_table[k].bounds.overlaps(box)) return true;
  }
  return false;
}

}  // namespace radkit
