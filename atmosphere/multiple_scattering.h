// The tables behind Atmosphere's multiple-scattering term (Hillaire 2020, "A Scalable and
// Production Ready Sky and Atmosphere Rendering Technique", EGSR, section 5.5): the sun's
// transmittance by altitude and zenith angle, and Ψ_ms, the radiance of all orders ≥ 2 that
// an isotropic scatterer at altitude h sees with the sun at cos zenith μ_s.
#pragma once

#include <vector>

#include "atmosphere/atmosphere.h"

namespace radkit::atmosphere {

/// \brief Transmittance to the top of the atmosphere, tabulated by altitude (√ spacing, dense
/// near the ground) and by cos zenith above the horizon (√ spacing, dense at the horizon);
/// bilinear. Nodes come from Atmosphere::opticalDepth. It serves the multiple-scattering
/// table only; skyRadiance marches its light rays itself.
class TransmittanceLut {
 public:
  explicit TransmittanceLut(const Atmosphere& atmosphere);
  /// Transmittance from altitude h toward cos zenith mu to the top; 0 below the horizon.
  Vec3 transmittance(double h, double mu) const;

  static constexpr int kAltitudes = 48, kCosines = 96;

 private:
  double m_groundRadius, m_topRadius;
  std::vector<Vec3> m_transmittance;  ///< [altitude][cosine]
};

/// \brief Ψ_ms(h, μ_s) = L_2nd / (1 − f_ms) (Hillaire 2020, eqs. 5–10): from each table point,
/// kDirections equal-area directions (an 8 × 8 grid in cos θ and φ) are marched in kSteps
/// midpoints; each sample adds the sun's single scattering with the isotropic phase, and a
/// ray ending on the ground adds the Lambertian ground lit by the transmitted sun. f_ms is the
/// same march's transfer of isotropic unit radiance, and 1/(1 − f_ms) the sum of all orders.
class MultipleScatteringLut {
 public:
  MultipleScatteringLut(const Atmosphere& atmosphere, const TransmittanceLut& transmittance);
  /// Bilinear in altitude and cos sun zenith (clamped to the table).
  Vec3 at(double h, double cosSunZenith) const;

  static constexpr int kSize = 32, kDirections = 64, kSteps = 32;

 private:
  double m_height;
  std::vector<Vec3> m_psi;  ///< [altitude][cos sun zenith], nodes at both ends
};

}  // namespace radkit::atmosphere
