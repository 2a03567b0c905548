// Link refinement: the oracle that decides whether a link is good enough, and the top-down
// refinement that starts from the root's link to itself (Hanrahan et al. 1991's Refine, with
// clusters; links are made only when a parent link is refined: lazy linking).
#pragma once

#include <cstdint>
#include <functional>
#include <stdexcept>
#include <vector>

#include "geometry/visibility.h"
#include "hierarchy/links.h"
#include "radiosity/quadrature.h"

namespace radkit {

struct RefineSettings {
  double threshold = 0;  ///< τ: the largest error a link may carry, W (scene units² · W/m²)
  bool last = true;      ///< the last round: blocked links may be dropped (by roulette)
  double minArea = 0;    ///< elements are not split below this area (scene units²)
  int raysPerLink = 16;  ///< K visibility rays per new link
  std::uint64_t seed = 1;
  int round = 0;  ///< refine-and-solve round: each round's visibility rays are a fresh stream
  std::size_t memoryBudget = std::size_t(8) << 30;
  std::size_t fixedBytes = 0;  ///< memory outside the hierarchy and links (mesh, Embree)
};

/// Work counters of one refinement.
struct RefineStats {
  long long evaluated = 0;  ///< candidate links looked at
  long long splits = 0;     ///< links replaced by their children's links
  long long dropped = 0;    ///< links that carry nothing (facing away, occluded)
  long long rays = 0;
};

/// Thrown when the hierarchy and its links outgrow the memory budget.
struct HierarchyMemoryError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class Refiner {
 public:
  Refiner(Hierarchy& h, const Visibility& visibility, const RefineSettings& settings);

  /// \brief Refines `links` (in: last round's links, or the root's self-link; out: links whose
  /// estimated error is at most settings.threshold, or which cannot be split further) with the
  /// sources' light in `state`; new nodes get their parent's radiosity in `state`.
  /// \param progress called after each level with the candidates settled and those pending
  RefineStats refine(std::vector<HLink>& links, SourceState& state,
                     const std::function<void(long long, long long)>& progress = {});

  /// The root's link to itself: where refinement starts.
  std::vector<HLink> rootLinks() const;

 private:
  enum class Decision { Keep, Drop, SplitReceiver, SplitSource, SplitBoth };
  struct Outcome {
    Decision decision = Decision::Drop;
    HLink link;
    int rays = 0;
  };
  Outcome evaluate(const HLink& candidate, bool knownVisibility, const SourceState& state) const;
  Decision splitLarger(int r, int s) const;
  bool splittable(int node) const;
  /// Unoccluded element ← element form factor by adaptive cubature over the receiver, to a
  /// relative tolerance of the four-point `estimate`.
  double elementFormFactor(int r, int s, double estimate) const;
  struct VisibilityEstimate {
    double visible = 1, standardError = 0.5;
    /// Mean over all rays of w·(1 − v), w = cosθ_x cosθ_y / r² (0 where they do not face), and
    /// its standard error: with the unoccluded F it gives an unbiased visible share.
    double blockedKernel = 0, blockedKernelError = 0;
    float quarter[4] = {-1, -1, -1, -1};          ///< per quarter of an element source
    float receiverQuarter[4] = {-1, -1, -1, -1};  ///< per quarter of an element receiver
  };
  /// Sets link.quarterShare from r's Gauss points and link.quarterVisible when s is split
  /// into quarters.
  void quarterShares(int r, int s, HLink& link) const;
  /// Sets link.receiverShare from F at the centroids of r's quarters and their visibility.
  void receiverShares(int r, int s, const VisibilityEstimate& v, HLink& link) const;
  /// Kernel-weighted visible fraction from K segments between the nodes, and its error;
  /// independent streams of segments for different `stream`.
  VisibilityEstimate visibleFraction(int r, int s, int rays, int stream) const;

  Hierarchy& m_h;
  const Visibility& m_visibility;
  RefineSettings m_settings;
  AdaptiveCubature m_cubature;
};

/// Grows `state` to the hierarchy's size: new nodes take their parent's radiosity.
void growState(const Hierarchy& h, SourceState& state);

}  // namespace radkit
