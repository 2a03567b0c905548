// Daylight per element of the hierarchy: every leaf element's irradiance from the sky and the
// sun, estimated on the element itself (not on its input face), and a refinement criterion on
// how much that daylight varies across the element's quarters, so elements are split along a
// sun shadow edge that crosses a large input face (docs/daylight.md, docs/hierarchical.md).
#pragma once

#include <cstdint>
#include <vector>

#include "daylight/daylight.h"
#include "daylight/sky.h"
#include "geometry/ray_scene.h"
#include "hierarchy/hierarchy.h"

namespace radkit {

/// Standard errors a quarter's sky light must differ from the element's mean by before the
/// difference counts: noise alone then splits almost nothing.
constexpr double kDaylightNoiseSigmas = 3;

class ElementDaylight {
 public:
  /// `seed`: the run's seed; each element's samples come from a stream keyed by (seed, its
  /// stable key), so they do not depend on creation order or the thread count.
  ElementDaylight(const RayScene& rays, const SkyModel& sky, std::uint64_t seed);

  /// \brief Estimates the daylight of every leaf element not estimated yet (parallel).
  void sampleNewLeaves(const Hierarchy& h);

  /// \brief Estimates new leaves, then splits every leaf element whose daylight varies across
  /// it by more than `threshold` allows, while its quarters stay at least `minArea`, estimates
  /// the quarters, and repeats on them. Returns the splits. The variation, in W like the link
  /// oracle's τ: max(ρ, 0.5) times (sky) Σ_q A_q |D_q − D̄| of the quarters' means beyond
  /// kDaylightNoiseSigmas standard errors, plus (sun) ∫|E_sun − Ē_sun| dA from the sun rays'
  /// visibility, A E_n cos θ · 2V̄(1 − V̄): a point is lit or not, so sun rays that disagree
  /// mean a shadow edge crosses the element, not noise.
  long long refine(Hierarchy& h, double threshold, double minArea);

  /// Per node: the element's own emission plus ρ times its daylight (sampled leaves; the
  /// gather reads it at the leaves).
  const std::vector<Vec3>& emission() const { return m_emission; }
  /// Sky plus sun irradiance of a sampled element, W/m².
  Vec3 daylight(int node) const { return m_sky[node] + m_sun[node]; }
  /// The daylight's variation over a sampled element (scene units² · W/m², largest channel):
  /// what refine() compares with the threshold after the reflectance.
  double variation(int node) const { return m_variation[node]; }

  /// \brief The leaves' daylight in the order given (a Daylight as computeDaylight makes per
  /// patch), with the rays and seconds spent on every element so far.
  Daylight leafDaylight(const Hierarchy& h, const std::vector<int>& leaves) const;

  long long rays() const { return m_rayCount; }
  long long sampled() const { return m_sampledCount; }
  long long splits() const { return m_splits; }
  double seconds() const { return m_seconds; }

 private:
  void sample(const Hierarchy& h, const std::vector<int>& nodes);
  void grow(const Hierarchy& h);

  const RayScene& m_rays;
  const SkyModel& m_model;
  std::uint64_t m_seed;
  std::vector<char> m_sampled;
  std::vector<Vec3> m_sky, m_sun, m_emission;
  std::vector<float> m_svf, m_skyError, m_svfError, m_variation;
  long long m_rayCount = 0, m_sampledCount = 0, m_splits = 0;
  double m_seconds = 0;
};

}  // namespace radkit
