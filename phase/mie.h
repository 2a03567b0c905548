// Lorenz-Mie scattering by a homogeneous sphere after Bohren and Huffman (1983), "Absorption and
// Scattering of Light by Small Particles", chapter 4 and their BHMIE program's algorithm
// (appendix A; written anew here), and the phase function of a cloud of water droplets with the
// gamma size distribution of Hansen and Travis (1974), "Light scattering in planetary
// atmospheres", Space Sci. Rev. 16, 527–610, section 2. Lengths in metres.
#pragma once

#include <complex>
#include <vector>

#include "phase/phase_function.h"

namespace radkit {

/// Efficiencies (cross sections over πr²) and amplitude functions of one sphere.
struct MieSphere {
  double qext = 0, qsca = 0, qback = 0;
  double g = 0;                          ///< asymmetry parameter ⟨cos θ⟩
  int terms = 0;                         ///< n_max, Wiscombe's (1980) x + 4x^{1/3} + 2
  std::vector<std::complex<double>> s1;  ///< S1 at the requested cos θ
  std::vector<std::complex<double>> s2;  ///< S2 at the requested cos θ
  double qabs() const { return qext - qsca; }
  /// Phase function (1/sr) at the i-th requested cosine: (|S1|² + |S2|²)/(2π x² Q_sca).
  double phase(int i, double x) const;
};

/// \brief Mie theory for size parameter x = 2π r n_medium/λ and relative refractive index
/// m = n_particle/n_medium (Im m ≥ 0 absorbs, e^{−iωt} convention), with S1, S2 evaluated at
/// each of `cosines` (none: efficiencies only). Throws std::invalid_argument for x ≤ 0 or
/// x > 1e5, Re m ≤ 0 or Im m < 0.
MieSphere mieSphere(double x, std::complex<double> m, const std::vector<double>& cosines = {});

/// A cloud: water droplets of a gamma size distribution seen at one wavelength.
struct MieCloudSettings {
  double wavelength = 550e-9;  ///< in vacuum
  /// Water at 550 nm: n = 1.333 (Hale and Querry 1973, Appl. Opt. 12, 555); its k of ~2e-9
  /// there is negligible for droplets of ~10 µm and left out.
  std::complex<double> refractiveIndex{1.333, 0};
  double mediumIndex = 1;  ///< air
  /// Hansen and Travis's gamma distribution n(r) ∝ r^{(1−3b)/b} e^{−r/(ab)}: a = r_eff, b = v_eff
  /// in (0, 0.5). 10 µm and 0.1 are a typical water cloud's.
  double effectiveRadius = 10e-6;
  double effectiveVariance = 0.1;
  int angles = 2001;  ///< θ grid of the table, forwardRefinedAngles
  int radii = 240;    ///< trapezoidal quadrature points in radius
};

/// The bulk optics of a cloud and its phase function table.
struct MiePhase {
  std::vector<double> theta;  ///< radians, 0 … π
  /// Size-averaged phase function (1/sr), normalised analytically (by ⟨C_sca⟩): its numerical
  /// integral over the sphere checks the table's resolution.
  std::vector<double> phase;
  double crossSectionScattering = 0;  ///< ⟨C_sca⟩ (m²): σ_s per unit number density
  double crossSectionExtinction = 0;  ///< ⟨C_ext⟩ (m²): σ_t per unit number density
  double g = 0;                       ///< ⟨C_sca g⟩/⟨C_sca⟩
  double singleScatteringAlbedo() const { return crossSectionScattering / crossSectionExtinction; }
  /// The quadrature's radii (m), their weights n(r)·Δr (trapezoidal, any common scale) and
  /// each radius's own asymmetry parameter.
  std::vector<double> radii, weights, radiusG;
  double seconds = 0;  ///< wall time of mieCloud
  /// The table as a sampleable phase function.
  TabulatedPhase table() const;
};

/// \brief Integrates Mie theory over the gamma distribution by the trapezoidal rule in r over
/// the radii that carry all but ~1e-8 of the scattering cross section, weighting each radius's
/// phase function by its scattering cross section. Radii in parallel (TBB).
MiePhase mieCloud(const MieCloudSettings& settings = {});

}  // namespace radkit
