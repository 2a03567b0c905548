#include "hierarchy/hierarchy.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <tbb/task_group.h>

#include "util/sampling.h"

namespace radkit {

namespace {

/// Faces per subtree below which the cluster build stops spawning tasks.
constexpr int kSerialBuild = 4096;
/// |Σ A n| / Σ A below this: the faces' normals disagree enough to part them by normal.
constexpr double kCoherentNormals = 0.75;

}  // namespace

std::uint64_t childKey(std::uint64_t parent, int k) {
  return splitMix64(parent * 4 + std::uint64_t(k) + 0x9e3779b97f4a7c15ULL);
}

/// Grows a vector's capacity by an eighth at a time instead of doubling it: the node arrays
/// of a million-face hierarchy hold hundreds of MiB, and refinement adds only a few per cent.
template <class T>
void growVector(std::vector<T>& v, std::size_t n) {
  reserveFor(v, n);
  v.resize(n);
}
template void growVector(std::vector<Vec3>&, std::size_t);
template void growVector(std::vector<double>&, std::size_t);

Hierarchy::Hierarchy(PatchMesh base, std::vector<SurfaceRadiometry> surfaces, bool byFace)
    : m_base(std::move(base)), m_surfaces(std::move(surfaces)), m_byFace(byFace) {
  const int n = m_base.size();
  if (n == 0) throw std::invalid_argument("hierarchy: the scene has no faces");
  m_nodes.resize(std::size_t(2) * n - 1);
  m_faceNode.resize(n);
  std::vector<int> faces(n);
  for (int f = 0; f < n; ++f) faces[f] = f;
  buildClusters(faces, 0, n, -1, 0, 0);
  int clusters = 0;
  for (HNode& node : m_nodes)
    if (!node.element) node.cluster = clusters++;
}

int Hierarchy::buildClusters(std::vector<int>& faces, int begin, int end, int parent, int level,
                             int at) {
  HNode& node = m_nodes[at];
  node.parent = parent;
  if (level > std::numeric_limits<std::int16_t>::max())
    throw std::runtime_error("hierarchy: the cluster tree is deeper than 32767 levels");
  node.level = static_cast<std::int16_t>(level);
  if (end - begin == 1) {
    // An input face: the element at the top of its quadtree.
    const int f = faces[begin];
    const Patch& p = m_base.patches[f];
    node.element = true;
    node.level = 0;
    node.face = f;
    node.centre = p.centroid;
    node.area = p.area;
    node.areaNormal = p.normal * p.area;
    node.coneAxis = p.normal;
    node.coneAngle = 0;
    for (int k = 0; k < p.vertexCount; ++k)
      node.radius = std::max(node.radius, length(m_base.vertex(p, k) - p.centroid));
    node.reflectanceMax = maxComponent(m_surfaces[m_byFace ? f : p.surface].reflectance);
    m_faceNode[f] = at;
    return at;
  }
  // Faces whose normals disagree (the walls of a room's corner) are first parted by normal,
  // so clusters below are near-planar and their emission estimate is close to exact
  // (projectedSum); otherwise a median split of the centroids along the widest axis. Ties are
  // broken by face index so the tree does not depend on the sort's internals.
  Bounds3 box, normals;
  Vec3 areaNormal;
  double area = 0;
  for (int k = begin; k < end; ++k) {
    const Patch& p = m_base.patches[faces[k]];
    box.extend(p.centroid);
    normals.extend(p.normal);
    areaNormal += p.normal * p.area;
    area += p.area;
  }
  int mid = begin;
  if (length(areaNormal) < kCoherentNormals * area) {
    Vec3 spread = normals.hi - normals.lo;
    int axis = spread.x >= spread.y && spread.x >= spread.z ? 0 : (spread.y >= spread.z ? 1 : 2);
    double cut = 0.5 * (normals.lo[axis] + normals.hi[axis]);
    mid = static_cast<int>(
        std::stable_partition(faces.begin() + begin, faces.begin() + end,
                              [&](int f) { return m_base.patches[f].normal[axis] < cut; }) -
        faces.begin());
  }
  if (mid == begin || mid == end) {
    Vec3 extent = box.hi - box.lo;
    int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
    mid = begin + (end - begin) / 2;
    auto less = [&](int a, int b) {
      double ca = m_base.patches[a].centroid[axis], cb = m_base.patches[b].centroid[axis];
      return ca < cb || (ca == cb && a < b);
    };
    std::nth_element(faces.begin() + begin, faces.begin() + mid, faces.begin() + end, less);
  }
  node.firstChild = at + 1;  // the left subtree follows its parent; the right follows it
  node.childCount = 2;
  const int left = at + 1, right = at + 2 * (mid - begin);
  if (end - begin > kSerialBuild) {
    tbb::task_group tasks;
    tasks.run([&] { buildClusters(faces, begin, mid, at, level + 1, left); });
    buildClusters(faces, mid, end, at, level + 1, right);
    tasks.wait();
  } else {
    buildClusters(faces, begin, mid, at, level + 1, left);
    buildClusters(faces, mid, end, at, level + 1, right);
  }
  node.rightChild = right;
  finishCluster(at);
  return at;
}

void Hierarchy::finishCluster(int at) {
  HNode& node = m_nodes[at];
  const HNode& a = m_nodes[node.firstChild];
  const HNode& b = m_nodes[node.rightChild];
  node.area = a.area + b.area;
  node.areaNormal = a.areaNormal + b.areaNormal;
  node.reflectanceMax = std::max(a.reflectanceMax, b.reflectanceMax);
  // Bounding sphere of the two children's spheres.
  Vec3 d = b.centre - a.centre;
  double dist = length(d);
  if (dist + b.radius <= a.radius) {
    node.centre = a.centre, node.radius = a.radius;
  } else if (dist + a.radius <= b.radius) {
    node.centre = b.centre, node.radius = b.radius;
  } else {
    node.radius = 0.5 * (dist + a.radius + b.radius);
    node.centre = a.centre + d * ((node.radius - a.radius) / dist);
  }
  double len = length(node.areaNormal);
  node.coneAxis = len > 1e-9 * node.area ? node.areaNormal / len : a.coneAxis;
  node.coneAngle = std::min(kPi, std::max(angleBetween(node.coneAxis, a.coneAxis) + a.coneAngle,
                                          angleBetween(node.coneAxis, b.coneAxis) + b.coneAngle));
}

void quarterPolygons(const HPolygon& parent, HPolygon kids[4], double areas[4]) {
  const Vec3* v = parent.v;
  if (parent.count == 4) {
    Vec3 m01 = (v[0] + v[1]) * 0.5, m12 = (v[1] + v[2]) * 0.5, m23 = (v[2] + v[3]) * 0.5,
         m30 = (v[3] + v[0]) * 0.5, c = (v[0] + v[1] + v[2] + v[3]) * 0.25;
    kids[0] = {{v[0], m01, c, m30}, 4, parent.normal};
    kids[1] = {{m01, v[1], m12, c}, 4, parent.normal};
    kids[2] = {{c, m12, v[2], m23}, 4, parent.normal};
    kids[3] = {{m30, c, m23, v[3]}, 4, parent.normal};
  } else {
    Vec3 m01 = (v[0] + v[1]) * 0.5, m12 = (v[1] + v[2]) * 0.5, m20 = (v[2] + v[0]) * 0.5;
    kids[0] = {{v[0], m01, m20, {}}, 3, parent.normal};
    kids[1] = {{m01, v[1], m12, {}}, 3, parent.normal};
    kids[2] = {{m20, m12, v[2], {}}, 3, parent.normal};
    kids[3] = {{m01, m12, m20, {}}, 3, parent.normal};
  }
  for (int k = 0; k < 4; ++k) {
    const HPolygon& p = kids[k];
    areas[k] = 0;
    for (int t = 1; t + 1 < p.count; ++t)
      areas[k] += 0.5 * length(cross(p.v[t] - p.v[0], p.v[t + 1] - p.v[0]));
  }
}

bool Hierarchy::canSplit(int node, double minArea) const {
  const HNode& n = m_nodes[node];
  return n.element && (n.childCount > 0 || n.area >= 4.0 * minArea);
}

void Hierarchy::split(int node) {
  if (m_nodes[node].childCount > 0) return;
  HPolygon kids[4];
  double areas[4];
  quarterPolygons(polygon(node), kids, areas);
  reserveFor(m_nodes, m_nodes.size() + 4);
  reserveFor(m_polygons, m_polygons.size() + 4);
  const int first = size();
  const HNode up = m_nodes[node];
  for (int k = 0; k < 4; ++k) {
    HNode child;
    child.element = true;
    child.parent = node;
    child.level = static_cast<std::int16_t>(up.level + 1);
    child.face = up.face;
    child.reflectanceMax = up.reflectanceMax;
    child.coneAxis = up.coneAxis;
    const HPolygon& p = kids[k];
    // Centroid by the fan of the (planar, convex) polygon.
    Vec3 c;
    for (int t = 1; t + 1 < p.count; ++t)
      c += (p.v[0] + p.v[t] + p.v[t + 1]) *
           (0.5 * length(cross(p.v[t] - p.v[0], p.v[t + 1] - p.v[0])) / 3.0);
    const double area = areas[k];
    child.area = area;
    child.centre = area > 0 ? c / area : p.v[0];
    child.areaNormal = p.normal * area;
    for (int t = 0; t < p.count; ++t)
      child.radius = std::max(child.radius, length(p.v[t] - child.centre));
    m_polygons.push_back(p);
    m_nodes.push_back(child);
  }
  m_nodes[node].firstChild = first;
  m_nodes[node].childCount = 4;
}

std::vector<int> Hierarchy::leavesByFace() const {
  std::vector<int> out, stack;
  for (int f = 0; f < m_base.size(); ++f) {
    stack.assign(1, m_faceNode[f]);
    while (!stack.empty()) {
      int n = stack.back();
      stack.pop_back();
      const HNode& node = m_nodes[n];
      if (node.isLeaf()) {
        out.push_back(n);
        continue;
      }
      for (int k = node.childCount - 1; k >= 0; --k) stack.push_back(node.firstChild + k);
    }
  }
  return out;
}

std::vector<int> Hierarchy::leavesInTreeOrder(std::vector<std::pair<int, int>>* range) const {
  std::vector<int> out;
  if (range) range->assign(m_nodes.size(), {0, 0});
  // Iterative depth-first walk; a node's range closes when it is popped the second time.
  std::vector<std::pair<int, bool>> stack{{root(), false}};
  while (!stack.empty()) {
    auto [n, closing] = stack.back();
    stack.pop_back();
    const HNode& node = m_nodes[n];
    if (closing) {
      if (range) (*range)[n].second = static_cast<int>(out.size());
      continue;
    }
    if (range) (*range)[n].first = static_cast<int>(out.size());
    if (node.isLeaf()) {
      out.push_back(n);
      if (range) (*range)[n].second = static_cast<int>(out.size());
      continue;
    }
    stack.push_back({n, true});
    if (node.element) {
      for (int k = node.childCount - 1; k >= 0; --k) stack.push_back({node.firstChild + k, false});
    } else {
      stack.push_back({node.rightChild, false});
      stack.push_back({node.firstChild, false});
    }
  }
  return out;
}

std::uint64_t Hierarchy::key(int node) const {
  if (node < firstSplitNode()) return splitMix64(std::uint64_t(node) ^ 0x5bd1e9955bd1e995ULL);
  const int parent = m_nodes[node].parent;
  return childKey(key(parent), node - m_nodes[parent].firstChild);
}

HPolygon Hierarchy::polygon(int node) const {
  const HNode& n = m_nodes[node];
  RADKIT_DCHECK(n.element);
  if (node >= firstSplitNode()) return m_polygons[node - firstSplitNode()];  // split in step
  const Patch& p = m_base.patches[n.face];
  HPolygon poly;
  poly.count = p.vertexCount;
  for (int k = 0; k < p.vertexCount; ++k) poly.v[k] = m_base.vertex(p, k);
  poly.normal = p.normal;
  return poly;
}

Vec3 Hierarchy::samplePoint(int n, double u0, double u1, double u2, Vec3& normal) const {
  // Descend by area, reusing u0 rescaled at each choice (it stays uniform).
  while (!m_nodes[n].element) {
    const HNode& node = m_nodes[n];
    int a = node.firstChild, b = node.rightChild;
    double pa = m_nodes[a].area / node.area;
    if (u0 < pa) {
      u0 = u0 / pa;
      n = a;
    } else {
      u0 = (u0 - pa) / (1 - pa);
      n = b;
    }
    u0 = std::min(u0, 0x1.fffffffffffffp-1);
  }
  const HPolygon p = polygon(n);
  normal = p.normal;
  return samplePatchUniform(p.v, p.count, u1, u2);
}

std::size_t Hierarchy::bytes() const {
  return m_nodes.capacity() * sizeof(HNode) + m_polygons.capacity() * sizeof(HPolygon) +
         m_faceNode.capacity() * sizeof(int);
}

}  // namespace radkit
