#include "render/sampler.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace radkit {

namespace {

std::uint32_t reverseBits(std::uint32_t x) {
  x = __builtin_bswap32(x);  // the bytes in one instruction, then the bits within each byte
  x = ((x & 0x0f0f0f0fu) << 4) | ((x & 0xf0f0f0f0u) >> 4);
  x = ((x & 0x33333333u) << 2) | ((x & 0xccccccccu) >> 2);
  x = ((x & 0x55555555u) << 1) | ((x & 0xaaaaaaaau) >> 1);
  return x;
}

std::uint64_t mix(std::uint64_t a, std::uint64_t b) { return splitMix64(a ^ splitMix64(b)); }

double toUnit(std::uint32_t x) { return x * 0x1p-32; }

/// The hash of owenScramble, acting on bit-reversed digits (Laine & Karras 2011's form with
/// Burley 2020's constants).
std::uint32_t laineKarras(std::uint32_t x, std::uint32_t seed) {
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return x;
}
double toUnit64(std::uint64_t x) { return (x >> 11) * 0x1p-53; }

/// Today's streams: one Rng per pixel, consumed in order across its samples.
class IndependentSampler : public Sampler {
 public:
  IndependentSampler(std::uint64_t seed, std::uint64_t stream)
      : m_seed(seed), m_stream(stream), m_rng(0, 0, 0) {}
  void start(std::uint64_t pixel, int index) override {
    if (index == 0 || pixel != m_pixel) m_rng = Rng(m_seed, pixel, m_stream);
    m_pixel = pixel;
  }
  double get1D() override { return m_rng.uniform(); }
  std::array<double, 2> get2D() override {
    const double a = m_rng.uniform();
    return {a, m_rng.uniform()};
  }

 private:
  std::uint64_t m_seed, m_stream, m_pixel = ~std::uint64_t(0);
  Rng m_rng;
};

/// Shared bookkeeping of the padded samplers: a key per pixel, a dimension counter.
class PaddedSampler : public Sampler {
 public:
  PaddedSampler(std::uint64_t seed, std::uint64_t stream) : m_key(mix(seed, stream)) {}
  void start(std::uint64_t pixel, int index) override {
    if (pixel != m_pixel || m_keys.empty()) {
      m_pixel = pixel;
      m_pixelKey = mix(m_key, pixel);
      m_keys.clear();
    }
    m_index = std::uint32_t(index);
    m_dimension = 0;
  }
  void skip1D() override { nextDimensionKeys(); }  // hashed once per pixel, then looked up

 protected:
  /// A dimension's two keys: the second, splitMix64 of the first, for a pair's other half.
  struct Keys {
    std::uint64_t first, second;
  };
  /// The keys depend on the pixel and the dimension, not on the sample: a pixel's samples
  /// come one after another, so they are hashed once per pixel and dimension and reused.
  const Keys& nextDimensionKeys() {
    if (m_dimension == m_keys.size()) {
      const std::uint64_t k = splitMix64(m_pixelKey + 0x9e3779b97f4a7c15ull * (m_dimension + 1));
      m_keys.push_back({k, splitMix64(k)});
    }
    return m_keys[m_dimension++];
  }
  std::uint64_t m_key = 0, m_pixelKey = 0, m_pixel = ~std::uint64_t(0);
  std::size_t m_dimension = 0;
  std::vector<Keys> m_keys;
  std::uint32_t m_index = 0;
};

/// Jittered strata: n strata per dimension, ⌊√n⌋² cells per pair, each dimension (pair)
/// visiting its strata in its own random order (shuffleIndex: a nested permutation would
/// send the first half of the samples to the same half of every dimension, correlating
/// them). Samples beyond the strata are independent.
class StratifiedSampler : public PaddedSampler {
 public:
  StratifiedSampler(std::uint64_t seed, std::uint64_t stream, int samples)
      : PaddedSampler(seed, stream),
        m_n(std::uint32_t(std::max(1, samples))),
        m_side(std::uint32_t(std::floor(std::sqrt(double(m_n))))) {}
  double get1D() override {
    const std::uint64_t key = nextDimensionKeys().first;
    const double jitter = toUnit64(mix(key, m_index));
    if (m_index >= m_n) return jitter;
    return (shuffleIndex(m_index, m_n, key) + jitter) / m_n;
  }
  std::array<double, 2> get2D() override {
    const std::uint64_t key = nextDimensionKeys().first;
    const std::uint64_t bits = mix(key, m_index);
    const double jx = toUnit(std::uint32_t(bits)), jy = toUnit(std::uint32_t(bits >> 32));
    if (m_index >= m_side * m_side) return {jx, jy};
    const std::uint32_t cell = shuffleIndex(m_index, m_side * m_side, key);
    const std::uint32_t column = cell % m_side, row = cell / m_side;  // the jittered cell
    return {(column + jx) / m_side, (row + jy) / m_side};
  }

