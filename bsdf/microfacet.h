// Microfacet theory for the Cook-Torrance BRDF: the GGX (Trowbridge-Reitz) distribution of
// normals, its Smith masking (and the older geometry terms a course compares), sampling of
// visible normals, and the directional-albedo tables of Kulla-Conty energy compensation.
// All directions are local: the macro-surface normal is +z. Formulas:
// docs/oracles.md (Microfacet BRDF identities); Heitz 2014 (JCGT 3(2)), Heitz 2018 (JCGT 7(4)),
// Kulla & Conty 2017 ("Revisiting physically based shading at Imageworks").
#pragma once

#include <string>
#include <vector>

#include "util/vec3.h"

namespace radkit {

/// The shadowing-masking term G(ωo, ωi) of f = D G F / (4 μo μi).
enum class MaskingShadowing {
  HeightCorrelated,  ///< Smith, 1 / (1 + Λ(ωo) + Λ(ωi))   (Heitz 2014, eq. 99)
  Separable,         ///< Smith, G1(ωo) G1(ωi)             (Heitz 2014, eq. 98)
  SchlickGgx,        ///< UE4's Schlick-GGX with k = (r + 1)² / 8, r = √α (Karis 2013)
  CookTorrance,      ///< min(1, 2(n·h)(n·v)/(v·h), 2(n·h)(n·l)/(v·h)) (Cook & Torrance 1982)
};

/// "height-correlated", "separable", "schlick", "cook-torrance".
const char* maskingShadowingName(MaskingShadowing g);
/// \brief Inverse of maskingShadowingName; throws std::invalid_argument naming the choices.
MaskingShadowing parseMaskingShadowing(const std::string& name);

/// \brief Isotropic GGX distribution with roughness alpha in (0, 1] (alpha = roughness²).
class GgxDistribution {
 public:
  /// \param alpha GGX width, clamped below at 1e-4 so that D stays finite in double.
  explicit GgxDistribution(double alpha);
  double alpha() const { return m_alpha; }

  /// \brief D(m) = α² / (π ((n·m)²(α² − 1) + 1)²) per steradian; 0 for m.z <= 0.
  double D(const Vec3& m) const;
  /// \brief Smith Λ(ω) = (√(1 + α² tan²θ) − 1) / 2 (Heitz 2014, eq. 86).
  double lambda(const Vec3& w) const;
  /// \brief Smith masking G1(ω) = 1 / (1 + Λ(ω)); 0 for ω.z <= 0.
  double G1(const Vec3& w) const;
  /// \brief The selected G(ωo, ωi); both directions above the surface, else 0.
  double G(const Vec3& wo, const Vec3& wi, MaskingShadowing g) const;

  /// \brief Visible normal m for wo (wo.z > 0) from u in [0,1)² (Heitz 2018, listing 1).
  Vec3 sampleVisibleNormal(const Vec3& wo, double u0, double u1) const;
  /// \brief Density of sampleVisibleNormal: D_ωo(m) = G1(ωo) max(0, ωo·m) D(m) / ωo.z.
  double visibleNormalPdf(const Vec3& wo, const Vec3& m) const;

 private:
  double m_alpha;
};

/// \brief Directional albedo with F = 1, E(μo) = ∫ D G / (4 μo μi) μi dωi, integrated by
/// the midpoint rule on strata × strata cells of the visible-normal warp, where the
/// integrand is the bounded ratio G(ωo, ωi) / G1(ωo) (zero below the horizon).
double directionalAlbedo(const GgxDistribution& d, MaskingShadowing g, double mu, int strata = 64);

/// \brief E(μ) tabulated for one α and G, linearly interpolated, with
/// E_avg = 2 ∫ E(μ) μ dμ of that interpolant, and Kulla-Conty's multiple-scattering lobe.
class MicrofacetAlbedoTable {
 public:
  /// \param muCount nodes at μ_k = (k + ½)/muCount (constant beyond the end nodes).
  MicrofacetAlbedoTable(const GgxDistribution& d, MaskingShadowing g, int muCount = 32,
                        int strata = 64);

  /// \brief Interpolated E(μ), μ in [0, 1].
  double albedo(double mu) const;
  /// \brief E_avg = 2 ∫₀¹ E(μ) μ dμ of the interpolant (exact up to 1e-7).
  double average() const { return m_average; }
  /// \brief f_ms = (1 − E(μo))(1 − E(μi)) / (π (1 − E_avg)) per steradian (Kulla & Conty
  /// 2017): ∫ f_ms μi dωi = 1 − E(μo), so E + that is 1 for F = 1.
  double multipleScattering(double muO, double muI) const;
  const std::vector<double>& nodes() const { return m_albedo; }

 private:
  std::vector<double> m_albedo;
  double m_average = 0;
};

/// \brief Kulla-Conty's colour of the multiple-scattering lobe, F_avg² E_avg / (1 −
/// F_avg (1 − E_avg)) per channel, with Schlick's F_avg = F0 + (1 − F0)/21. 1 when F0 = 1.
Vec3 multipleScatteringFresnel(const Vec3& f0, double averageAlbedo);

}  // namespace radkit
