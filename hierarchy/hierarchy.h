// The hierarchy of hierarchical radiosity with clustering: a binary cluster tree (BVH) over
// the input faces, and below each face a quadtree of elements made on demand (Hanrahan,
// Salzman & Aupperle 1991; clusters after Smits, Arvo & Greenberg 1994 and Sillion 1995).
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "geometry/patch_mesh.h"
#include "util/check.h"
#include "util/vec3.h"

namespace radkit {

/// One node. Clusters hold surfaces of many input faces; elements are planar polygons (an input
/// face or a quarter of an element). Every node carries what the link oracle bounds with: a
/// bounding sphere, its area, its area-weighted normal sum and a cone holding every normal.
struct HNode {
  Vec3 centre;           ///< bounding-sphere centre (element: area centroid)
  double radius = 0;     ///< bounding-sphere radius
  double area = 0;       ///< surface area below this node (scene units²)
  Vec3 areaNormal;       ///< Σ A_k n_k over the elements below (|·| = area when all coplanar)
  Vec3 coneAxis;         ///< unit axis of the normal cone
  double coneAngle = 0;  ///< every normal below lies within this angle (radians) of coneAxis
  double reflectanceMax = 0;  ///< largest ρ (any channel) below: the oracle's worst case
  int parent = -1;
  int firstChild = -1;     ///< an element's four children are contiguous from here
  int rightChild = -1;     ///< a cluster's second child (its left subtree lies in between)
  int face = -1;           ///< elements: the input face (patch of the base mesh); clusters: -1
  int cluster = -1;        ///< clusters: row in the per-cluster arrays (SourceState::powerVector)
  std::int16_t level = 0;  ///< elements: splits below the input face; clusters: depth in the tree
  std::uint8_t childCount = 0;  ///< 2 for clusters, 4 for split elements, 0 for leaves
  bool element = false;

  bool isLeaf() const { return childCount == 0; }
};
// Two nodes per input face: at ten million faces every byte here is 20 MB.
static_assert(sizeof(HNode) == 128, "HNode grew");

/// An element's polygon: 3 or 4 vertices, counter-clockwise seen from the front.
struct HPolygon {
  Vec3 v[4];
  int count = 0;
  Vec3 normal;
};

/// \brief The four quarters of an element's polygon by midpoint subdivision (the children
/// Hierarchy::split makes, in the same order), and their areas.
void quarterPolygons(const HPolygon& p, HPolygon kids[4], double areas[4]);

/// Per-surface material data the hierarchy needs (radiosity uses only the diffuse part).
struct SurfaceRadiometry {
  Vec3 reflectance;  ///< ρ per channel in [0, 1)
  Vec3 emission;     ///< E per channel, W/m²
  /// All of `emission` is reflected daylight: not an emitter for the ray budgets, which
  /// spend more on the few surfaces that emit.
  bool daylightOnly = false;
};

class Hierarchy {
 public:
  /// \brief Builds the cluster tree over the faces of `base` (one patch per input face).
  /// Deterministic: the same input gives the same node numbering whatever the thread count.
  /// `byFace`: `surfaces` has one entry per face rather than per surface (daylight makes each
  /// face's emission its own).
  Hierarchy(PatchMesh base, std::vector<SurfaceRadiometry> surfaces, bool byFace = false);

  const PatchMesh& base() const { return m_base; }
  int root() const { return 0; }
  int size() const { return static_cast<int>(m_nodes.size()); }
  const HNode& operator[](int i) const {
    RADKIT_DCHECK(i >= 0 && i < size());
    return m_nodes[i];
  }
  /// An element's polygon: an input face's read from the base mesh (not stored twice), a
  /// quarter's stored when it was split off.
  HPolygon polygon(int node) const;
  /// An element's unit front normal: its input face's (quarters are coplanar with it).
  const Vec3& normal(int node) const { return m_base.patches[m_nodes[node].face].normal; }
  const SurfaceRadiometry& radiometry(int node) const {
    const int face = m_nodes[node].face;
    return m_surfaces[m_byFace ? face : m_base.patches[face].surface];
  }
  /// Child k of a node (k < childCount).
  int child(int node, int k) const {
    const HNode& n = (*this)[node];
    RADKIT_DCHECK(k >= 0 && k < n.childCount);
    return n.element ? n.firstChild + k : (k == 0 ? n.firstChild : n.rightChild);
  }
  int surfaceOf(int node) const { return m_base.patches[m_nodes[node].face].surface; }
  /// Nodes made by split() are numbered from here on (the tree over the input faces comes
  /// first).
  int firstSplitNode() const { return 2 * m_base.size() - 1; }
  /// Stable identity of a node, independent of creation order: seeds its rays. The tree's
  /// nodes hash their number; a split element's is its parent's key and its quarter.
  std::uint64_t key(int node) const;
  /// Node of input face f.
  int faceNode(int f) const { return m_faceNode[f]; }
  /// Clusters (inner nodes of the tree over the input faces); split() makes none.
  int clusterCount() const { return m_base.size() - 1; }

  /// \brief Whether element `node` may be split: its quarters are at least minArea.
  bool canSplit(int node, double minArea) const;
  /// \brief Splits element `node` into four (midpoint subdivision) unless it is split already.
  /// Not thread-safe: the refinement applies splits serially in a fixed order.
  void split(int node);

  /// Leaves in output order: by input face (so grouped by surface), quadtree order within.
  std::vector<int> leavesByFace() const;
  /// Leaves in tree order (depth first from the root): every node covers a contiguous range.
  /// range[node] = {first, end} positions in that order.
  std::vector<int> leavesInTreeOrder(std::vector<std::pair<int, int>>* range = nullptr) const;

  /// \brief A uniform point on the surfaces below `node` (an element's own polygon, or a face
  /// picked in proportion to area) and its normal; u0..u2 uniform in [0, 1).
  Vec3 samplePoint(int node, double u0, double u1, double u2, Vec3& normal) const;

  std::size_t bytes() const;

 private:
  int buildClusters(std::vector<int>& faces, int begin, int end, int parent, int level, int at);
  void finishCluster(int node);

  PatchMesh m_base;
  std::vector<SurfaceRadiometry> m_surfaces;
  bool m_byFace = false;
  std::vector<HNode> m_nodes;
  std::vector<HPolygon> m_polygons;
  std::vector<int> m_faceNode;
};

/// Resizes v to n, growing its capacity by an eighth at a time (not doubling): what refinement
/// adds to per-node arrays of millions of nodes is a few per cent.
template <class T>
void growVector(std::vector<T>& v, std::size_t n);
/// Makes room for n elements the same way (an eighth more than the capacity when it grows).
template <class T>
void reserveFor(std::vector<T>& v, std::size_t n) {
  if (n > v.capacity()) v.reserve(std::max(n, v.capacity() + v.capacity() / 8 + 16));
}

/// Stable key of child k of a node with key `parent`.
std::uint64_t childKey(std::uint64_t parent, int k);

}  // namespace radkit