 private:
  std::uint32_t m_n, m_side;
};

/// Shuffled indices stay in the first power-of-two block that holds the pixel's samples (a
/// nested scramble maps [0, 2^k) onto itself once the digits above k are masked off), so
/// each power-of-two prefix of them is still a net, and sobol1 meets only k bits.
/// The arithmetic stays in bit-reversed form where it can (the index is reversed once per
/// sample, sobol1 is tabulated reversed): a sample costs three bit reversals per pair
/// instead of five, for the same numbers.
class SobolSampler : public PaddedSampler {
 public:
  SobolSampler(std::uint64_t seed, std::uint64_t stream, int samples)
      : PaddedSampler(seed, stream) {
    while (m_mask < std::uint32_t(std::max(1, samples) - 1)) m_mask = (m_mask << 1) | 1;
    m_reversedMask = reverseBits(m_mask);
  }
  void start(std::uint64_t pixel, int index) override {
    PaddedSampler::start(pixel, index);
    m_reversedIndex = reverseBits(m_index);
  }
  // owenScramble(sobol0(i), s) = reverse(LK(i, s)): sobol0 is itself a reversal.
  double get1D() override {
    const std::uint64_t key = nextDimensionKeys().first;
    return toUnit(reverseBits(laineKarras(shuffled(std::uint32_t(key)), std::uint32_t(key >> 32))));
  }
  std::array<double, 2> get2D() override {
    const Keys& keys = nextDimensionKeys();
    const std::uint64_t key = keys.first, key2 = keys.second;
    const std::uint32_t i = shuffled(std::uint32_t(key));
    // owenScramble(sobol1(i), s) = reverse(LK(reverse(sobol1(i)), s)).
    return {toUnit(reverseBits(laineKarras(i, std::uint32_t(key >> 32)))),
            toUnit(reverseBits(laineKarras(reversedSobol1(i), std::uint32_t(key2))))};
  }

 private:
  /// owenScramble(index, seed), masked to the block: reverse(LK(reverse(index), seed)).
  /// Indices past the block (more samples than declared) keep their higher digits.
  std::uint32_t shuffled(std::uint32_t seed) const {
    const std::uint32_t r = laineKarras(m_reversedIndex, seed);
    return reverseBits(m_index > m_mask ? r : r & m_reversedMask);
  }
  std::uint32_t m_mask = 0, m_reversedMask = 0, m_reversedIndex = 0;
};

}  // namespace

SamplerType parseSamplerType(const std::string& name) {
  if (name == "independent") return SamplerType::Independent;
  if (name == "stratified") return SamplerType::Stratified;
  if (name == "sobol") return SamplerType::Sobol;
  throw std::invalid_argument("unknown sampler \"" + name +
                              "\" (independent, stratified or sobol)");
}

std::string samplerName(SamplerType type) {
  switch (type) {
    case SamplerType::Independent:
      return "independent";
    case SamplerType::Stratified:
      return "stratified";
    case SamplerType::Sobol:
      return "sobol";
  }
  return "?";
}

