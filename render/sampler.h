// Samplers: the numbers a camera sample consumes, dimension by dimension. Independent
// (today's streams), stratified (jittered, per dimension and per pair of dimensions), and
// Owen-scrambled Sobol (0,2)-sequences padded pair by pair (Burley 2020, "Practical
// Hash-based Owen Scrambling", JCGT 9(4)): each pair of dimensions of each pixel gets its own
// scramble and its own shuffle of the sample index, so pixels and dimensions are decorrelated
// while every power-of-two prefix of a pixel's samples stays a (0,m,2)-net.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>

#include "util/sampling.h"

namespace radkit {

enum class SamplerType { Independent, Stratified, Sobol };

/// "independent", "stratified" or "sobol"; throws std::invalid_argument otherwise.
SamplerType parseSamplerType(const std::string& name);
std::string samplerName(SamplerType type);

/// Numbers in [0, 1) for sample `index` of pixel `pixel`: get1D/get2D walk through the
/// dimensions; start() rewinds to dimension 0. Deterministic in (seed, stream, pixel, index).
class Sampler {
 public:
  virtual ~Sampler() = default;
  /// \brief Begins sample `index` of `pixel`. The independent sampler continues one stream per
  /// pixel, so its indices must come in order 0, 1, 2, ...; the others are random access.
  virtual void start(std::uint64_t pixel, int index) = 0;
  virtual double get1D() = 0;
  virtual std::array<double, 2> get2D() = 0;
  /// \brief Passes over a 1-D dimension, as get1D() would, without the number where that
  /// saves work: the dimensions after it are the same either way.
  virtual void skip1D() { get1D(); }
  /// \brief get1D() if `used`, else skip1D() and 0: for numbers a scene may not need (a
  /// choice among one emitter, or among the lobes of a single-lobe BSDF).
  double get1DIfUsed(bool used) {
    if (used) return get1D();
    skip1D();
    return 0;
  }
};

/// \param samplesPerPixel strata count (stratified), power-of-two block of indices (Sobol)
std::unique_ptr<Sampler> makeSampler(SamplerType type, std::uint64_t seed, std::uint64_t stream,
                                     int samplesPerPixel);

/// \name Building blocks (exposed for tests)
/// \{
/// Sobol's first two dimensions (van der Corput and the Pascal matrix): a (0,2)-sequence,
/// 32-bit fixed point.
std::uint32_t sobol0(std::uint32_t index);
std::uint32_t sobol1(std::uint32_t index);
/// reverseBits(sobol1(index)), tabulated directly.
std::uint32_t reversedSobol1(std::uint32_t index);
/// \brief Owen (nested uniform) scrambling of a 32-bit fraction: bit b flips by a hash of the
/// seed and the bits above b (Laine & Karras 2011 hash with Burley's constants).
std::uint32_t owenScramble(std::uint32_t x, std::uint32_t seed);
/// \brief A random permutation of [0, n) keyed by seed: cycle-walking an Owen scramble of
/// the index's bits, which permutes every aligned power-of-two block.
std::uint32_t permuteIndex(std::uint32_t i, std::uint32_t n, std::uint32_t seed);
/// \brief A random permutation of [0, n) keyed by seed with no nested structure (for strata,
/// whose order must not correlate dimensions): cycle-walking rounds of small bijections.
std::uint32_t shuffleIndex(std::uint32_t i, std::uint32_t n, std::uint64_t seed);
/// \}

}  // namespace radkit
