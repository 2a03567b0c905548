// point-polygon: F_ij = (1/A_i) ∫_Ai F_dAi→Aj dA_i · V_ij. Pairs apart from each other take a
// tensor Gauss–Legendre rule with the point-to-point kernel, its level chosen per pair from an
// error bound (pair_rule.h); the rest the exact contour integrand (contour.h) under adaptive
// cubature (quadrature.h). V_ij the visible fraction of the kernel estimated from K segments
// stratified over both patches: V̂ = Σ w_k v_k / Σ w_k with w_k = cosθ_i cosθ_j / r² of
// segment k and v_k its visibility (a ratio estimator: F_ij V̂ → F_ij exactly as K grows,
// and V̂ = 1 or 0 exactly when nothing or everything is blocked).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "radiosity/contour.h"
#include "radiosity/form_factor_method.h"
#include "radiosity/occluder_culling.h"
#include "radiosity/pair_rule.h"
#include "radiosity/patch_pairs.h"
#include "util/format.h"
#include "util/params.h"
#include "util/sampling.h"

namespace radkit {

static_assert(kMaxPairLevel + 1 == kPairRuleCount, "one count per rule");

namespace {

class PointPolygon final : public FormFactorMethod {
 public:
  PointPolygon(const PatchMesh& mesh, const Visibility& visibility, const FormFactorSettings& s)
      : m_table(mesh),
        m_points(m_table, s.quadrature.pairLevels),
        m_culling(mesh, m_table),
        m_visibility(visibility),
        m_settings(s),
        m_cubature(s.quadrature) {}

  std::string name() const override { return "point-polygon"; }
  std::string describe() const override {
    std::ostringstream d;
    d << "point-polygon: contour formula integrated over the smaller patch of each pair by "
      << "adaptive " << m_settings.quadrature.order << "x" << m_settings.quadrature.order
      << " Gauss-Legendre cubature (tolerance " << m_settings.quadrature.tolerance
      << ", depth <= " << m_settings.quadrature.maxDepth << ", far ratio "
      << m_settings.quadrature.farRatio << ")";
    if (m_settings.quadrature.pairLevels > 0)
      d << ", or for pairs in front of each other the cheapest tensor Gauss-Legendre rule of "
        << "level <= " << m_settings.quadrature.pairLevels
        << " whose error bound is <= " << m_settings.quadrature.tolerance << " relative";
    d << ", visibility from K=" << m_settings.samples << " stratified rays per pair"
      << (m_settings.cullUnblockable ? " (none for unblockable pairs)" : "")
      << ", F_ji by reciprocity, seed " << m_settings.seed;
    return d.str();
  }
  RowCoverage coverage() const override { return RowCoverage::UpperTriangle; }
  void computeRow(int i, RowResult& out) const override;

  /// Unoccluded F_ij: the selected tensor rule when the patches are in front of each other,
  /// else cubature over the smaller patch; F_ji follows by reciprocity. Counts the rule used
  /// in `out`.
  double unoccluded(int i, int j, bool inFront, QuadratureStats& stats, RowResult& out) const;
  /// Unoccluded F_ij by adaptive cubature of the contour integrand.
  double adaptiveContour(int i, int j, QuadratureStats& stats) const;
  /// Buffers reused across the pairs of a row.
  struct Scratch {
    std::vector<double> u, weight;
    std::vector<int> permutation;
    std::vector<char> visible;
  };
  /// Kernel-weighted visible fraction from K stratified segments, and its standard error.
  std::pair<double, double> visibleFraction(int i, int j, Scratch& scratch) const;

