// Tensor Gauss–Legendre rules on patch pairs and their error bound.
#include "radiosity/pair_rule.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "radiosity/quadrature.h"
#include "util/target_clones.h"

// The kernel loops are vectorised over the points of b, with an AVX2 clone
// (util/target_clones.h).

namespace radkit {

namespace {

// kPairBoundConstant (pair_rule.h), C_n of the bound: 3 × the largest
// |F_n − F| / (F ρ^(2n) (1 + 1/cosA)(1 + 1/cosB)) over 20 000 random triangles,
// parallelograms and twisted quads (PairRule.DISABLED_FitBoundConstants): at ρ in
// [0.02, 0.6] for n = 1..4 (fitted 0.1355, 0.0337, 0.00802, 0.000770), at ρ in [0.02, 0.85]
// for n = 5..8 (fitted 1.96e-4, 2.41e-5, 3.76e-6, 7.27e-7; the same run gives n = 1..4
// within 4 %). PairRule.BoundHoldsOnRandomPairs checks the bound on other pairs.

// The product rule's weights (normalised to sum 1): 16 corner pairs and 8 axis pairs.
constexpr double kProductCornerWeight = 1.0 / 36, kProductAxisWeight = 5.0 / 72;

const GaussLegendreRule& rule(int n) {
  static const std::array<GaussLegendreRule, kMaxPairLevel + 2> rules = [] {
    std::array<GaussLegendreRule, kMaxPairLevel + 2> r;
    for (int k = 1; k <= kMaxPairLevel + 1; ++k) r[k] = gaussLegendre(k);
    return r;
  }();
  return rules[n];
}

RADKIT_TARGET_CLONES
double kernelSum(const PointSet& a, const PointSet& b, const double* u, const double* v) {
  // Σ_p u_p Σ_q v_q / |y_q − x_p|⁴, one accumulator per point of b: the loop over b carries
  // no reduction, so it vectorises without reassociating the sum (same result on every clone).
  alignas(32) double acc[PatchPoints::kCapacity];
  const int m = b.padded;
  for (int q = 0; q < m; ++q) acc[q] = 0;  // only what is used: level 8 holds 84
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

double pairRuleBound(int n, const PairSeparation& s) {
  if (n < 1 || n > kMaxPairLevel) throw std::invalid_argument("pair rule level out of range");
  if (!(s.rho < 1) || !(s.cosA > 0) || !(s.cosB > 0)) return INFINITY;
  double rho2 = s.rho * s.rho, power = 1;
  for (int k = 0; k < n; ++k) power *= rho2;
  return kPairBoundConstant[n] * power * (1 + 1 / s.cosA) * (1 + 1 / s.cosB);
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
    if (!parallelogram) {
      PatchChart chart(p.v, p.count);
      for (int a = 0; a < m; ++a)
        for (int b = 0; b < m; ++b, ++k) {
          double s = r.nodes[a], t = r.nodes[b];
          Vec3 x = chart.point(s, t);
          out.x[k] = x.x, out.y[k] = x.y, out.z[k] = x.z;
          out.w[k] = r.weights[a] * r.weights[b] * chart.jacobian(s, t);
        }
    }
  }
  out.count = k;
  out.padded = (k + 3) / 4 * 4;
  for (; k < out.padded; ++k)
    out.x[k] = out.x[0], out.y[k] = out.y[0], out.z[k] = out.z[0], out.w[k] = 0;
}

void productPoints(const PatchInfo& p, PatchPoints& out) {
  if (!p.parallelogram) throw std::invalid_argument("product rule points need a parallelogram");
  const double t = std::sqrt(0.5), r = std::sqrt(0.8);
  const double xi[8] = {t, t, -t, -t, r, -r, 0, 0}, eta[8] = {t, -t, t, -t, 0, 0, r, -r};
  const Vec3 h1 = (p.v[1] - p.v[0]) * 0.5, h2 = (p.v[3] - p.v[0]) * 0.5;
  for (int k = 0; k < 8; ++k) {
    Vec3 x = p.centroid + h1 * xi[k] + h2 * eta[k];
    out.x[k] = x.x, out.y[k] = x.y, out.z[k] = x.z, out.w[k] = 0;
  }
  out.count = out.padded = 8;
}

int productRulePairs(const PatchInfo& a, const PatchInfo& b, Vec3* x, Vec3* y, double* w) {
  PatchPoints pa, pb;
  productPoints(a, pa), productPoints(b, pb);
  auto at = [](const PatchPoints& p, int k) { return Vec3{p.x[k], p.y[k], p.z[k]}; };
  const double areas = a.area * b.area;
  int m = 0;
  for (int p = 0; p < 4; ++p)
    for (int q = 0; q < 4; ++q, ++m)
      x[m] = at(pa, p), y[m] = at(pb, q), w[m] = areas * kProductCornerWeight;
  for (int k = 4; k < 8; ++k, ++m)
    x[m] = at(pa, k), y[m] = b.centroid, w[m] = areas * kProductAxisWeight;
  for (int k = 4; k < 8; ++k, ++m)
    x[m] = a.centroid, y[m] = at(pb, k), w[m] = areas * kProductAxisWeight;
  return m;
}

PatchPointCache::PatchPointCache(const PatchTable& table, int maxLevel)
    : m_levels(std::max(0, std::min(maxLevel, kCachedPairLevels))) {
  const std::size_t slots = std::size_t(table.size()) * (m_levels + 1);
  m_offset.resize(slots), m_count.resize(slots), m_padded.resize(slots);
  PatchPoints points;
  for (int i = 0; i < table.size(); ++i)
    for (int n = 1; n <= m_levels + 1; ++n) {
      const std::size_t slot = std::size_t(i) * (m_levels + 1) + (n - 1);
      if (n <= m_levels)
        patchPoints(table[i], n, points);
      else if (m_levels >= 3 && table[i].parallelogram)
        radkit::productPoints(table[i], points);
      else
        points.count = points.padded = 0;
      m_offset[slot] = m_pool.size();
      m_count[slot] = points.count, m_padded[slot] = points.padded;
      for (const double* array : {points.x, points.y, points.z, points.w})
        m_pool.insert(m_pool.end(), array, array + points.padded);
    }
}

double pairRuleFormFactor(const PatchInfo& a, const PointSet& pa, const PatchInfo& b,
                          const PointSet& pb) {
  // Every point of a lies in a's plane and every point of b in b's, so the cosine factors
  // separate: n_a·(y − x) = n_a·y − offset_a depends on y alone, −n_b·(y − x) on x alone.
  alignas(32) double u[PatchPoints::kCapacity], v[PatchPoints::kCapacity];
  for (int p = 0; p < pa.count; ++p)
    u[p] = pa.w[p] *
           (b.normal.x * pa.x[p] + b.normal.y * pa.y[p] + b.normal.z * pa.z[p] - b.planeOffset);
  for (int q = 0; q < pb.padded; ++q)
    v[q] = pb.w[q] *
           (a.normal.x * pb.x[q] + a.normal.y * pb.y[q] + a.normal.z * pb.z[q] - a.planeOffset);
  return kernelSum(pa, pb, u, v) / (M_PI * a.area);
}

namespace {
RADKIT_TARGET_CLONES
double productKernel(const PatchInfo& pa, const PointSet& a, const PatchInfo& pb,
                     const PointSet& b) {
  // The cosines separate as in pairRuleFormFactor: u on a's points, v on b's. Loops of 4
  // lanes with no reduction inside, as in kernelSum.
  alignas(32) double u[8], v[8], acc[4] = {}, axis[4];
  for (int k = 0; k < 8; ++k) {
    u[k] = pb.normal.x * a.x[k] + pb.normal.y * a.y[k] + pb.normal.z * a.z[k] - pb.planeOffset;
    v[k] = pa.normal.x * b.x[k] + pa.normal.y * b.y[k] + pa.normal.z * b.z[k] - pa.planeOffset;
  }
  const Vec3 &ca = pa.centroid, &cb = pb.centroid;
  const double uc = pb.height(ca), vc = pa.height(cb);
  // Divisions bound this loop, so terms go in twos over one divisor: u/r⁴ + u'/r'⁴ =
  // (u r'⁴ + u' r⁴)/(r⁴ r'⁴). r⁸ stays a normal double for 1e-38 < r < 1e38 (scene units).
  for (int p = 0; p < 4; p += 2) {  // the 16 corner pairs
    const double ax = a.x[p], ay = a.y[p], az = a.z[p], up = u[p];
    const double bx = a.x[p + 1], by = a.y[p + 1], bz = a.z[p + 1], uq = u[p + 1];
    for (int q = 0; q < 4; ++q) {
      const double dx = b.x[q] - ax, dy = b.y[q] - ay, dz = b.z[q] - az;
      const double ex = b.x[q] - bx, ey = b.y[q] - by, ez = b.z[q] - bz;
      const double r2 = dx * dx + dy * dy + dz * dz, s2 = ex * ex + ey * ey + ez * ez;
      const double r4 = r2 * r2, s4 = s2 * s2;
      acc[q] += (up * s4 + uq * r4) / (r4 * s4);
    }
  }
  for (int k = 0; k < 4; ++k) {  // a's axis points with b's centroid, a's centroid with b's
    const double dx = cb.x - a.x[4 + k], dy = cb.y - a.y[4 + k], dz = cb.z - a.z[4 + k];
    const double ex = b.x[4 + k] - ca.x, ey = b.y[4 + k] - ca.y, ez = b.z[4 + k] - ca.z;
    const double r2 = dx * dx + dy * dy + dz * dz, s2 = ex * ex + ey * ey + ez * ez;
    const double r4 = r2 * r2, s4 = s2 * s2;
    axis[k] = (vc * u[4 + k] * s4 + uc * v[4 + k] * r4) / (r4 * s4);
  }
  double corner = 0, axes = 0;
  for (int k = 0; k < 4; ++k) corner += v[k] * acc[k], axes += axis[k];
  return corner * kProductCornerWeight + axes * kProductAxisWeight;
}
}  // namespace

double productRuleFormFactor(const PatchInfo& a, const PointSet& pa, const PatchInfo& b,
                             const PointSet& pb) {
  return b.area * productKernel(a, pa, b, pb) / M_PI;
}

bool inFrontOfEachOther(const PatchInfo& a, const PatchInfo& b, double tolerance) {
  for (int k = 0; k < b.count; ++k)
    if (a.height(b.v[k]) < -tolerance) return false;
  for (int k = 0; k < a.count; ++k)
    if (b.height(a.v[k]) < -tolerance) return false;
  return true;
}

}  // namespace radkit
