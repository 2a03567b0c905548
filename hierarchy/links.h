// Links of hierarchical radiosity and the light they carry. A link r ← s says that node r
// gathers light from node s at the level of those two nodes. Between two elements it carries
// the form factor F_rs (Lambert's contour formula integrated over r) times a visibility
// estimate; when either end is a cluster it carries the point-to-point transfer between the
// nodes' centres, with each end's projected area estimated from its normals (below).
#pragma once

#include <array>
#include <cmath>
#include <vector>

#include "hierarchy/hierarchy.h"

namespace radkit {

struct HLink {
  int receiver = -1;
  int source = -1;
  double formFactor = 0;  ///< element ← element: unoccluded F_rs; otherwise unused (0)
  /// Visible share from rays: for element pairs the control-variate estimate with the
  /// unoccluded F, else the kernel-weighted ratio; times 1/P for a link that looked blocked and
  /// survived the last round's roulette with probability P (refine.cpp), so it may exceed 1.
  float visibility = 1;
  /// Its standard error (delta method); when every ray agreed, 1/(rays + 1). Float: an error.
  float visibilityError = 0;
  /// Element ← split element: the share of F_rs each quarter of s stands for (from r's Gauss
  /// points), so the gather weighs the quarters' radiosity instead of taking s's mean: the mean
  /// misses that r sees the bright part of s better or worse than the dark part. Negative
  /// first entry: not set (s unsplit). Float: shares of a sum that is itself stored in double.
  float quarterShare[4] = {-1, 0, 0, 0};
  /// Element source: kernel-weighted visible fraction of each quarter of s from the rays that
  /// ended there (−1: none did), so the shares above count the quarters r sees, not only how
  /// close they are: a floor element half under a block is seen by its lit half only.
  float quarterVisible[4] = {-1, -1, -1, -1};
  /// Element receiver: what each quarter of r gets of the link's irradiance, as a multiple of
  /// r's mean (area-weighted mean 1; negative first entry: the same everywhere). From F at the
  /// quarters' centroids and the rays that started there, so when r is split the light goes
  /// where it falls: not onto the part of a floor element hidden under a block, which would
  /// absorb it unseen.
  float receiverShare[4] = {-1, 0, 0, 0};
};

/// Radiosity of source s as link l sees it: its quarters weighted by the link's shares where
/// set, else s's mean.
inline Vec3 linkSourceRadiosity(const Hierarchy& h, const std::vector<Vec3>& radiosity,
                                const HLink& l) {
  const HNode& s = h[l.source];
  if (l.quarterShare[0] < 0 || s.childCount != 4) return radiosity[l.source];
  Vec3 b;
  for (int k = 0; k < 4; ++k) b += radiosity[s.firstChild + k] * double(l.quarterShare[k]);
  return b;
}

enum class LinkKind { ElementElement, ElementCluster, ClusterElement, ClusterCluster };
/// Kind of a link by its ends, receiver first ("element ← cluster" is ElementCluster).
LinkKind linkKind(const Hierarchy& h, const HLink& link);
const char* linkKindName(LinkKind kind);

/// Light leaving the nodes during a solve: radiosity B (area average, W/m²) per node, and for
/// clusters the power vector Φ_c = Σ_k B_kc A_k n_k per channel (Willmott, Heckbert & Garland
/// 1999's vector form, which makes a planar cluster's emission exact).
struct SourceState {
  std::vector<Vec3> radiosity;
  /// Per cluster (row HNode::cluster; elements need none): Σ B A n over the faces below, per
  /// channel.
  std::vector<std::array<Vec3, 3>> powerVector;
  /// Range of the leaves' radiosity (largest channel) below each node: a link that uses the
  /// source's mean B errs by up to this where the part the receiver sees is brighter or darker
  /// than the rest (the lit part of a floor around a block's shadow).
  std::vector<double> radiosityMin, radiosityMax;
  /// Area of each node that can be seen: leaves that see nothing (a floor under a block; by
  /// reciprocity nothing sees them) count 0. A node's radiosity is the mean over this area: the
  /// rays of a link to it already count its hidden part as blocked, so the whole-area mean
  /// would count that part's darkness twice. Empty: every leaf counts.
  std::vector<double> visibleArea;
};

/// \brief Σ_k X_k max(0, n_k·w) for weights X_k >= 0 and unit normals n_k, from X = Σ X_k and
/// V = Σ X_k n_k only. Σ X_k |n_k·w| lies in [|V·w|, X]; it is taken as |V·w| + (X − |V|)/2,
/// exact when every n_k is the same (a planar cluster or one direction) and right on average
/// for normals spread evenly over the sphere (Σ|cos| = X/2).
inline double projectedSum(double total, const Vec3& vector, const Vec3& w) {
  double along = dot(vector, w);
  double absolute = std::fabs(along) + 0.5 * (total - length(vector));
  return std::max(0.0, 0.5 * (absolute + along));
}

/// \brief Radiant intensity (W/sr per unit of scene area) of node s toward unit direction w,
/// per channel: Σ_k B_k A_k max(0, n_k·w)/π, by projectedSum over s's coherent parts.
Vec3 intensityToward(const Hierarchy& h, const SourceState& state, int s, const Vec3& w);

/// \brief Area of node n projected onto the plane normal to unit w, counting only surfaces
/// that face w: exact for an element; for a cluster, projectedSum over its coherent parts.
double projectedArea(const Hierarchy& h, int n, const Vec3& w);

/// Geometry of a link with a cluster at either end: the unit direction ω from r's centre to
/// s's, and the transfer's denominator d² + P_s/π. The P_s/π term treats the source as a disk
/// of its projected area (Wallace, Elmquist & Haines 1989: ΔF = A cosθ cosθ'/(πr² + A)): exact
/// on the axis of a facing disk, where the point formula overestimates by (1 + R²/d²), and it
/// keeps links between nearby or overlapping nodes finite.
struct ClusterTransfer {
  Vec3 w;
  double denominator = 0;
};
inline ClusterTransfer clusterTransfer(const Hierarchy& h, int r, int s) {
  Vec3 d = h[s].centre - h[r].centre;
  double d2 = dot(d, d);
  Vec3 w = d2 > 0 ? d / std::sqrt(d2) : h[r].coneAxis;
  return {w, d2 + projectedArea(h, s, -w) / 3.14159265358979323846};
}

}  // namespace radkit
