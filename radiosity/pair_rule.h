// Per-pair quadrature for point-polygon: a tensor Gauss–Legendre rule over both patches with
// the point-to-point kernel, chosen per pair from an a-priori error bound. Pairs no rule can
// serve within the tolerance (near pairs, shared edges, one patch straddling the other's
// plane) keep the adaptive contour cubature (quadrature.h).
#pragma once

#include <cmath>

#include "radiosity/patch_pairs.h"

namespace radkit {

/// Highest level the selector picks: n = 4 is 4×4 points per patch, 256 kernel evaluations.
constexpr int kMaxPairLevel = 4;

/// How far apart two patches are, as the error bound of the tensor rules needs it.
struct PairSeparation {
  double rho = INFINITY;  ///< (r_a + r_b) / |c_b − c_a|, r the bounding radius about centroid c
  double cosA = 0;        ///< n_a · (c_b − c_a)/|c_b − c_a|
  double cosB = 0;        ///< n_b · (c_a − c_b)/|c_b − c_a|
};

/// \brief The separation of a pair; rho = +inf when the centroids coincide.
PairSeparation pairSeparation(const PatchInfo& a, const PatchInfo& b);

/// \brief Bound on the relative error |F_n − F| / F of the level-n rule:
/// C_n ρ^(2n) (1 + 1/cosA)(1 + 1/cosB). The rule's error is a 2n-th derivative of the
/// kernel times size^(2n); the derivatives that fall on a cosine add the 1/cos terms, which
/// grow as the pair turns edge-on. C_n fitted on random pairs with a margin
/// (docs/formfactors.md), checked on other random pairs by tests/radiosity/pair_rule_test.cpp.
/// +inf for ρ >= 1 or a cosine <= 0.
double pairRuleBound(int n, const PairSeparation& s);

/// \brief The cheapest level in [1, maxLevel] whose bound is at most `tolerance` (relative
/// error of F_ab); 0 when none is, meaning: use the adaptive contour cubature.
int selectPairLevel(const PairSeparation& s, double tolerance, int maxLevel = kMaxPairLevel);

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

/// \brief Fills `out` with the level-n points of p, 1 <= n <= kMaxPairLevel.
void patchPoints(const PatchInfo& p, int n, PatchPoints& out);

/// \brief F_ab = (1/(π A_a)) Σ_p Σ_q w_p w_q (n_a·d)(−n_b·d)/|d|⁴, d = y_q − x_p: the tensor
/// rule for the unoccluded form factor. Valid only when no part of either patch lies behind
/// the other's plane (the kernel's cosines are then never clipped) and the patches are apart.
double pairRuleFormFactor(const PatchInfo& a, const PatchPoints& pa, const PatchInfo& b,
                          const PatchPoints& pb);

/// \brief True when every vertex of b is on or in front of a's plane and every vertex of a
/// on or in front of b's (within `tolerance`): the condition for pairRuleFormFactor.
bool inFrontOfEachOther(const PatchInfo& a, const PatchInfo& b, double tolerance);

}  // namespace radkit
