#include "hierarchy/links.h"

namespace radkit {

namespace {

/// A cluster whose normals lie within this angle of their axis is estimated as one (its
/// error is below 1 − cos 0.35 ≈ 6 %); a wider one is summed over its children, at most
/// kSplitLevels levels down (8 terms), which separates the walls of a room's corner.
constexpr double kCoherentCone = 0.35;
constexpr int kSplitLevels = 3;

template <typename Leaf>
double sumOverCoherent(const Hierarchy& h, int n, int levels, const Leaf& leaf) {
  const HNode& node = h[n];
  if (node.element || node.coneAngle <= kCoherentCone || levels == 0) return leaf(n);
  return sumOverCoherent(h, h.child(n, 0), levels - 1, leaf) +
         sumOverCoherent(h, h.child(n, 1), levels - 1, leaf);
}

}  // namespace

LinkKind linkKind(const Hierarchy& h, const HLink& link) {
  bool r = h[link.receiver].element, s = h[link.source].element;
  if (r && s) return LinkKind::ElementElement;
  if (r) return LinkKind::ElementCluster;
  if (s) return LinkKind::ClusterElement;
  return LinkKind::ClusterCluster;
}

const char* linkKindName(LinkKind kind) {
  switch (kind) {
    case LinkKind::ElementElement:
      return "element_element";
    case LinkKind::ElementCluster:
      return "element_cluster";
    case LinkKind::ClusterElement:
      return "cluster_element";
    case LinkKind::ClusterCluster:
      return "cluster_cluster";
  }
  return "?";
}

double projectedArea(const Hierarchy& h, int n, const Vec3& w) {
  return sumOverCoherent(h, n, kSplitLevels, [&](int k) {
    const HNode& node = h[k];
    return node.element ? node.area * std::max(0.0, dot(h.normal(k), w))
                        : projectedSum(node.area, node.areaNormal, w);
  });
}

Vec3 intensityToward(const Hierarchy& h, const SourceState& state, int s, const Vec3& w) {
  Vec3 out;
  for (int c = 0; c < 3; ++c)
    out[c] = sumOverCoherent(h, s, kSplitLevels, [&](int k) {
      const HNode& node = h[k];
      const double power = state.radiosity[k][c] * node.area;
      return node.element ? power * std::max(0.0, dot(h.normal(k), w))
                          : projectedSum(power, state.powerVector[node.cluster][c], w);
    });
  return out / kPi;
}

}  // namespace radkit
