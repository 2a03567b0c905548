// The linear system of constant-element radiosity, B = E + ρ F B, solved per RGB channel
// (Cohen & Wallace 1993, eq. 2.3 in matrix form). Knows nothing of geometry: a patch is an area,
// a reflectance and an emission.
#pragma once

#include <vector>

#include "solvers/kernels.h"
#include "solvers/matrix.h"

namespace radkit {

/// How a solver's residual is measured against the tolerance.
enum class ResidualNorm {
  /// ‖E + ρFB − B‖∞ / ‖E‖∞ over all channels (docs/formats.md); absolute ‖·‖∞ when E = 0.
  Relative,
  /// max over patches and channels of |r_i| / max(|B_i|, |B_i + r_i|): every patch is measured
  /// against its own radiosity, so a 1e-20 patch is held to the same relative accuracy as a
  /// 1e20 one (the ∞-norm relative to ‖E‖∞ cannot see it).
  PerPatch,
};

/// B = E + ρ F B for three channels. Holds a pointer to F (not owned: F outlives the system).
struct RadiositySystem {
  const FormFactorMatrix* formFactors = nullptr;
  std::vector<double> area;  ///< A_i > 0, m² (only ratios matter).
  Channels reflectance;      ///< ρ_i per channel, in [0, 1).
  Channels emission;         ///< E_i per channel, >= 0, W/m².

  /// \brief Number of patches n.
  int size() const { return static_cast<int>(area.size()); }
  /// \brief F; throws std::logic_error when no matrix is set.
  const FormFactorMatrix& matrix() const;
  /// \brief Throws std::invalid_argument naming the first offending entry: F missing or not
  ///        n x n, a channel not of length n, A_i <= 0, ρ outside [0, 1), E < 0 or not finite.
  void validate() const;
  /// \brief ‖E‖∞ over all channels.
  double emissionNorm() const { return maxAbs(emission); }
};

/// \brief r = E + ρ F B − B for three channels (one pass over F).
Channels residualVector(const RadiositySystem& system, const Channels& b);

/// \brief The measure of residual r of radiosity b that solvers compare with the tolerance.
/// \param r  residual E + ρFb − b
/// \param b  the radiosity r belongs to
double residualMeasure(const RadiositySystem& system, const Channels& r, const Channels& b,
                       ResidualNorm norm);

/// \brief Σ_i A_i Σ_c |r_ic|: power (W) not yet accounted for. For Southwell, r = ΔB and this
///        is the unshot power of Cohen et al. (1988).
double residualPower(const RadiositySystem& system, const Channels& r);

}  // namespace radkit
