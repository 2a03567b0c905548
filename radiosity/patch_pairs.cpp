// Geometric relations between patch pairs.
#include "radiosity/patch_pairs.h"

#include <algorithm>
#include <cmath>

#include "radiosity/contour.h"
#include "util/sampling.h"

namespace radkit {

namespace {
/// Fills the fields that follow from the vertices, normal, centroid and area.
void finishInfo(PatchInfo& info) {
  info.bounds = Bounds3();
  for (int k = 0; k < info.count; ++k) info.bounds.extend(info.v[k]);
  info.planeOffset = dot(info.normal, info.centroid);
  info.split = patchSplit(info.v, info.count);
  info.sphereCentre = info.centroid;
  info.sphereRadius = 0;
  for (int k = 0; k < info.count; ++k)
    info.sphereRadius = std::max(info.sphereRadius, length(info.v[k] - info.centroid));
  // v0 − v1 + v2 − v3 is the bilinear map's twist: zero exactly for a parallelogram.
  info.parallelogram = info.count == 4 && length(info.v[0] - info.v[1] + info.v[2] - info.v[3]) <=
                                              1e-12 * info.sphereRadius;
}
}  // namespace

PatchInfo makePatchInfo(const Vec3* v, int count, const Vec3& normal) {
  PatchInfo info;
  info.count = count;
  std::copy(v, v + count, info.v);
  info.normal = normal;
  Vec3 weighted;
  for (int k = 1; k + 1 < count; ++k) {
    double a = 0.5 * length(cross(v[k] - v[0], v[k + 1] - v[0]));
    info.area += a;
    weighted += (v[0] + v[k] + v[k + 1]) * (a / 3);
  }
  info.centroid = info.area > 0 ? weighted / info.area : v[0];
  finishInfo(info);
  return info;
}

PatchTable::PatchTable(const PatchMesh& mesh) {
  Bounds3 b = mesh.bounds();
  m_tolerance = 1e-9 * std::max(1e-300, b.empty() ? 1.0 : b.diagonal());
  m_patches.resize(mesh.patches.size());
  for (std::size_t i = 0; i < mesh.patches.size(); ++i) {
    const Patch& p = mesh.patches[i];
    PatchInfo& info = m_patches[i];
    info.count = p.vertexCount;
    for (int k = 0; k < p.vertexCount; ++k) info.v[k] = mesh.vertex(p, k);
    info.normal = p.normal;
    info.centroid = p.centroid;
    info.area = p.area;
    info.surface = p.surface;
    finishInfo(info);
  }
}

bool PatchTable::facing(int a, int b) const {
  return pairSides(m_patches[a], m_patches[b], m_tolerance).facing;
}

bool PatchTable::coplanar(int a, int b) const {
  const PatchInfo& pa = m_patches[a];
  const PatchInfo& pb = m_patches[b];
  for (int k = 0; k < pb.count; ++k)
    if (std::fabs(pa.height(pb.v[k])) > m_tolerance) return false;
  for (int k = 0; k < pa.count; ++k)
    if (std::fabs(pb.height(pa.v[k])) > m_tolerance) return false;
  return true;
}

double PatchTable::overlapArea(int a, int b) const {
  // Clip a by the inward planes of b's edges (both convex, in one plane), then measure.
  const PatchInfo& pa = m_patches[a];
  const PatchInfo& pb = m_patches[b];
  Vec3 poly[kMaxPolygonVertices], next[kMaxPolygonVertices];
  int m = pa.count;
  std::copy(pa.v, pa.v + pa.count, poly);
  for (int k = 0; k < pb.count && m >= 3; ++k) {
    Vec3 edge = pb.v[(k + 1) % pb.count] - pb.v[k];
    Vec3 inward = cross(pb.normal, edge);  // CCW polygon: the interior is to the left
    double len = length(inward);
    if (len <= 0) continue;
    // Shrink b by the tolerance so that patches sharing an edge overlap by nothing.
    Vec3 origin = pb.v[k] + inward * (m_tolerance / len);
    m = clipToHalfSpace(poly, m, origin, inward, next);
    std::copy(next, next + m, poly);
  }
  if (m < 3) return 0.0;
  Vec3 sum;
  for (int k = 1; k + 1 < m; ++k) sum += cross(poly[k] - poly[0], poly[k + 1] - poly[0]);
  return 0.5 * length(sum);
}

}  // namespace radkit
