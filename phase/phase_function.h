// Phase functions of participating media as plugins (as bsdf/registry.cpp does for BSDFs): each
// is a density over the sphere of directions (1/sr) of cos θ between the light's direction of
// travel before and after scattering, with exact importance sampling of cos θ (the azimuth is
// uniform and the caller's). The formulas are closed_form.h's; the tabulated one serves Mie
// tables (mie.h).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "util/registry.h"

namespace radkit {

/// A rotationally symmetric phase function: ∫ eval over the sphere is 1.
class PhaseFunction {
 public:
  virtual ~PhaseFunction() = default;
  /// Density per steradian at cos θ ∈ [−1, 1].
  virtual double eval(double cosTheta) const = 0;
  /// \brief cos θ distributed as the density, from u ∈ [0, 1); pdf is eval at the result (per sr).
  virtual double sample(double u, double& pdf) const = 0;
  /// ⟨cos θ⟩, the asymmetry parameter g.
  virtual double meanCosine() const = 0;
  /// The registry's name ("henyey-greenstein").
  virtual std::string name() const = 0;
  /// \brief The density with its anisotropy scaled by `scale` ∈ [0, 1]: the octave model of
  ///        multiple scattering (media/cloud_marcher.h) evaluates octave i with scale c^i, so
  ///        higher orders scatter more evenly. Each phase function says what scaling means for
  ///        it (scale 1 is eval).
  virtual double evalAnisotropyScaled(double cosTheta, double scale) const = 0;
};

/// 1/(4π).
class IsotropicPhase final : public PhaseFunction {
 public:
  double eval(double cosTheta) const override;
  double sample(double u, double& pdf) const override;
  double meanCosine() const override { return 0; }
  std::string name() const override { return "isotropic"; }
  double evalAnisotropyScaled(double cosTheta, double) const override { return eval(cosTheta); }
};

/// 3(1 + cos²θ)/(16π), sampled by inverting its cubic CDF.
class RayleighPhase final : public PhaseFunction {
 public:
  double eval(double cosTheta) const override;
  double sample(double u, double& pdf) const override;
  double meanCosine() const override { return 0; }
  std::string name() const override { return "rayleigh"; }
  /// Rayleigh has no anisotropy parameter to scale: unchanged.
  double evalAnisotropyScaled(double cosTheta, double) const override { return eval(cosTheta); }
};

/// Henyey and Greenstein (1941), g ∈ (−1, 1).
class HenyeyGreensteinPhase final : public PhaseFunction {
 public:
  explicit HenyeyGreensteinPhase(double g);
  double eval(double cosTheta) const override;
  double sample(double u, double& pdf) const override;
  double meanCosine() const override { return m_g; }
  std::string name() const override { return "henyey-greenstein"; }
  /// HG(scale · g).
  double evalAnisotropyScaled(double cosTheta, double scale) const override;

 private:
  double m_g;
};

/// \brief w·HG(g1) + (1 − w)·HG(g2) (Kattawar 1975): a forward and a backward lobe. Sampled
/// by choosing a lobe with probability w, then reusing the rest of u for that lobe.
class DoubleHenyeyGreensteinPhase final : public PhaseFunction {
 public:
  DoubleHenyeyGreensteinPhase(double g1, double g2, double w);
  double eval(double cosTheta) const override;
  double sample(double u, double& pdf) const override;
  double meanCosine() const override { return m_w * m_g1 + (1 - m_w) * m_g2; }
  std::string name() const override { return "double-henyey-greenstein"; }
  /// Each lobe's g scaled: w HG(scale · g1) + (1 − w) HG(scale · g2).
  double evalAnisotropyScaled(double cosTheta, double scale) const override;
  double g1() const { return m_g1; }
  double g2() const { return m_g2; }
  double w() const { return m_w; }

 private:
  double m_g1, m_g2, m_w;
};

/// \brief A phase function given at points of θ: the density is piecewise linear in cos θ
/// between them, normalised exactly (trapezoids in cos θ are exact for it), and sampled by
/// inverting its piecewise-quadratic CDF in closed form, so eval is exactly what sample draws.
class TabulatedPhase final : public PhaseFunction {
 public:
  /// \param theta strictly increasing angles in radians from 0 to π (at least 2).
  /// \param values the density at each angle, ≥ 0, any scale (it is normalised here).
  TabulatedPhase(const std::vector<double>& theta, const std::vector<double>& values,
                 std::string name = "tabulated");
  double eval(double cosTheta) const override;
  double sample(double u, double& pdf) const override;
  double meanCosine() const override { return m_mean; }
  std::string name() const override { return m_name; }
  /// A table has no anisotropy parameter: HG(scale · ⟨cos θ⟩), the octave model's usual
  /// stand-in (it drops a Mie table's forward peak and glory from the higher octaves).
  double evalAnisotropyScaled(double cosTheta, double scale) const override;

  /// The grid in increasing cos θ (−1 … 1) and the normalised density there (1/sr).
  const std::vector<double>& cosines() const { return m_mu; }
  const std::vector<double>& densities() const { return m_p; }
  /// ∫ of the density over the sphere for cos θ in [a, b] (exact for the piecewise-linear form).
  double probability(double a, double b) const;

 private:
  double cdfAt(double mu) const;
  std::vector<double> m_mu, m_p, m_cdf;  ///< m_cdf[i]: probability of cos θ < m_mu[i]
  double m_mean = 0;
  std::string m_name;
};

/// \brief θ grid of n points from 0 to π, quadratic in the index so the steps near θ = 0 are
/// ~40 times finer than near π (a forward peak of width 1/x needs them): the Mie tables' grid.
std::vector<double> forwardRefinedAngles(int n);

/// \brief A phase function by its registry name and "key=value, ..." parameters:
/// "isotropic", "rayleigh", "henyey-greenstein" (g), "double-henyey-greenstein" (g1, g2, w),
/// "mie-cloud" (r_eff, v_eff in µm, wavelength in µm, n, k: a tabulated Mie phase function of a
/// gamma distribution of droplets, phase/mie.h). Throws std::invalid_argument naming an unknown
/// name or key, or the valid range of a value outside it.
std::unique_ptr<PhaseFunction> makePhaseFunction(const std::string& name,
                                                 const std::string& params = "");
/// The registry's names.
std::vector<std::string> phaseFunctionNames();
/// The registry itself (names for help texts, entries for tests).
const Registry<PhaseFunction>& phaseRegistry();
/// \brief Parameters the registry-driven tests use for each name (a valid example).
std::string phaseFunctionExample(const std::string& name);

}  // namespace radkit
