// The hierarchical solve: gather over links, then push-pull (Hanrahan et al. 1991, §4).
// Gathering at a cluster keeps the irradiance as a sum and a vector per channel (the light's
// directions), so each element below takes what its own normal sees when it is pushed down.
#pragma once

#include <algorithm>
#include <array>
#include <vector>

#include "hierarchy/links.h"

namespace radkit {

/// Gather orderings. Jacobi gathers every link from the last sweep's radiosity; Gauss-Seidel
/// sweeps the tree in fixed blocks (subtrees) and each block gathers from the radiosity the
/// blocks before it already updated. Both give the same bits for any thread count.
enum class GatherOrder { Jacobi, GaussSeidel };

/// \brief Recomputes one inner node's radiosity, range and power vector from its children.
void pullNode(const Hierarchy& h, int node, SourceState& state);
/// \brief The same for every inner node, from the leaves up (needs no links).
void pull(const Hierarchy& h, SourceState& state);

class HierarchicalSystem {
 public:
  /// Links are sorted by receiver (then source) so every gather sums in one fixed order.
  /// `rowTarget[n]` > 0 is what leaf n's row sum Σ_j F_ij is known to be independently of the
  /// links: 1 where the whole hemisphere is covered by the scene (the enclosure rule, Siegel &
  /// Howell), or a ray estimate below 1 where a little of it is not. The leaf's irradiance is
  /// scaled so its links add up to that, which removes the error of gathering at coarser
  /// nodes from the leaf's total. Empty or 0: not known, not scaled (only capped).
  /// `scratch` is the solve's state: the row sums are taken in it (its leaves' radiosity is
  /// kept, everything pulled from them is not: pull it again after) instead of in a state of
  /// its own, which at a million faces is a few hundred MiB more at the peak.
  HierarchicalSystem(const Hierarchy& h, std::vector<HLink> links, GatherOrder order,
                     SourceState& scratch, const std::vector<float>& rowTarget = {},
                     const std::vector<char>& hidden = {});

  const std::vector<HLink>& links() const { return m_links; }
  /// Hands the links over (for the next round's refinement); the system is unusable after.
  std::vector<HLink> releaseLinks() { return std::move(m_links); }
  /// \brief Frees everything but the links and their counts per node (linkCount()) and the
  /// statistics: the gather's arrays are most of the system's bytes, and the outputs need only
  /// the links. sweep(), leafIrradiance(), linkPower() and rowSum() must not be called after.
  void releaseGatherArrays();
  /// Links gathered by node n.
  int linkCount(int n) const { return m_begin[n + 1] - m_begin[n]; }

  /// How much the leaves' radiosity changed in a sweep.
  struct Change {
    double max = 0;    ///< max over leaves and channels of |B_new − B_old|, W/m²
    double power = 0;  ///< Σ_leaves A Σ_c |B_new − B_old| (scene units² · W/m²)
    void add(const Change& o) { max = std::max(max, o.max), power += o.power; }
  };
  /// \brief One sweep: gather, push down to the leaves (B = E + ρH there), pull up.
  Change sweep(SourceState& state);
  /// \brief Irradiance H at every leaf (indexed by node) that the links deliver from `state`,
  /// without changing it. With B = 1 everywhere this is the row sum Σ_j F_ij of each leaf.
  std::vector<Vec3> leafIrradiance(const SourceState& state);
  /// Power link i delivers to its receiver per unit of its source's radiosity (scene units²),
  /// as the gather computes it from `unit` (unitState()), before row sums are scaled.
  double linkPower(int i, const SourceState& unit) const;
  /// π I_s(−ω) of cluster link i's source toward its receiver, per channel, from `state`.
  Vec3 sourceIntensity(int i, const SourceState& state) const;
  /// Row sum of leaf n as the solve uses it: its target where it has one, else capped.
  double rowSum(int n) const { return m_rowSum[n]; }
  /// Bytes held by the system's arrays (links, landings, per-node sums).
  std::size_t bytes() const;
  /// \brief A state with B = 1 on every node (for row sums).
  SourceState unitState() const;
  /// \brief Sets state.visibleArea (hidden leaves count 0) for pull().
  void setVisibleArea(SourceState& state) const;
  /// \brief Each leaf's emission E by node (daylight per element), instead of its surface's;
  /// nullptr: the surface's. Not owned; must cover every leaf.
  void setEmission(const std::vector<Vec3>* emission) { m_emission = emission; }
  /// Open leaves whose links add up to a row sum so far above 1 that ρ·(row sum) > (1 + ρ)/2,
  /// and the largest deviation |row sum − 1| of any leaf before scaling. Such an open leaf's
  /// irradiance is scaled down to that cap, so coarse links between nearby clusters can never
  /// make a sweep grow (with ρ near 1 the solve would diverge); report.json counts them.
  int clampedLeaves() const { return m_clamped; }
  int normalisedLeaves() const { return m_normalised; }
  double largestRowSumError() const { return m_largestRowSumError; }
  /// Closed leaves whose row sum was too far from 1 to be normalised (capped instead).
  int unnormalisedClosedLeaves() const { return m_unnormalised; }
  /// Cluster-link ends that were too large to resolve into facing nodes and were estimated.
  long long approximateLandings() const { return m_approximateLandings; }
  /// Landings (facing nodes) over all cluster links, both ends.
  long long landings() const { return m_landingCount; }