 private:
  PatchTable m_table;
  PatchPointCache m_points;  ///< every patch's tensor-rule points, shared by the rows
  OccluderCulling m_culling;
  const Visibility& m_visibility;
  FormFactorSettings m_settings;
  AdaptiveCubature m_cubature;
};

double PointPolygon::unoccluded(int i, int j, bool inFront, QuadratureStats& stats,
                                RowResult& out) const {
  const QuadratureSettings& q = m_settings.quadrature;
  const PatchInfo& a = m_table[i];
  const PatchInfo& b = m_table[j];
  if (q.pairLevels > 0 && inFront) {
    int n = selectPairLevel(pairSeparation(a, b), q.tolerance, q.pairLevels);
    if (n > 0) {
      ++out.pairsByRule[n];
      if (n == 3 && a.parallelogram && b.parallelogram) {
        out.kernelPoints += 24;
        return productRuleFormFactor(a, m_points.productPoints(i), b, m_points.productPoints(j));
      }
      if (n > kCachedPairLevels) {  // rare and dear: the points cost little next to n⁴ kernels
        PatchPoints ownA, ownB;
        patchPoints(a, n, ownA), patchPoints(b, n, ownB);
        out.kernelPoints += (long long)ownA.count * ownB.count;
        return pairRuleFormFactor(a, ownA, b, ownB);
      }
      PointSet pa = m_points.points(i, n), pb = m_points.points(j, n);
      out.kernelPoints += (long long)pa.count * pb.count;
      return pairRuleFormFactor(a, pa, b, pb);
    }
  }
  ++out.pairsByRule[0];
  return adaptiveContour(i, j, stats);
}

double PointPolygon::adaptiveContour(int i, int j, QuadratureStats& stats) const {
  // Integrate over the smaller patch a: for a given number of points the integrand varies
  // least over the patch that is small compared with its distance to the other.
  bool swap = m_table[j].area < m_table[i].area;
  const PatchInfo& a = m_table[swap ? j : i];
  const PatchInfo& b = m_table[swap ? i : j];
  // Only the part of a in front of b's plane sees b's front: clip it, so the integrand has
  // no kink inside the domain.
  Vec3 domain[kMaxPolygonVertices];
  int count = clipToHalfSpace(a.v, a.count, b.centroid, b.normal, domain);
  if (count < 3) return 0.0;
  PlaneToPolygon integrand(a.centroid, a.normal, b.v, b.count);  // b clipped to a's front once
  double tolerance = m_settings.quadrature.tolerance * a.area;
  TargetSphere target{b.sphereCentre, b.sphereRadius};
  double fab = m_cubature.integrate(domain, count, tolerance, integrand, stats, target) / a.area;
  return swap ? fab * a.area / b.area : fab;  // reciprocity: A_j F_ji = A_i F_ij
}

std::pair<double, double> PointPolygon::visibleFraction(int i, int j, Scratch& sc) const {
  const PatchInfo& pi = m_table[i];
  const PatchInfo& pj = m_table[j];
  const int K = m_settings.samples;
  Rng rng(m_settings.seed, std::uint64_t(i), std::uint64_t(j));
  latinHypercube(K, 4, rng, sc.u, sc.permutation);
  sc.weight.resize(K);
  sc.visible.resize(K);
  double sumW = 0, sumWV = 0;
  for (int k = 0; k < K; ++k) {
    const double* s = &sc.u[std::size_t(k) * 4];
    Vec3 x = samplePatchUniform(pi.v, pi.count, pi.split, s[0], s[1]);
    Vec3 y = samplePatchUniform(pj.v, pj.count, pj.split, s[2], s[3]);
    Vec3 d = y - x;
    double r2 = dot(d, d);
    // w_k: the kernel cosθ_i cosθ_j/r² (its 1/π cancels in the ratio).
    double w = std::max(0.0, dot(pi.normal, d)) * std::max(0.0, -dot(pj.normal, d)) / (r2 * r2);
    sc.visible[k] = !m_visibility.occluded(x, pi.normal, y, pj.normal);
    sc.weight[k] = w;
    sumW += w;
    sumWV += w * sc.visible[k];
  }
  if (!(sumW > 0)) return {0.5, 0.5};  // every segment grazing: no information
  double V = sumWV / sumW, var = 0;
  for (int k = 0; k < K; ++k) {
    double e = sc.weight[k] * (sc.visible[k] - V);
    var += e * e;
  }
  return {V, std::sqrt(var) / sumW};  // delta-method standard error of the ratio
}

void PointPolygon::computeRow(int i, RowResult& out) const {
  out.clear();
  Clock::time_point start = Clock::now();
  QuadratureStats stats;
  std::vector<RowEntry> needRays;
  const int n = m_table.size();
  const long long K = m_settings.samples;
  const double tolerance = m_table.planeTolerance();
  out.entries.reserve(std::size_t(n - i));
  // Whether anything can block the pairs of (i, surface): -1 not asked yet, 0 no, 1 maybe.
  std::vector<signed char> surfaceMayBlock(m_culling.surfaceCount(), -1);
  auto mayBeBlocked = [&](int j) {
    int s = m_table[j].surface;
    if (s < 0 || s >= int(surfaceMayBlock.size())) return m_culling.mayBeBlocked(i, j);
    if (surfaceMayBlock[s] < 0) surfaceMayBlock[s] = m_culling.mayBeBlockedFromSurface(i, s);
    return surfaceMayBlock[s] != 0 && m_culling.mayBeBlocked(i, j);
  };
  for (int j = i + 1; j < n; ++j) {
    const PairSides sides = pairSides(m_table[i], m_table[j], tolerance);
    if (!sides.facing) {
      // Coincident or overlapping coplanar patches: F = 0 (no front sees the other), reported.
      if (m_table[i].bounds.overlaps(m_table[j].bounds) && m_table.coplanar(i, j) &&
          m_table.overlapArea(i, j) > 0) {
        if (out.overlappingPairs++ == 0) out.firstOverlap[0] = i, out.firstOverlap[1] = j;
      }
      continue;
    }
    ++out.pairsFacing;
    double f = unoccluded(i, j, sides.inFront, stats, out);
    if (!(f > 0)) continue;
    if (m_settings.cullUnblockable && !mayBeBlocked(j)) {
      ++out.pairsCulled;
      out.raysSaved += K;
      out.entries.push_back({j, f, 0.0});
    } else {
      needRays.push_back({j, f, 0.0});
    }
  }
  out.quadraturePoints = stats.evaluations;
  out.geometrySeconds = secondsSince(start);

  start = Clock::now();
  Scratch scratch;
  std::size_t nVisible = 0;
  for (const RowEntry& e : needRays) {
    auto [v, se] = visibleFraction(i, e.column, scratch);
    out.raysCast += K;
    if (v > 0) out.entries.push_back({e.column, e.value * v, e.value * se}), ++nVisible;
  }
  out.raySeconds = secondsSince(start);
  // Culled entries and ray-traced ones each came in column order: merge the two runs.
  std::inplace_merge(out.entries.begin(), out.entries.end() - std::ptrdiff_t(nVisible),
                     out.entries.end(),
                     [](const RowEntry& a, const RowEntry& b) { return a.column < b.column; });
}
}  // namespace

std::unique_ptr<FormFactorMethod> createPointPolygon(Params& params, const PatchMesh& mesh,
                                                     const Visibility& visibility,
                                                     const FormFactorSettings& settings) {
  FormFactorSettings s = settings;
  // The highest tensor rule a pair may take; --ff-pair-levels sets the default.
  s.quadrature.pairLevels =
      int(params.integer("pair_levels", settings.quadrature.pairLevels, 0, kMaxPairLevel));
  return std::make_unique<PointPolygon>(mesh, visibility, s);
}

}  // namespace radkit