std::unique_ptr<Sampler> makeSampler(SamplerType type, std::uint64_t seed, std::uint64_t stream,
                                     int samplesPerPixel) {
  switch (type) {
    case SamplerType::Independent:
      return std::make_unique<IndependentSampler>(seed, stream);
    case SamplerType::Stratified:
      return std::make_unique<StratifiedSampler>(seed, stream, samplesPerPixel);
    case SamplerType::Sobol:
      return std::make_unique<SobolSampler>(seed, stream, samplesPerPixel);
  }
  throw std::invalid_argument("makeSampler: unknown sampler type");
}

std::uint32_t sobol0(std::uint32_t index) { return reverseBits(index); }

namespace {
using Sobol1Table = std::array<std::array<std::uint32_t, 256>, 4>;
/// Column j of the Pascal matrix mod 2, as a 32-bit fraction: v_{j+1} = v_j ^ (v_j >> 1).
/// The matrix-vector product is linear over GF(2): tabulate it a byte of the index at a
/// time, the columns bit-reversed or not.
Sobol1Table makeSobol1Table(bool reversed) {
  Sobol1Table t{};
  std::uint32_t column[32];
  column[0] = 1u << 31;
  for (int j = 1; j < 32; ++j) column[j] = column[j - 1] ^ (column[j - 1] >> 1);
  for (int b = 0; b < 4; ++b)
    for (int byte = 0; byte < 256; ++byte)
      for (int j = 0; j < 8; ++j)
        if (byte >> j & 1)
          t[b][byte] ^= reversed ? reverseBits(column[8 * b + j]) : column[8 * b + j];
  return t;
}
std::uint32_t applySobol1(const Sobol1Table& t, std::uint32_t index) {
  return t[0][index & 255] ^ t[1][index >> 8 & 255] ^ t[2][index >> 16 & 255] ^ t[3][index >> 24];
}
/// At namespace scope, not a function's static: the sampler reads it per 2-D sample, and a
/// function-local static costs a call and a guard check there.
const Sobol1Table kReversedSobol1 = makeSobol1Table(true);
}  // namespace

std::uint32_t sobol1(std::uint32_t index) {
  static const Sobol1Table table = makeSobol1Table(false);
  return applySobol1(table, index);
}

std::uint32_t reversedSobol1(std::uint32_t index) { return applySobol1(kReversedSobol1, index); }

std::uint32_t owenScramble(std::uint32_t x, std::uint32_t seed) {
  // Reversed, the most significant digit becomes bit 0; additions and x ^= x·even then only
  // carry upward, so each digit flips by a function of the seed and the digits above it.
  return reverseBits(laineKarras(reverseBits(x), seed));
}

std::uint32_t shuffleIndex(std::uint32_t i, std::uint32_t n, std::uint64_t seed) {
  int bits = 0;
  while ((std::uint64_t(1) << bits) < n) ++bits;
  const std::uint32_t mask = bits == 32 ? ~0u : (1u << bits) - 1;
  // Rounds of bijections of [0, 2^bits): xor, multiply by an odd number (mixes upward),
  // xorshift right (mixes downward); cycle-walk until the result lies below n.
  do {
    std::uint64_t key = seed;
    for (int round = 0; round < 4; ++round) {
      key = splitMix64(key);
      i = (i ^ std::uint32_t(key)) & mask;
      i = (i * (std::uint32_t(key >> 32) | 1u)) & mask;
      if (bits > 1) i ^= i >> ((bits + 1) / 2);
    }
  } while (i >= n);
  return i;
}

std::uint32_t permuteIndex(std::uint32_t i, std::uint32_t n, std::uint32_t seed) {
  std::uint32_t mask = 0;
  while (mask < n - 1) mask = (mask << 1) | 1;
  // Indices below 2^k have zero digits above k, which scramble to a constant: the low k
  // bits alone are a permutation of [0, 2^k). Walk its cycle until it lands below n.
  do i = owenScramble(i, seed) & mask;
  while (i >= n);
  return i;
}

}  // namespace radkit
