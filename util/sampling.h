// Random streams and sampling warps for the form-factor estimators. Every warp has its pdf
// beside it and, where cheap, its inverse (pbrt-v4 util/sampling.h, Nori warp.h).
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "util/frame.h"
#include "util/vec3.h"

namespace radkit {

/// SplitMix64 finaliser (Steele, Lea & Flood 2014): a bijective 64-bit mixer.
std::uint64_t splitMix64(std::uint64_t z);

/// A counter-based random stream: output k is splitMix64(key + k·golden). Streams keyed by
/// (seed, i, j) give the same numbers whatever thread computes them.
class Rng {
 public:
  /// \brief Stream for the ordered key (seed, a, b).
  Rng(std::uint64_t seed, std::uint64_t a, std::uint64_t b);
  std::uint64_t nextBits();
  /// \brief Uniform double in [0, 1) with 53 random bits.
  double uniform();

 private:
  std::uint64_t m_state;
};

/// \brief Latin-hypercube samples: K points in [0,1)^dims, each dimension stratified into K
/// intervals (one point each) and randomly permuted independently. out[k·dims + d].
void latinHypercube(int K, int dims, Rng& rng, std::vector<double>& out, std::vector<int>& scratch);

/// \brief Uniform point on triangle abc: barycentrics (1−√u0, u1√u0).
Vec3 sampleUniformTriangle(const Vec3& a, const Vec3& b, const Vec3& c, double u0, double u1);
/// \brief Inverse of sampleUniformTriangle for a point p in the triangle.
void invertUniformTriangleSample(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& p,
                                 double& u0, double& u1);

/// \brief Uniform point on a planar convex patch (triangle or quad; a quad is split into the
/// triangles (0,1,2) and (0,2,3), chosen by u0 in proportion to area). Density 1/area.
Vec3 samplePatchUniform(const Vec3* v, int count, double u0, double u1);
/// \brief The same with the first triangle's share of the area precomputed (patchSplit).
Vec3 samplePatchUniform(const Vec3* v, int count, double split, double u0, double u1);
/// \brief Area of triangle (0,1,2) over the patch area (1 for triangles).
double patchSplit(const Vec3* v, int count);
/// \brief Density per unit area of samplePatchUniform: 1/area on the patch.
inline double patchUniformPdf(double area) { return 1.0 / area; }

/// \brief Power heuristic with β = 2 (Veach 1997, eq. 9.13): f² / (f² + g²), the multiple
/// importance sampling weight of the strategy with density f against the one with g.
inline double powerHeuristic(double f, double g) {
  const double f2 = f * f, g2 = g * g;
  return f2 + g2 > 0 ? f2 / (f2 + g2) : 0.0;
}

/// Indices 0..n−1 drawn with probability proportional to non-negative weights, by binary
/// search of the cumulative sum. An all-zero (or empty) table draws nothing: size() == 0.
class DiscreteDistribution {
 public:
  DiscreteDistribution() = default;
  explicit DiscreteDistribution(const std::vector<double>& weights);
  /// \brief The index whose CDF interval holds u ∈ [0, 1); `remapped`, when given, gets u's
  /// position inside that interval, a fresh uniform number for the next choice.
  std::size_t sample(double u, double* remapped = nullptr) const;
  double probability(std::size_t i) const;
  std::size_t size() const { return m_cdf.size(); }

 private:
  std::vector<double> m_cdf;  ///< m_cdf[i] = P(index ≤ i), m_cdf.back() == 1
};

/// \brief Directions drawn in proportion to a sky's radiance (the mean of its channels),
/// tabulated on an equal-area grid of cells in (cos θ, φ) and mixed with uniform sampling of
/// the sphere, so every direction keeps a density of at least uniformFraction/(4π): light a
/// cell's 2 × 2 probe points missed is still reached, and the estimator stays unbiased.
class SkySampler {
 public:
  /// The grid's axis is z. `upperOnly` leaves the cells with z < 0 empty (a ground there hides
  /// the sky).
  explicit SkySampler(const std::function<Vec3(const Vec3&)>& sky, bool upperOnly = false,
                      int rows = 64, int columns = 128, double uniformFraction = 0.1);
  /// A unit direction from three uniform numbers in [0, 1), with its density per steradian.
  Vec3 sample(double u0, double u1, double u2, double& pdf) const;
  /// Density per steradian of sample() drawing the unit direction d.
  double pdf(const Vec3& d) const;

 private:
  std::size_t cell(const Vec3& d) const;
  int m_rows, m_columns;
  double m_uniform;
  DiscreteDistribution m_cells;  ///< row-major, row 0 at the zenith (cos θ from 1 down)
};

}  // namespace radkit
