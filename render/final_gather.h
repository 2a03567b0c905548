// Final gather of a radiosity solution (the classic two-pass method's second pass): per
// camera sample, one BSDF-sampled bounce from the first non-delta surface that looks up the
// radiosity the solution reflects where it lands, and direct light by next-event estimation
// (both combined with the bounce's own hits on emitters by MIS). The patches' discretisation
// error is thereby averaged over the gathered hemisphere instead of being seen directly.
#pragma once

#include "render/shading.h"
#include "render/smooth_radiosity.h"
#include "solvers/matrix.h"

namespace radkit {

/// \brief Where the solution's reflected light comes from, per receiving patch i: patch j
/// with probability ∝ F_ij · Y(B_j − E_j). Guided gathering samples a point on such a patch
/// (uniform by area) and shades it like a light, so rays go where the indirect light is.
class GatherGuide {
 public:
  GatherGuide(const FormFactorMatrix& f, const RadiosityLighting& lighting);
  bool empty(int patch) const { return m_start[patch] == m_start[patch + 1]; }
  /// \brief The source patch u picks for receiver i, and its probability. Requires !empty(i).
  int pick(int receiver, double u, double& probability) const;
  /// Probability that pick() returns `source` for `receiver` (0 if never).
  double probability(int receiver, int source) const;

 private:
  std::vector<std::size_t> m_start;  ///< per receiver, into m_source / m_cdf
  std::vector<int> m_source;         ///< ascending per receiver
  std::vector<float> m_cdf;          ///< cumulative probability, last of a row 1
};

struct FinalGatherSettings {
  int width = 256;
  int height = 256;
  int samplesPerPixel = 16;  ///< camera samples per pixel, each one light and one gather ray
  std::uint64_t seed = 1;    ///< keys every pixel's numbers (stream 2)
  SamplerType sampler = SamplerType::Sobol;
  int maxSpecularDepth = 8;  ///< mirror/glass bounces followed before the gathering vertex
  bool smooth = true;        ///< look up the crease-aware smooth reconstruction, not flat B
  SmoothSettings smoothing;
};

/// \brief The final-gather image. `scene` must be built on the mesh the lighting was solved on.
/// With a guide, each gather adds a guided sample to the BSDF-sampled one, the two weighted
/// by the power heuristic (one more shadow ray, much less noise where few patches are bright).
MonteCarloImage renderFinalGather(const ShadingScene& scene, const Camera& camera,
                                  const RadiosityLighting& lighting,
                                  const FinalGatherSettings& settings,
                                  const GatherGuide* guide = nullptr);

}  // namespace radkit
