// Per-pair quadrature for point-polygon: a tensor Gauss–Legendre rule over both patches with
// the point-to-point kernel (at level 3 for two parallelograms a 24-pair rule on their 4-D
// product instead), chosen per pair from an a-priori error bound. Pairs no rule can
// serve within the tolerance (near pairs, shared edges, one patch straddling the other's
// plane) keep the adaptive contour cubature (quadrature.h).
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

#include "radiosity/patch_pairs.h"

namespace radkit {

/// Highest level the selector picks: n = 8 is 8×8 points per patch, 4 096 kernel evaluations
/// (about 5 µs), still cheaper than the adaptive contour on the near pairs levels 5–8 took over.
constexpr int kMaxPairLevel = 8;
/// Levels PatchPointCache keeps for every patch; the rarer higher ones are computed per pair.
constexpr int kCachedPairLevels = 4;

/// How far apart two patches are, as the error bound of the tensor rules needs it.
struct PairSeparation {
  double rho = INFINITY;  ///< (r_a + r_b) / |c_b − c_a|, r the bounding radius about centroid c
  double cosA = 0;        ///< n_a · (c_b − c_a)/|c_b − c_a|
  double cosB = 0;        ///< n_b · (c_a − c_b)/|c_b − c_a|
};

/// \brief The separation of a pair; rho = +inf when the centroids coincide. Inline: it runs
/// for every facing pair.
inline PairSeparation pairSeparation(const PatchInfo& a, const PatchInfo& b) {
  PairSeparation s;
  Vec3 d = b.centroid - a.centroid;
  double length2 = dot(d, d);
  if (!(length2 > 0)) return s;
  double inverse = 1 / std::sqrt(length2);
  s.rho = (a.sphereRadius + b.sphereRadius) * inverse;
  s.cosA = dot(a.normal, d) * inverse;
  s.cosB = -dot(b.normal, d) * inverse;
  return s;
}

/// \brief Bound on the relative error |F_n − F| / F of the level-n rule:
/// C_n ρ^(2n) (1 + 1/cosA)(1 + 1/cosB). The rule's error is a 2n-th derivative of the
/// kernel times size^(2n); the derivatives that fall on a cosine add the 1/cos terms, which
/// grow as the pair turns edge-on. C_n fitted on random pairs with a margin
/// (docs/formfactors.md), checked on other random pairs by tests/radiosity/pair_rule_test.cpp.
/// +inf for ρ >= 1 or a cosine <= 0.
double pairRuleBound(int n, const PairSeparation& s);

/// C_n of pairRuleBound, index n (docs/formfactors.md has how they were fitted).
inline constexpr double kPairBoundConstant[kMaxPairLevel + 1] = {
    0, 0.41, 0.10, 0.024, 0.0023, 6.0e-4, 7.5e-5, 1.2e-5, 2.2e-6};

/// \brief The cheapest level in [1, maxLevel] whose bound is at most `tolerance` (relative
/// error of F_ab); 0 when none is, meaning: use the adaptive contour cubature.
inline int selectPairLevel(const PairSeparation& s, double tolerance,
                           int maxLevel = kMaxPairLevel) {
  if (!(s.rho < 1) || !(s.cosA > 0) || !(s.cosB > 0)) return 0;
  // pairRuleBound <= tolerance with its cosine factor multiplied out: no division.
  const double rho2 = s.rho * s.rho, factor = (s.cosA + 1) * (s.cosB + 1);
  const double allowed = tolerance * s.cosA * s.cosB;
  double power = rho2;
  const int top = maxLevel < kMaxPairLevel ? maxLevel : kMaxPairLevel;
  for (int n = 1; n <= top; ++n) {
    if (kPairBoundConstant[n] * power * factor <= allowed) return n;
    power *= rho2;
  }
  return 0;
}

/// The level-n points of a patch, structure of arrays, weights = area elements (they sum to
/// the area): the centroid for n = 1; n×n Gauss–Legendre points for a parallelogram,
/// (n+1)×(n+1) for a triangle (Duffy map) or a twisted quad, so that every shape integrates
/// polynomials of degree 2n − 1 exactly. Padded to a multiple of 4 with zero-weight copies of
/// the first point so the kernel runs in whole vectors.
struct PatchPoints {
  static constexpr int kCapacity = ((kMaxPairLevel + 1) * (kMaxPairLevel + 1) + 3) / 4 * 4;
  alignas(32) double x[kCapacity], y[kCapacity], z[kCapacity], w[kCapacity];
  int count = 0;   ///< real points (n²)
  int padded = 0;  ///< count rounded up to a multiple of 4
};

/// Points of one patch at one level as the kernel reads them: arrays of `padded` numbers.
struct PointSet {
  const double *x = nullptr, *y = nullptr, *z = nullptr, *w = nullptr;
  int count = 0, padded = 0;
  PointSet() = default;
  PointSet(const PatchPoints& p)  // NOLINT: a view of the struct, implicit by design
      : x(p.x), y(p.y), z(p.z), w(p.w), count(p.count), padded(p.padded) {}
};

/// \brief The 8 points of a parallelogram the product rule uses, in its [−1, 1]² chart about
/// the centroid: (±t, ±t) with t = 1/√2, then (±r, 0) and (0, ±r) with r = √(4/5). Weights
/// are left 0: the rule's weights belong to pairs of points (productRulePairs).
void productPoints(const PatchInfo& p, PatchPoints& out);

/// \brief Level 3 for two parallelograms: a degree-5 rule on the 4-D product of the patches
/// with 24 point pairs where the tensor of two 7-point rules takes 49. The 16 pairs of
/// corner points (±t, ±t) × (±t, ±t) weigh 1/36 each; a's 4 axis points against b's
/// centroid and a's centroid against b's 4 axis points 5/72 each (the fully symmetric
/// 4-cube rule whose centre weight vanishes: E[x²] = 1/3, E[x⁴] = 1/5, E[x²y²] = 1/9 fix
/// t² = 1/2, r² = 4/5). pa, pb from productPoints. Same conditions as pairRuleFormFactor.
double productRuleFormFactor(const PatchInfo& a, const PointSet& pa, const PatchInfo& b,
                             const PointSet& pb);

/// \brief The product rule's 24 point pairs (x_k on a, y_k on b) and weights, which sum to
/// A_a A_b: F_ab = Σ w_k K(x_k, y_k) / (π A_a). For tests; the kernel above reads the cache.
int productRulePairs(const PatchInfo& a, const PatchInfo& b, Vec3* x, Vec3* y, double* w);

/// The level-1..maxLevel points of every patch of a table, computed once and shared by all
/// rows, and the product rule's points of parallelograms: 40 points (1.25 KiB) per
/// parallelogram patch at maxLevel 4, 60 for other shapes.
class PatchPointCache {
 public:
  PatchPointCache(const PatchTable& table, int maxLevel);
  /// \brief The level-n points of patch i, 1 <= n <= maxLevel.
  PointSet points(int i, int n) const {
    const std::size_t slot = std::size_t(i) * (m_levels + 1) + (n - 1);
    const double* base = m_pool.data() + m_offset[slot];
    const std::ptrdiff_t padded = m_padded[slot];
    PointSet s;
    s.x = base, s.y = base + padded, s.z = base + 2 * padded, s.w = base + 3 * padded;
    s.count = m_count[slot], s.padded = m_padded[slot];
    return s;
  }
  /// \brief The product rule's points of parallelogram i (maxLevel >= 3).
  PointSet productPoints(int i) const { return points(i, m_levels + 1); }

 private:
  int m_levels = 0;
  std::vector<std::size_t> m_offset;
  std::vector<int> m_count, m_padded;
  std::vector<double> m_pool;
};

/// \brief Fills `out` with the level-n points of p, 1 <= n <= kMaxPairLevel.
void patchPoints(const PatchInfo& p, int n, PatchPoints& out);

/// \brief F_ab = (1/(π A_a)) Σ_p Σ_q w_p w_q (n_a·d)(−n_b·d)/|d|⁴, d = y_q − x_p: the tensor
/// rule for the unoccluded form factor. Valid only when no part of either patch lies behind
/// the other's plane (the kernel's cosines are then never clipped) and the patches are apart.
double pairRuleFormFactor(const PatchInfo& a, const PointSet& pa, const PatchInfo& b,
                          const PointSet& pb);

/// \brief True when every vertex of b is on or in front of a's plane and every vertex of a
/// on or in front of b's (within `tolerance`): the condition for pairRuleFormFactor.
bool inFrontOfEachOther(const PatchInfo& a, const PatchInfo& b, double tolerance);

}  // namespace radkit
