// Sampling warps: each maps [0,1)² onto its domain with the density stated in sampling.h.
#include "util/sampling.h"

#include <algorithm>
#include <cmath>

namespace radkit {

namespace {
constexpr std::uint64_t kGolden = 0x9E3779B97F4A7C15ull;
}

std::uint64_t splitMix64(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

Rng::Rng(std::uint64_t seed, std::uint64_t a, std::uint64_t b)
    : m_state(splitMix64(splitMix64(splitMix64(seed + kGolden) ^ a) + kGolden * (b + 1))) {}

std::uint64_t Rng::nextBits() {
  m_state += kGolden;
  return splitMix64(m_state);
}

double Rng::uniform() { return double(nextBits() >> 11) * 0x1.0p-53; }

void latinHypercube(int K, int dims, Rng& rng, std::vector<double>& out,
                    std::vector<int>& scratch) {
  out.resize(static_cast<std::size_t>(K) * dims);
  scratch.resize(K);
  for (int d = 0; d < dims; ++d) {
    for (int k = 0; k < K; ++k) scratch[k] = k;
    for (int k = K - 1; k > 0; --k) {  // Fisher–Yates
      // Lemire's multiply-shift: an index in [0, k] from the high 32 bits.
      int r = static_cast<int>(((rng.nextBits() >> 32) * std::uint64_t(k + 1)) >> 32);
      std::swap(scratch[k], scratch[r]);
    }
    for (int k = 0; k < K; ++k)
      out[static_cast<std::size_t>(k) * dims + d] = (scratch[k] + rng.uniform()) / K;
  }
}

Vec3 sampleUniformTriangle(const Vec3& a, const Vec3& b, const Vec3& c, double u0, double u1) {
  double su = std::sqrt(u0);
  double b0 = 1 - su, b1 = u1 * su;
  return a * b0 + b * b1 + c * (1 - b0 - b1);
}

void invertUniformTriangleSample(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& p,
                                 double& u0, double& u1) {
  // Barycentrics of p by area ratios, then u0 = (1 − b0)², u1 = b1/(1 − b0).
  Vec3 normal = cross(b - a, c - a);
  double area2 = dot(normal, normal);
  double b0 = dot(cross(b - p, c - p), normal) / area2;
  double b1 = dot(cross(c - p, a - p), normal) / area2;
  u0 = (1 - b0) * (1 - b0);
  u1 = b0 < 1 ? b1 / (1 - b0) : 0.0;
}

double patchSplit(const Vec3* v, int count) {
  if (count == 3) return 1.0;
  double a0 = length(cross(v[1] - v[0], v[2] - v[0]));
  double a1 = length(cross(v[2] - v[0], v[3] - v[0]));
  return a0 / (a0 + a1);
}

Vec3 samplePatchUniform(const Vec3* v, int count, double u0, double u1) {
  return samplePatchUniform(v, count, patchSplit(v, count), u0, u1);
}

Vec3 samplePatchUniform(const Vec3* v, int count, double split, double u0, double u1) {
  if (count == 3 || split >= 1) return sampleUniformTriangle(v[0], v[1], v[2], u0, u1);
  // Reusing u0 after rescaling keeps the Latin-hypercube stratification of the input.
  if (u0 < split) return sampleUniformTriangle(v[0], v[1], v[2], u0 / split, u1);
  return sampleUniformTriangle(v[0], v[2], v[3], std::min((u0 - split) / (1 - split), 1.0), u1);
}

DiscreteDistribution::DiscreteDistribution(const std::vector<double>& weights) {
  double total = 0;
  for (double w : weights) total += w > 0 ? w : 0;  // negative and NaN weights count as 0
  if (!(total > 0) || !std::isfinite(total)) return;
  m_cdf.resize(weights.size());
  double running = 0;
  for (std::size_t i = 0; i < weights.size(); ++i) {
    running += weights[i] > 0 ? weights[i] : 0;
    m_cdf[i] = running / total;
  }
  m_cdf.back() = 1;
}

std::size_t DiscreteDistribution::sample(double u, double* remapped) const {
  // The first entry whose cumulative probability exceeds u; zero-weight entries have empty
  // intervals and are never chosen.
  const std::size_t i = std::min<std::size_t>(
      std::size_t(std::upper_bound(m_cdf.begin(), m_cdf.end(), u) - m_cdf.begin()),
      m_cdf.size() - 1);
  if (remapped) {
    const double lo = i ? m_cdf[i - 1] : 0, width = m_cdf[i] - lo;
    *remapped =
        width > 0 ? std::min(std::max((u - lo) / width, 0.0), std::nextafter(1.0, 0.0)) : 0.5;
  }
  return i;
}

double DiscreteDistribution::probability(std::size_t i) const {
  if (i >= m_cdf.size()) return 0;
  return m_cdf[i] - (i ? m_cdf[i - 1] : 0);
}

SkySampler::SkySampler(const std::function<Vec3(const Vec3&)>& sky, bool upperOnly, int rows,
                       int columns, double uniformFraction)
    : m_rows(std::max(1, rows)),
      m_columns(std::max(1, columns)),
      m_uniform(std::min(std::max(uniformFraction, 0.0), 1.0)) {
  // Each cell spans the same solid angle 4π/(rows·columns); its weight is the mean radiance at
  // 2 × 2 points inside it, so a bright sun aureole is not missed between cell centres.
  std::vector<double> weights(std::size_t(m_rows) * m_columns, 0.0);
  for (int r = 0; r < m_rows; ++r)
    for (int c = 0; c < m_columns; ++c) {
      double w = 0;
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) {
          const double mu = 1 - 2 * (r + (i + 0.5) / 2) / m_rows;
          if (upperOnly && mu <= 0) continue;
          const Vec3 L = sky(localDirection(mu, 2 * kPi * (c + (j + 0.5) / 2) / m_columns));
          if (std::isfinite(L.x + L.y + L.z)) w += std::max(0.0, (L.x + L.y + L.z) / 3);
        }
      weights[std::size_t(r) * m_columns + c] = w;
    }
  m_cells = DiscreteDistribution(weights);
  if (m_cells.size() == 0) m_uniform = 1;  // a black sky: uniform directions only
}

std::size_t SkySampler::cell(const Vec3& d) const {
  const int r = std::min(m_rows - 1, std::max(0, int((1 - d.z) / 2 * m_rows)));
  double phi = std::atan2(d.y, d.x);
  if (phi < 0) phi += 2 * kPi;
  const int c = std::min(m_columns - 1, std::max(0, int(phi / (2 * kPi) * m_columns)));
  return std::size_t(r) * m_columns + c;
}

Vec3 SkySampler::sample(double u0, double u1, double u2, double& pdf) const {
  Vec3 d;
  if (u0 < m_uniform) {
    d = localDirection(1 - 2 * u1, 2 * kPi * u2);
  } else {
    // A cell by its weight, then a uniform point in it (uniform in cos θ and φ is uniform in
    // solid angle); u1 remapped inside the chosen cell's interval picks the row offset.
    double v;
    const std::size_t i = m_cells.sample(u1, &v);
    const int r = int(i / std::size_t(m_columns)), c = int(i % std::size_t(m_columns));
    d = localDirection(1 - 2 * (r + v) / m_rows, 2 * kPi * (c + u2) / m_columns);
  }
  pdf = this->pdf(d);
  return d;
}

double SkySampler::pdf(const Vec3& d) const {
  const double uniform = 1 / (4 * kPi);
  if (m_uniform >= 1) return uniform;
  const double cellSolidAngle = 4 * kPi / (double(m_rows) * m_columns);
  return m_uniform * uniform + (1 - m_uniform) * m_cells.probability(cell(d)) / cellSolidAngle;
}

}  // namespace radkit
