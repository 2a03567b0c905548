// Tensor Gauss–Legendre rules on patch pairs and their error bound.
#include "radiosity/pair_rule.h"

#include <array>
#include <cmath>
#include <stdexcept>

#include "radiosity/quadrature.h"

// The kernel loop is vectorised over the points of b. GCC builds an AVX2 clone beside the
// portable one and picks at load time; "avx2" alone enables no FMA, so both clones round
// identically and F does not depend on the CPU.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define RADKIT_KERNEL_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define RADKIT_KERNEL_CLONES
#endif

namespace radkit {

namespace {

// C_n of the bound: 3 × the largest |F_n − F| / (F ρ^(2n) (1 + 1/cosA)(1 + 1/cosB)) over
// 20 000 random triangles, parallelograms and twisted quads at ρ in [0.02, 0.6] (fitted
// 0.1355, 0.0337, 0.00802, 0.000770 by PairRule.DISABLED_FitBoundConstants;
// PairRule.BoundHoldsOnRandomPairs checks the bound on other pairs).
constexpr std::array<double, kMaxPairLevel + 1> kBoundConstant = {0, 0.41, 0.10, 0.024, 0.0023};

const GaussLegendreRule& rule(int n) {
  static const std::array<GaussLegendreRule, kMaxPairLevel + 2> rules = [] {
    std::array<GaussLegendreRule, kMaxPairLevel + 2> r;
    for (int k = 1; k <= kMaxPairLevel + 1; ++k) r[k] = gaussLegendre(k);
    return r;
  }();
  return rules[n];
}

RADKIT_KERNEL_CLONES
double kernelSum(const PatchPoints& a, const PatchPoints& b, const double* u, const double* v) {
  // Σ_p u_p Σ_q v_q / |y_q − x_p|⁴, one accumulator per point of b: the loop over b carries
  // no reduction, so it vectorises without reassociating the sum (same result on every clone).
  alignas(32) double acc[PatchPoints::kCapacity] = {};
  const int m = b.padded;
  for (int p = 0; p < a.count; ++p) {
    const double ax = a.x[p], ay = a.y[p], az = a.z[p], up = u[p];
    for (int q = 0; q < m; ++q) {
      const double dx = b.x[q] - ax, dy = b.y[q] - ay, dz = b.z[q] - az;
      const double r2 = dx * dx + dy * dy + dz * dz;
      acc[q] += up / (r2 * r2);
    }
  }
  double sum = 0;
  for (int q = 0; q < m; ++q) sum += v[q] * acc[q];
  return sum;
}

}  // namespace

PairSeparation pairSeparation(const PatchInfo& a, const PatchInfo& b) {
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

double pairRuleBound(int n, const PairSeparation& s) {
  if (n < 1 || n > kMaxPairLevel) throw std::invalid_argument("pair rule level out of range");
  if (!(s.rho < 1) || !(s.cosA > 0) || !(s.cosB > 0)) return INFINITY;
  double rho2 = s.rho * s.rho, power = 1;
  for (int k = 0; k < n; ++k) power *= rho2;
  return kBoundConstant[n] * power * (1 + 1 / s.cosA) * (1 + 1 / s.cosB);
}

int selectPairLevel(const PairSeparation& s, double tolerance, int maxLevel) {
  if (!(s.rho < 1) || !(s.cosA > 0) || !(s.cosB > 0)) return 0;
  // pairRuleBound level by level, with the common factors computed once.
  const double rho2 = s.rho * s.rho, scaled = tolerance / ((1 + 1 / s.cosA) * (1 + 1 / s.cosB));
  double power = rho2;
  for (int n = 1; n <= std::min(maxLevel, kMaxPairLevel); ++n, power *= rho2)
    if (kBoundConstant[n] * power <= scaled) return n;
  return 0;
}

void patchPoints(const PatchInfo& p, int n, PatchPoints& out) {
  if (n < 1 || n > kMaxPairLevel) throw std::invalid_argument("pair rule level out of range");
  int k = 0;
  if (n == 1) {
    // The chart's midpoint is not the area centroid (Duffy triangles, non-parallelogram
    // quads); only the centroid makes the one-point rule exact for linear functions.
    out.x[0] = p.centroid.x, out.y[0] = p.centroid.y, out.z[0] = p.centroid.z;
    out.w[0] = p.area;
    k = 1;
  } else {
    // n×n points integrate every polynomial of degree 2n − 1 exactly over a parallelogram.
    // Through a Duffy triangle or a twisted bilinear quad, the Jacobian costs a degree: n + 1
    // points per axis (exact to degree 2n) keep the error at O(ρ^(2n)) like a parallelogram.
    const bool parallelogram = p.parallelogram;
    const int m = parallelogram ? n : n + 1;
    const GaussLegendreRule& r = rule(m);
    if (parallelogram && n == 3) {
      // Radon's 7-point rule, exact to degree 5 like 3×3 Gauss–Legendre with 2 points fewer
      // per side (Radon 1948; Stroud 1971, formula C2 5-1): on [−1, 1]² the centre with
      // weight 8/7, (0, ±√(14/15)) with 20/63 and (±√(3/5), ±√(1/3)) with 5/9.
      const double a = std::sqrt(14.0 / 15), b = std::sqrt(3.0 / 5), c = std::sqrt(1.0 / 3);
      const double xi[7] = {0, 0, 0, b, b, -b, -b}, eta[7] = {0, a, -a, c, -c, c, -c};
      const double weight[7] = {8.0 / 7, 20.0 / 63, 20.0 / 63, 5.0 / 9, 5.0 / 9, 5.0 / 9, 5.0 / 9};
      const Vec3 e1 = p.v[1] - p.v[0], e2 = p.v[3] - p.v[0];
      for (; k < 7; ++k) {
        Vec3 x = p.v[0] + e1 * (0.5 * (1 + xi[k])) + e2 * (0.5 * (1 + eta[k]));
        out.x[k] = x.x, out.y[k] = x.y, out.z[k] = x.z;
        out.w[k] = 0.25 * weight[k] * p.area;
      }
    } else if (parallelogram) {  // affine map, constant Jacobian: the common case, kept cheap
      const Vec3 e1 = p.v[1] - p.v[0], e2 = p.v[3] - p.v[0];
      for (int a = 0; a < m; ++a)
        for (int b = 0; b < m; ++b, ++k) {
          Vec3 x = p.v[0] + e1 * r.nodes[a] + e2 * r.nodes[b];
          out.x[k] = x.x, out.y[k] = x.y, out.z[k] = x.z;
          out.w[k] = r.weights[a] * r.weights[b] * p.area;
        }
    }
    PatchChart chart(p.v, p.count);
    for (int a = 0; a < m && !parallelogram; ++a)
      for (int b = 0; b < m; ++b, ++k) {
        double s = r.nodes[a], t = r.nodes[b];
        Vec3 x = chart.point(s, t);
        out.x[k] = x.x, out.y[k] = x.y, out.z[k] = x.z;
        out.w[k] = r.weights[a] * r.weights[b] * chart.jacobian(s, t);
      }
  }
  out.count = k;
  out.padded = (k + 3) / 4 * 4;
  for (; k < out.padded; ++k)
    out.x[k] = out.x[0], out.y[k] = out.y[0], out.z[k] = out.z[0], out.w[k] = 0;
}

double pairRuleFormFactor(const PatchInfo& a, const PatchPoints& pa, const PatchInfo& b,
                          const PatchPoints& pb) {
  // Every point of a lies in a's plane and every point of b in b's, so the cosine factors
  // separate: n_a·(y − x) = n_a·y − offset_a depends on y alone, −n_b·(y − x) on x alone.
  alignas(32) double u[PatchPoints::kCapacity], v[PatchPoints::kCapacity];
  for (int p = 0; p < pa.count; ++p)
    u[p] = pa.w[p] * (b.normal.x * pa.x[p] + b.normal.y * pa.y[p] + b.normal.z * pa.z[p] -
                      b.planeOffset);
  for (int q = 0; q < pb.padded; ++q)
    v[q] = pb.w[q] * (a.normal.x * pb.x[q] + a.normal.y * pb.y[q] + a.normal.z * pb.z[q] -
                      a.planeOffset);
  return kernelSum(pa, pb, u, v) / (M_PI * a.area);
}

bool inFrontOfEachOther(const PatchInfo& a, const PatchInfo& b, double tolerance) {
  for (int k = 0; k < b.count; ++k)
    if (a.height(b.v[k]) < -tolerance) return false;
  for (int k = 0; k < a.count; ++k)
    if (b.height(a.v[k]) < -tolerance) return false;
  return true;
}

}  // namespace radkit
