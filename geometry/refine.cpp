#include "geometry/refine.h"

#include <algorithm>
#include <array>
#include <map>
#include <stdexcept>

namespace radkit {

namespace {

using Key = std::array<double, 3>;
Key key(const Vec3& p) { return {p.x, p.y, p.z}; }
Vec3 midpoint(const Vec3& a, const Vec3& b) { return (a + b) * 0.5; }

/// The vertices one surface's patches use, found by exact position.
class SurfaceVertices {
 public:
  /// \param out receives new vertices; `in` (whose vertices out starts with) lists the patches
  SurfaceVertices(PatchMesh& out, const PatchMesh& in, int begin, int end) : m_mesh(out) {
    for (int i = begin; i < end; ++i)
      for (int k = 0; k < in.patches[i].vertexCount; ++k) {
        int v = in.patches[i].vertex[k];
        m_index.emplace(key(in.vertices[v]), v);
      }
  }
  /// The vertex at p, appended to the mesh when new.
  int at(const Vec3& p) {
    auto [it, added] = m_index.emplace(key(p), int(m_mesh.vertices.size()));
    if (added) m_mesh.vertices.push_back(p);
    return it->second;
  }

 private:
  PatchMesh& m_mesh;
  std::map<Key, int> m_index;
};

Patch makePatch(const PatchMesh& mesh, std::array<int, 4> v, int count, int surface) {
  Patch p;
  p.vertex = v;
  p.vertexCount = count;
  p.surface = surface;
  computePatchGeometry(mesh.vertices, p);
  return p;
}

/// The four children of patch p (Cohen & Wallace §8.3: regular element subdivision).
void splitPatch(PatchMesh& out, SurfaceVertices& verts, const Patch& p) {
  const std::array<int, 4>& v = p.vertex;
  auto P = [&](int k) { return out.vertices[v[k]]; };
  if (p.isQuad()) {
    int m01 = verts.at(midpoint(P(0), P(1))), m12 = verts.at(midpoint(P(1), P(2)));
    int m23 = verts.at(midpoint(P(2), P(3))), m30 = verts.at(midpoint(P(3), P(0)));
    int c = verts.at((P(0) + P(1) + P(2) + P(3)) * 0.25);
    for (const std::array<int, 4>& q : {std::array<int, 4>{v[0], m01, c, m30},
                                        {m01, v[1], m12, c},
                                        {c, m12, v[2], m23},
                                        {m30, c, m23, v[3]}})
      out.patches.push_back(makePatch(out, q, 4, p.surface));
  } else {
    int m01 = verts.at(midpoint(P(0), P(1))), m12 = verts.at(midpoint(P(1), P(2)));
    int m20 = verts.at(midpoint(P(2), P(0)));
    for (const std::array<int, 4>& t : {std::array<int, 4>{v[0], m01, m20, -1},
                                        {m01, v[1], m12, -1},
                                        {m20, m12, v[2], -1},
                                        {m01, m12, m20, -1}})
      out.patches.push_back(makePatch(out, t, 3, p.surface));
  }
}

}  // namespace

RefinedMesh refinePatches(const PatchMesh& mesh, const std::vector<char>& split) {
  if (split.size() != mesh.patches.size())
    throw std::invalid_argument("refinePatches: one split flag per patch is required");
  RefinedMesh r;
  r.mesh.vertices = mesh.vertices;
  r.mesh.cullBack = mesh.cullBack;
  r.mesh.surfaceBegin.assign(1, 0);
  for (std::size_t s = 0; s + 1 < mesh.surfaceBegin.size(); ++s) {
    int begin = mesh.surfaceBegin[s], end = mesh.surfaceBegin[s + 1];
    SurfaceVertices verts(r.mesh, mesh, begin, end);
    for (int i = begin; i < end; ++i) {
      if (split[i]) {
        splitPatch(r.mesh, verts, mesh.patches[i]);
        r.parent.insert(r.parent.end(), 4, i);
      } else {
        r.mesh.patches.push_back(mesh.patches[i]);
        r.parent.push_back(i);
      }
    }
    r.mesh.surfaceBegin.push_back(r.mesh.size());
  }
  return r;
}

std::vector<std::vector<int>> surfaceNeighbours(const PatchMesh& mesh) {
  std::vector<std::vector<int>> nb(mesh.patches.size());
  for (std::size_t s = 0; s + 1 < mesh.surfaceBegin.size(); ++s) {
    int begin = mesh.surfaceBegin[s], end = mesh.surfaceBegin[s + 1];
    std::map<Key, std::vector<int>> cornerOf;  // position -> patches having it as a corner
    for (int i = begin; i < end; ++i)
      for (int k = 0; k < mesh.patches[i].vertexCount; ++k)
        cornerOf[key(mesh.vertices[mesh.patches[i].vertex[k]])].push_back(i);
    auto link = [&](int i, const Vec3& p) {
      auto it = cornerOf.find(key(p));
      if (it == cornerOf.end()) return false;
      for (int j : it->second)
        if (j != i) nb[i].push_back(j), nb[j].push_back(i);
      return true;
    };
    // Edge midpoints at any depth: a T-junction's vertex is one of them.
    auto walkEdge = [&](int i, const Vec3& a, const Vec3& b, int depth, auto&& self) -> void {
      Vec3 m = midpoint(a, b);
      if (depth > 30 || !link(i, m)) return;
      self(i, a, m, depth + 1, self);
      self(i, m, b, depth + 1, self);
    };
    for (int i = begin; i < end; ++i) {
      const Patch& p = mesh.patches[i];
      for (int k = 0; k < p.vertexCount; ++k) {
        Vec3 a = mesh.vertex(p, k), b = mesh.vertex(p, (k + 1) % p.vertexCount);
        link(i, a);
        walkEdge(i, a, b, 0, walkEdge);
      }
    }
  }
  for (std::vector<int>& list : nb) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  return nb;
}

}  // namespace radkit
