// Bsdf: how a surface scatters light, as the image modes and photon tracing see it (radiosity
// sees only diffuseAlbedo()). One interface, one .cpp per model (Nori's bsdf.h), each listed
// by name in bsdf/registry.cpp: lambert, phong, cook-torrance, mirror, glass, oren-nayar. A
// BSDF offers eval, sample and pdf together. docs/extending.md walks through adding one.
//
// Conventions (pbrt-v4): directions are unit vectors in the local shading frame, the
// surface's front normal is +z, both point away from the surface; wo toward the viewer,
// wi toward the light. Reflection-only models are one-sided (zero unless wo.z > 0 and
// wi.z > 0); callers flip the frame of two-sided materials. Glass sees both sides.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bsdf/microfacet.h"
#include "util/params.h"
#include "util/registry.h"
#include "util/sampling.h"  // powerHeuristic, which every BSDF user weighs with
#include "util/vec3.h"

namespace radkit {

/// A sampled incident direction and what it carries.
struct BsdfSample {
  Vec3 wi;             ///< local, unit
  Vec3 weight;         ///< f(wo, wi) |wi.z| / pdf per channel (the throughput factor)
  double pdf = 0;      ///< density per steradian (of the chosen lobe for delta lobes: 1)
  bool delta = false;  ///< from a Dirac lobe: eval() and pdf() do not see it
  /// The part of `weight` that scales radiance only (1/η² across a refracting interface,
  /// pbrt-v4's TransportMode::Radiance); photon tracing, which carries power, divides it out.
  double radianceScale = 1;
};

/// Options the BSDF factory applies to every material.
struct BsdfSettings {
  MaskingShadowing masking = MaskingShadowing::HeightCorrelated;  ///< Cook-Torrance G
  bool compensated = false;  ///< Cook-Torrance: add the Kulla-Conty multiple-scattering lobe
  int albedoTableSize = 32;  ///< μ nodes of the E(μ) table (compensation only)
};

class Bsdf {
 public:
  virtual ~Bsdf() = default;

  /// \brief f(wo, wi) per steradian per channel; zero for Dirac lobes.
  virtual Vec3 eval(const Vec3& wo, const Vec3& wi) const = 0;
  /// \brief Samples wi for wo from u in [0,1)³ (u0 chooses a lobe, u1 and u2 the
  /// direction). Nothing when the sample is lost (below the horizon, wo on the back).
  virtual std::optional<BsdfSample> sample(const Vec3& wo, double u0, double u1,
                                           double u2) const = 0;
  /// \brief Density per steradian with which sample() produces wi (non-delta lobes).
  virtual double pdf(const Vec3& wo, const Vec3& wi) const = 0;

  /// Whether sample() reads u0 (a choice among lobes); a single-lobe BSDF says no, and path
  /// tracers then skip that number instead of computing it.
  virtual bool choosesLobe() const { return true; }
  /// True when every lobe is a Dirac delta (mirror, glass): no light sampling there.
  virtual bool isDelta() const { return false; }
  /// The Lambertian part's albedo ρ_d (its lobe is ρ_d / π); what two-pass shading lights
  /// with the radiosity solution's irradiance.
  virtual Vec3 diffuseAlbedo() const { return {}; }
  /// True when f = diffuseAlbedo()/π everywhere above the surface: photon mapping may then use
  /// an irradiance estimate in place of a BSDF-weighted one.
  virtual bool lambertian() const { return false; }
  /// True when light passes through to the back side (glass): such surfaces keep their front
  /// frame on both sides, since the sign of wo.z tells inside from outside.
  virtual bool transmits() const { return false; }
  /// One line for reports: the model and its parameters.
  virtual std::string describe() const = 0;

  /// A diffuse lobe plus one glossy lobe, described without its model's formulas, so that a
  /// renderer can draw it with another model (render/shading_context.h); nothing for other
  /// BSDFs.
  struct GlossyLobe {
    enum class Family { Phong, Microfacet };
    Family family;
    Vec3 diffuse;   ///< ρ_d
    Vec3 specular;  ///< the glossy lobe's reflectance at normal incidence (Phong's ks, F0)
    /// GGX roughness α; Phong's exponent n maps to α = √(2/(n + 2)) (Walter et al. 2007,
    /// eq. 35, Beckmann ↔ Phong, used for GGX).
    double alpha;
  };
  virtual std::optional<GlossyLobe> glossyLobe() const { return std::nullopt; }

 protected:
  /// \brief The sample of direction wi drawn by a mixture of non-delta lobes: its density is
  ///        the whole pdf(wo, wi) (one-sample MIS over the lobes) and its weight f cos θi / pdf.
  ///        Nothing below the horizon or where the density vanishes.
  std::optional<BsdfSample> mixtureSample(const Vec3& wo, const Vec3& wi) const {
    if (wi.z <= 0) return std::nullopt;
    BsdfSample s;
    s.wi = wi;
    s.pdf = pdf(wo, wi);
    if (!(s.pdf > 0)) return std::nullopt;
    s.weight = eval(wo, wi) * (wi.z / s.pdf);
    return s;
  }
};

/// \brief The BSDF `name` with its parameters (bsdf/registry.cpp); each BSDF reads its own
///        keys and the registry rejects the rest.
/// \throws ParamError for an unknown name (listing the known ones), a key the BSDF does
///         not read, or a value out of range.
std::unique_ptr<Bsdf> makeBsdf(const std::string& name, Params params,
                               const BsdfSettings& settings = {});

/// \brief Every registered BSDF (bsdf/registry.cpp), in table order: names, help, examples.
const Registry<Bsdf, const BsdfSettings&>& bsdfRegistry();

// The built-in models by value, for tests and for the substitutions of the shading modes.
std::unique_ptr<Bsdf> makeLambertBsdf(const Vec3& albedo);
/// Energy-normalised Phong (Lafortune & Willems 1994): kd/π + ks (n + 2)/(2π) cos^n α.
std::unique_ptr<Bsdf> makePhongBsdf(const Vec3& kd, const Vec3& ks, double shininess);
/// Metallic-roughness Cook-Torrance: (1 − metallic) base/π + D G F / (4 μo μi) with
/// F0 = lerp(f0, base, metallic), alpha = roughness².
std::unique_ptr<Bsdf> makeCookTorranceBsdf(const Vec3& base, double metallic, double roughness,
                                           const Vec3& f0, const BsdfSettings& settings);
std::unique_ptr<Bsdf> makeMirrorBsdf(const Vec3& colour);
/// Smooth dielectric, eta = n_inside / n_outside (inside is behind the front normal).
std::unique_ptr<Bsdf> makeGlassBsdf(double eta);

}  // namespace radkit
