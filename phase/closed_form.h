// The closed-form phase functions (densities over the sphere of directions, 1/sr, of cos θ
// between the light's direction of travel and the scattered direction) and their exact
// importance sampling: each sampler returns cos θ distributed exactly as the density (no
// weights). The sky (atmosphere/), the media's phase-function plugins (phase_function.h) and
// the cloud model all use these.
#pragma once

#include "util/sampling.h"
#include "util/vec3.h"

namespace radkit {

/// \name Densities
/// \{
double isotropicPhase();
double rayleighPhase(double cosTheta);  ///< 3(1 + cos²θ)/(16π)
/// (3(1−g²)/(2(2+g²))) (1+cos²θ)/(1+g²−2g cosθ)^{3/2} / (4π): Cornette and Shanks 1992.
double cornetteShanksPhase(double cosTheta, double g);
double henyeyGreensteinPhase(double cosTheta, double g);
/// \}

/// \name Sampling
/// Rayleigh by inverting its CDF in μ = cos θ, (μ³ + 3μ + 4)/8: the cubic's one real root
/// (Cardano), μ = A − 1/A with A = ∛(z + √(z² + 1)), z = 4u − 2. u in [0, 1).
double sampleRayleighCosine(double u);
/// Henyey-Greenstein by its inverse CDF (isotropic when |g| < 1e-6). u in [0, 1).
double sampleHenyeyGreensteinCosine(double u, double g);
/// \brief Cornette-Shanks by rejection: it is HG(g) times (1 + μ²) up to a constant, so an
/// HG(g) sample is kept with probability (1 + μ²)/2 (at least half are). Draws 2k uniforms.
double sampleCornetteShanksCosine(Rng& rng, double g);
/// The unit direction at cos θ = mu from unit `axis`, azimuth 2π·u about it.
Vec3 directionAround(const Vec3& axis, double mu, double u);

}  // namespace radkit
