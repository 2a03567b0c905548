// Procedural 2D noise (terrain heightfields) and the hash all noise uses: the PCG hash, 2D gradient
// noise, fBm and Musgrave's ridged multifractal (Ebert et al., "Texturing and Modeling: A
// Procedural Approach", 3rd ed., ch. 16).
#pragma once

#include <cstdint>

namespace radkit {

/// \brief The PCG hash of Jarzynski and Olano ("Hash Functions for GPU Rendering", JCGT 9(3),
/// 2020): one LCG step and PCG's RXS-M-XS output permutation. hashPCG(0) = 129708002.
std::uint32_t hashPCG(std::uint32_t v);

/// \brief Perlin's (2002) quintic fade 6t⁵ − 15t⁴ + 10t³: C² at the lattice, so gradient
/// noise has no creases there (2D here, 3D in noise3d.h).
inline double quinticFade(double t) { return t * t * t * (t * (t * 6 - 15) + 10); }

/// \brief Gradient noise at (x, y): unit gradients at the integer lattice chosen by hashPCG of
/// the lattice point and the seed, blended with Perlin's quintic fade (Perlin 2002). Zero at
/// lattice points; |value| < 1 (about ±0.7 in practice).
double gradientNoise(double x, double y, std::uint32_t seed);

struct FractalSettings {
  int octaves = 8;
  double lacunarity = 2;  ///< frequency ratio between octaves
  double H = 1;           ///< fractal increment: octave i is weighted lacunarity^(−iH)
  double gain = 2;        ///< ridged: how strongly an octave's signal damps the next ones
  double offset = 1;      ///< ridged: the ridge height before squaring
  std::uint32_t seed = 1;
};

/// \brief Fractional Brownian motion: Σ_i noise(p·lac^i) lac^(−iH), each octave its own seed.
double fbm(double x, double y, const FractalSettings& s);

/// \brief Musgrave's ridged multifractal: signal (offset − |noise|)², each octave weighted by
/// the previous signal × gain (clamped to [0, 1]) and by lac^(−iH). Non-negative.
double ridgedMultifractal(double x, double y, const FractalSettings& s);

}  // namespace radkit
