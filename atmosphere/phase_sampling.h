// Importance sampling of the phase functions of atmosphere.h for the reference path tracer:
// each returns cos θ between the light's direction of travel before and after scattering,
// distributed exactly as the phase function (no weights).
#pragma once

#include "geometry/sampling.h"
#include "geometry/vec3.h"

namespace radkit::atmosphere {

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

}  // namespace radkit::atmosphere