 private:
  struct Accumulator {
    Vec3 sum;                   ///< irradiance H on a surface (uniform over the faces below)
    std::array<Vec3, 3> vec{};  ///< clusters: Σ e·ω per channel, from sources they all face
    void add(const Accumulator& o) {
      sum += o.sum;
      for (int c = 0; c < 3; ++c) vec[c] += o.vec[c];
    }
  };
  /// What node n gathered itself plus what its incoherent ancestors gathered for it.
  Accumulator gathered(int n) const;
  void gather(int r, const SourceState& state);
  void buildLandings();
  /// Push-pull below `node` with what its ancestors gathered: records each leaf's H and, with a
  /// state, sets its B = E + ρH and pulls up; returns the largest change of a leaf's B.
  Change pushPull(int node, const Accumulator& inherited, SourceState* state);
  void gatherList(const std::vector<int>& receivers, const SourceState& state);

  const Hierarchy& m_h;
  const std::vector<Vec3>* m_emission = nullptr;
  std::vector<HLink> m_links;
  std::vector<int> m_begin;
  /// Per node: the irradiance its own element links gathered (cluster links land in slots).
  std::vector<Vec3> m_gathered;
  /// Links with a cluster at either end carry the transfer between the nodes' centres along
  /// ω (receiver to source). Each end is resolved, once per system, into the nodes below it
  /// that face ω as a whole (every normal of their cone within 90° of it), skipping those
  /// that face away, down to input faces (landings). Light then leaves a source only from
  /// surfaces that face the receiver and reaches only faces that face the source: a sum of
  /// non-negative terms, linear in B, so row sums bound every sweep. Gathering a sum of
  /// irradiance vectors at a node whose faces point every way would let light from opposite
  /// sides cancel (a closed model in a room lost half its light that way).
  /// Each landing also carries `scale`: the link's d² + P_s/π over its own (its centre's
  /// distance to the other end's centre), so a near link is not taken at the distance between
  /// the ends' centres alone (the mean of 1/d² over a node exceeds its value at the centre:
  /// --check-links measured cluster links 2-13 % low into a model without it).
  struct SourceLanding {
    int node;
    float cosine;  ///< element: its n·(−ω); kApproximate: a cluster summed by projectedSum
    float scale;
  };
  /// A receiver-end landing: one link's light onto one facing node.
  struct ReceiverLanding {
    int node;
    float factor;  ///< kVector: a cluster facing ω (Σ e·ω kept); else irradiance per unit e
    float scale;
  };
  /// The same stored by target node: m_incoming[m_incomingBegin[n] ...] in link order, so the
  /// push-down sums a node's landings from one receiver (one slot) before adding the next:
  /// the order the sums have always been taken in.
  struct IncomingLanding {
    int link;  ///< −(link + 1) on the first landing of a slot
    float factor;
    float scale;
  };
  static constexpr float kApproximate = -2.0f, kVector = -1.0f;
  /// Resolves both ends of cluster link i (transfer `t`) into facing nodes, appended to
  /// `sources` (unless null) and `receivers` (hidden leaves receive nothing); `found` is
  /// scratch.
  void resolveLink(int i, const ClusterTransfer& t, std::vector<std::pair<int, float>>& found,
                   std::vector<SourceLanding>* sources, std::vector<ReceiverLanding>& receivers,
                   long long& approximate) const;
  std::vector<Vec3> m_linkDirection;   ///< per link: ω (cluster links)
  std::vector<double> m_linkGeometry;  ///< per link: V / (π (d² + P_s/π)) (cluster links)
  std::vector<int> m_sourceBegin;      ///< per link, into m_sourceLandings
  std::vector<SourceLanding> m_sourceLandings;
  std::vector<int> m_incomingBegin;  ///< per node, into m_incoming
  std::vector<IncomingLanding> m_incoming;
  std::vector<char> m_hidden;  ///< per node: a leaf that nothing sees (receives nothing)
  long long m_approximateLandings = 0, m_landingCount = 0;
  bool m_released = false;
  bool m_rowPass = false;  ///< leafIrradiance() writes raw row sums into m_rowSum instead
  /// Per link, from the last gather: the irradiance e its cluster end delivers (cluster links).
  std::vector<Vec3> m_linkIrradiance;
  std::vector<Vec3> m_leafIrradiance;
  /// Per quarter of a split element (node n at n − m_firstSplit, split nodes being numbered
  /// after the input faces' tree): its share of its parent's links' irradiance beyond the
  /// parent's mean (HLink::receiverShare); written only by the parent's gather.
  std::vector<Vec3> m_fromParent;
  int m_firstSplit = 0;
  std::vector<double> m_visibleFraction;  ///< per node: share of its area on leaves not hidden
  std::vector<double> m_rowScale;         ///< per leaf: caps an open leaf's row sum
  /// Per leaf with a row-sum target: target − row sum, filled each sweep with its surface's
  /// light per unit of row sum (m_meanIncoming, from the last sweep). m_leafRaw: H before.
  std::vector<double> m_deficit, m_rowSum;
  std::vector<Vec3> m_leafRaw, m_meanIncoming;
  int m_fillSurfaces = 0;
  void updateMeanIncoming();
  int m_clamped = 0, m_normalised = 0, m_unnormalised = 0;
  double m_largestRowSumError = 0;
  /// Blocks in sweep order (Jacobi: the root alone), the receivers inside each, and those
  /// above every block.
  std::vector<int> m_blocks;
  std::vector<std::vector<int>> m_blockReceivers;
  std::vector<int> m_aboveReceivers;
  std::vector<int> m_aboveClusters;  ///< clusters above the blocks, parents before children
};

}  // namespace radkit
