#include "hierarchy/refine.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <tbb/parallel_for.h>

#include "radiosity/contour.h"
#include "util/sampling.h"
#include "util/setting_names.h"

namespace radkit {

namespace {

/// Relative accuracy of an element-to-element form factor's cubature.
constexpr double kFormFactorTolerance = 1e-3;
/// Nodes of the 2-point Gauss-Legendre rule on [0, 1]: where F is sampled over a receiver.
const double kGauss2[2] = {0.5 - 0.5 / std::sqrt(3.0), 0.5 + 0.5 / std::sqrt(3.0)};
/// Fresh rays for a partly blocked link's kept value, as a multiple of K: these links carry the
/// shadows (16 instead of 4 changed no Cornell surface by more than 0.05 % for a third more time).
constexpr int kPartialRays = 4;
/// Most rays a unanimous link may be given, as a multiple of K, before it is split instead.
constexpr int kConfirmRays = 16;
/// Weight of the source's radiosity range in a link's error. The range bounds the error of
/// using the source's mean (quarter shares correct it one level down only); on the Cornell box
/// at ε = 1e-4, weight 16 instead of 4 took the ceiling from −0.43 % to −0.29 % of the photon
/// reference and the short block from −0.87 % to −0.82 %, for a quarter more CPU time.
constexpr double kSourceSpreadWeight = 16.0;
/// Least reflectance the oracle weighs a receiver's error with. Its error bound is in reflected
/// watts, so a black receiver (ρ = 0) would never be refined and its irradiance, which
/// surfaces.csv reports (lux on a photometer plane), would be the coarsest link's.
constexpr double kIrradianceWeight = 0.5;

/// The point of polygon p nearest to x (its plane's foot point when that lies inside).
Vec3 nearestPoint(const HPolygon& p, const Vec3& x) {
  Vec3 foot = x - p.normal * dot(x - p.v[0], p.normal);
  bool inside = true;
  for (int k = 0; k < p.count; ++k)
    inside &= dot(cross(p.v[(k + 1) % p.count] - p.v[k], foot - p.v[k]), p.normal) >= 0;
  if (inside) return foot;
  Vec3 best = p.v[0];
  double bestD2 = INFINITY;
  for (int k = 0; k < p.count; ++k) {
    const Vec3 a = p.v[k], e = p.v[(k + 1) % p.count] - a;
    const double t = std::clamp(dot(foot - a, e) / std::max(dot(e, e), 1e-300), 0.0, 1.0);
    const Vec3 q = a + e * t;
    const double d2 = dot(q - foot, q - foot);
    if (d2 < bestD2) bestD2 = d2, best = q;
  }
  return best;
}

/// Largest and smallest max(0, n·w) over normals within `cone` of `axis` and directions within
/// `spread` of w: the cosine bounds of a node seen along directions near w.
std::pair<double, double> cosineBounds(const Vec3& axis, double cone, const Vec3& w,
                                       double spread) {
  double phi = angleBetween(axis, w);
  double hi = std::max(0.0, std::cos(std::max(0.0, phi - cone - spread)));
  double lo = std::max(0.0, std::cos(std::min(kPi, phi + cone + spread)));
  return {lo, hi};
}

/// Uniform points on a node; on an element, quarter by quarter (the quarter picked by area
/// with u0, which is then rescaled and reused: still uniform), reporting the quarter.
struct QuarterSampler {
  const Hierarchy& h;
  int node;
  bool element;
  HPolygon kids[4];
  double cumulative[4] = {0, 0, 0, 1};
  QuarterSampler(const Hierarchy& hierarchy, int n)
      : h(hierarchy), node(n), element(hierarchy[n].element) {
    if (!element) return;
    double areas[4];
    quarterPolygons(h.polygon(n), kids, areas);
    const double total = areas[0] + areas[1] + areas[2] + areas[3];
    for (int k = 0; k < 3; ++k)
      cumulative[k] = (k > 0 ? cumulative[k - 1] : 0.0) + areas[k] / total;
  }
  Vec3 sample(double u0, double u1, double u2, Vec3& normal, int& quarter) const {
    quarter = 0;
    if (!element) return h.samplePoint(node, u0, u1, u2, normal);
    while (quarter < 3 && u0 >= cumulative[quarter]) ++quarter;
    const double lo = quarter > 0 ? cumulative[quarter - 1] : 0.0, width = cumulative[quarter] - lo;
    u0 = width > 0 ? std::min((u0 - lo) / width, 0x1.fffffffffffffp-1) : 0.0;
    normal = kids[quarter].normal;
    return samplePatchUniform(kids[quarter].v, kids[quarter].count, u0, u1);
  }
};

std::string gib(std::size_t bytes) {
  std::ostringstream s;
  s.precision(3);
  s << double(bytes) / double(1ull << 30) << " GiB";
  return s.str();
}

}  // namespace

void growState(const Hierarchy& h, SourceState& state) {
  std::size_t old = state.radiosity.size();
  growVector(state.radiosity, h.size());
  growVector(state.radiosityMin, h.size());
  growVector(state.radiosityMax, h.size());
  if (!state.visibleArea.empty()) growVector(state.visibleArea, h.size());
  for (std::size_t n = old; n < state.radiosity.size(); ++n) {
    int parent = h[int(n)].parent;
    state.radiosity[n] = parent >= 0 ? state.radiosity[parent] : Vec3{};
    state.radiosityMin[n] = state.radiosityMax[n] = maxComponent(state.radiosity[n]);
    // A quarter of a leaf that saw nothing is taken to see nothing until the next solve says.
    if (!state.visibleArea.empty())
      state.visibleArea[n] = parent >= 0 && state.visibleArea[parent] > 0 ? h[int(n)].area : 0.0;
  }
}

Refiner::Refiner(Hierarchy& h, const Visibility& visibility, const RefineSettings& settings)
    : m_h(h), m_visibility(visibility), m_settings(settings), m_cubature(QuadratureSettings{}) {}

std::vector<HLink> Refiner::rootLinks() const {
  HLink self;
  self.receiver = self.source = m_h.root();
  return {self};
}

bool Refiner::splittable(int node) const {
  return !m_h[node].element || m_h.canSplit(node, m_settings.minArea);
}

Refiner::Decision Refiner::splitLarger(int r, int s) const {
  bool canR = splittable(r), canS = splittable(s);
  if (canR && (!canS || m_h[r].radius >= m_h[s].radius)) return Decision::SplitReceiver;
  return canS ? Decision::SplitSource : Decision::Keep;
}

double Refiner::elementFormFactor(int r, int s, double estimate) const {
  const HPolygon pr = m_h.polygon(r);
  const HPolygon ps = m_h.polygon(s);
  // Only the part of r in front of s sees s's front: integrate over that part, so the
  // integrand has no kink inside the domain.
  Vec3 domain[kMaxPolygonVertices];
  int count = clipToHalfSpace(pr.v, pr.count, m_h[s].centre, ps.normal, domain);
  if (count < 3) return 0.0;
  PlaneToPolygon integrand(pr.v[0], pr.normal, ps.v, ps.count);  // s clipped once
  QuadratureStats stats;
  const double area = m_h[r].area;
  TargetSphere target{m_h[s].centre, m_h[s].radius};
  // Relative accuracy: a link's F need not be known better than the error its oracle allows,
  // and the four-point estimate already has it to (size/distance)⁴ for distant pairs.
  const double tolerance =
      std::max(kFormFactorTolerance * estimate, QuadratureSettings{}.tolerance) * area;
  return m_cubature.integrate(domain, count, tolerance, integrand, stats, target) / area;
}

void Refiner::quarterShares(int r, int s, HLink& link) const {
  link.quarterShare[0] = -1;
  const HNode& S = m_h[s];
  if (S.childCount != 4) return;
  const HPolygon pr = m_h.polygon(r);
  PatchChart chart(pr.v, pr.count);
  double f[4] = {0, 0, 0, 0}, total = 0;
  for (int k = 0; k < 4; ++k) {
    const HPolygon q = m_h.polygon(S.firstChild + k);
    const PlaneToPolygon toQ(pr.v[0], pr.normal, q.v, q.count);  // q clipped to r's front once
    for (double a : kGauss2)
      for (double b : kGauss2) {
        Vec3 x = chart.point(a, b);
        if (dot(x - m_h[S.firstChild + k].centre, q.normal) > 0)
          f[k] += chart.jacobian(a, b) * toQ(x);
      }
    if (link.quarterVisible[k] >= 0)
      f[k] *= link.quarterVisible[k];
    else if (link.visibility < 1)
      f[k] *= link.visibility;  // no ray ended there: the link's mean
    total += f[k];
  }
  if (!(total > 0)) return;
  for (int k = 0; k < 4; ++k) link.quarterShare[k] = float(f[k] / total);
}

void Refiner::receiverShares(int r, int s, const VisibilityEstimate& v, HLink& link) const {
  link.receiverShare[0] = -1;
  const HPolygon ps = m_h.polygon(s);
  HPolygon kids[4];
  double areas[4], f[4], mean = 0, total = 0;
  quarterPolygons(m_h.polygon(r), kids, areas);
  for (int k = 0; k < 4; ++k) {
    Vec3 c;
    for (int t = 0; t < kids[k].count; ++t) c += kids[k].v[t];
    c = c / double(kids[k].count);
    f[k] = dot(c - m_h[s].centre, ps.normal) > 0
               ? pointToPolygonFormFactor(c, kids[k].normal, ps.v, ps.count)
               : 0.0;
    if (v.receiverQuarter[k] >= 0)
      f[k] *= v.receiverQuarter[k];
    else if (v.visible < 1)
      f[k] *= v.visible;  // no ray started there: the link's mean
    mean += areas[k] * f[k], total += areas[k];
  }
  mean /= total;
  if (!(mean > 0)) return;
  for (int k = 0; k < 4; ++k) link.receiverShare[k] = float(f[k] / mean);
}

Refiner::VisibilityEstimate Refiner::visibleFraction(int r, int s, int K, int stream) const {
  Rng rng(m_settings.seed + 0x9E3779B97F4A7C15ull * std::uint64_t(stream), m_h.key(r), m_h.key(s));
  std::vector<double> u;
  std::vector<int> scratch;
  latinHypercube(K, 6, rng, u, scratch);
  // An element end is sampled quarter by quarter (a quarter picked by area, then a uniform
  // point in it: uniform over the element), so each ray also tells which quarters it joined.
  QuarterSampler sq(m_h, s), rq(m_h, r);
  double sumW = 0, sumWV = 0, sumW2V = 0, sumW2 = 0, sumBlocked = 0, sumBlocked2 = 0;
  double quarterW[4] = {0, 0, 0, 0}, quarterWV[4] = {0, 0, 0, 0};
  double receiverW[4] = {0, 0, 0, 0}, receiverWV[4] = {0, 0, 0, 0};
  for (int k = 0; k < K; ++k) {
    const double* q = &u[std::size_t(k) * 6];
    Vec3 nx, ny;
    int quarter = 0, receiverQuarter = 0;
    Vec3 x = rq.sample(q[0], q[1], q[2], nx, receiverQuarter);
    Vec3 y = sq.sample(q[3], q[4], q[5], ny, quarter);
    Vec3 d = y - x;
    double r2 = dot(d, d);
    if (!(r2 > 0)) continue;
    // The kernel cosθ_x cosθ_y / r² (per unit r² again for the unnormalised d).
    double w = std::max(0.0, dot(nx, d)) * std::max(0.0, -dot(ny, d)) / (r2 * r2);
    if (!(w > 0)) continue;
    bool visible = !m_visibility.occluded(x, nx, y, ny);
    sumW += w;
    sumW2 += w * w;
    quarterW[quarter] += w;
    receiverW[receiverQuarter] += w;
    if (visible)
      sumWV += w, sumW2V += w * w, quarterWV[quarter] += w, receiverWV[receiverQuarter] += w;
    else
      sumBlocked += w, sumBlocked2 += w * w;
  }
  VisibilityEstimate out;
  out.blockedKernel = sumBlocked / K;
  if (K > 1)
    out.blockedKernelError =
        std::sqrt(std::max(0.0, sumBlocked2 / K - out.blockedKernel * out.blockedKernel) / (K - 1));
  if (!(sumW > 0)) return out;  // no sample pair faces both ways: nothing known
  out.visible = sumWV / sumW;
  // Σ w_k²(v_k − V)² with v_k ∈ {0, 1}, expanded.
  double var = sumW2V * (1 - 2 * out.visible) + out.visible * out.visible * sumW2;
  out.standardError = std::sqrt(std::max(0.0, var)) / sumW;
  for (int k = 0; k < 4; ++k) {
    if (sq.element) out.quarter[k] = quarterW[k] > 0 ? float(quarterWV[k] / quarterW[k]) : -1.0f;
    if (rq.element)
      out.receiverQuarter[k] = receiverW[k] > 0 ? float(receiverWV[k] / receiverW[k]) : -1.0f;
  }
  return out;
}

Refiner::Outcome Refiner::evaluate(const HLink& c, bool knownVisibility,
                                   const SourceState& state) const {
  Outcome out;
  out.link = c;
  const int r = c.receiver, s = c.source;
  const HNode& R = m_h[r];
  const HNode& S = m_h[s];
  if (r == s) {
    out.decision = R.element ? Decision::Drop : Decision::SplitBoth;  // a plane never sees itself
    return out;
  }
  const double rho = std::max(R.reflectanceMax, kIrradianceWeight);
  const double tau = m_settings.threshold;
  const double sourceRadiosity = maxComponent(state.radiosity[s]);
  double transfer = 0, errorGeometry = 0;  // W, with full visibility
  double fMean = 0;
  const Vec3 toSource = S.centre - R.centre;
  const double dist = length(toSource);
  const bool overlapping = !(dist > R.radius + S.radius);

  if (R.element && S.element) {
    const HPolygon pr = m_h.polygon(r);
    const HPolygon ps = m_h.polygon(s);
    const double tol = 1e-3 * m_visibility.epsilon();
    bool sInFront = false, rInFront = false;
    for (int k = 0; k < ps.count; ++k) sInFront |= dot(ps.v[k] - R.centre, pr.normal) > tol;
    for (int k = 0; k < pr.count; ++k) rInFront |= dot(pr.v[k] - S.centre, ps.normal) > tol;
    if (!sInFront || !rInFront) return out;  // Drop
    // Point values over r: the mean of the 2×2 Gauss points estimates F_rs; the spread of
    // those and of points near each corner and at the centre says how much F varies over r
    // (symmetric points alone miss it: directly opposite squares give four equal values).
    // Points behind s's plane see nothing of its front.
    const PlaneToPolygon toS(pr.v[0], pr.normal, ps.v, ps.count);  // s clipped to r's front once
    auto pointValue = [&](const Vec3& x) {
      return dot(x - S.centre, ps.normal) > 0 ? toS(x) : 0.0;
    };
    PatchChart chart(pr.v, pr.count);
    double fMin = INFINITY, fMax = 0, sum = 0, weight = 0;
    for (double a : kGauss2)
      for (double b : kGauss2) {
        double f = pointValue(chart.point(a, b));
        double j = chart.jacobian(a, b);
        fMin = std::min(fMin, f), fMax = std::max(fMax, f);
        sum += j * f, weight += j;
      }
    for (int k = 0; k <= pr.count + 1; ++k) {
      // Corners pulled a hundredth toward the centroid: a corner on s's edge is singular. The
      // last point is r's nearest to s: on a face far larger than s (a long floor under a
      // lamp) the peak of F lies there, between the other points.
      Vec3 x = k < pr.count ? pr.v[k] * 0.99 + R.centre * 0.01 : R.centre;
      if (k > pr.count) {
        // Pulled toward the centroid by a hundredth of s's size at most: a hundredth of a
        // 1 000 km floor would move it kilometres away from the lamp above it.
        const Vec3 q = nearestPoint(pr, S.centre), in = R.centre - q;
        const double len = length(in);
        x = len > 0 ? q + in * (std::min(0.01 * len, 0.01 * S.radius) / len) : q;
      }
      double f = pointValue(x);
      fMin = std::min(fMin, f), fMax = std::max(fMax, f);
    }
    double f = weight > 0 ? sum / weight : 0.0;
    fMean = f;
    transfer = R.area * f * sourceRadiosity;
    // Neighbours (bounding spheres overlap): sample points cannot bound the variation near a
    // shared edge (F grows without bound toward it), so the largest value seen plus the mean
    // count as error until the pair is small.
    errorGeometry = rho * R.area * sourceRadiosity * (overlapping ? fMax + f : fMax - fMin);
    if (!(fMax > 0) && !overlapping) return out;  // Drop: r sees nothing of s's front
  } else {
    const double power = sourceRadiosity * S.area;  // W leaving s (per unit of the largest channel)
    if (overlapping) {
      // No bound on the geometry: all the power s sends out could arrive.
      transfer = power;
      errorGeometry = rho * power;
    } else {
      const Vec3 w = toSource / dist;
      const double spread = std::asin(std::min(1.0, (R.radius + S.radius) / dist));
      auto [rLo, rHi] = cosineBounds(R.coneAxis, R.element ? 0.0 : R.coneAngle, w, spread);
      auto [sLo, sHi] = cosineBounds(S.coneAxis, S.element ? 0.0 : S.coneAngle, -w, spread);
      if (!(rHi > 0) || !(sHi > 0)) return out;  // Drop: they face away from each other
      const double near = dist - R.radius - S.radius, far = dist + R.radius + S.radius;
      double tMax = power / kPi * sHi * R.area * rHi / (near * near);
      double tMin = power / kPi * sLo * R.area * rLo / (far * far);
      Vec3 intensity = intensityToward(m_h, state, s, -w);
      transfer = std::clamp(maxComponent(intensity) * projectedArea(m_h, r, w) /
                                clusterTransfer(m_h, r, s).denominator,
                            tMin, tMax);
      errorGeometry = rho * 0.5 * (tMax - tMin);
    }
  }

  // The source's own variation: the receiver may see only its brighter or darker part.
  if (sourceRadiosity > 0)
    errorGeometry += kSourceSpreadWeight * rho * transfer *
                     (state.radiosityMax[s] - state.radiosityMin[s]) / sourceRadiosity;
  if (errorGeometry > tau) {
    out.decision = splitLarger(r, s);
    if (out.decision != Decision::Keep) return out;
  }
  double V = c.visibility, se = c.visibilityError;
  VisibilityEstimate decided, fresh;  // the rays behind the decision, and behind the kept value
  const int K = m_settings.raysPerLink;
  int cast = K;  // rays behind the decision
  auto unanimous = [](const VisibilityEstimate& v) {
    return (v.visible <= 0 || v.visible >= 1) && v.standardError < 0.5;
  };
  if (!knownVisibility) {
    VisibilityEstimate& v = decided;
    v = visibleFraction(r, s, K, 2 * m_settings.round);
    out.rays = K;
    // Rays that all agree leave a share of about 1/(K + 1) unseen: links that carry more than
    // τ·(K + 1) cast more rays before trusting them.
    while (unanimous(v) && rho * transfer > tau * (cast + 1) && cast < kConfirmRays * K) {
      cast *= 4;
      v = visibleFraction(r, s, cast, 2 * m_settings.round);
      out.rays += cast;
    }
    V = v.visible,
    se = unanimous(v) ? 1.0 / (cast + 1) : v.standardError;  // unanimous: one ray's worth
  }
  // A partly blocked link may hide a shadow boundary: refine it first (its uncertainty counts
  // the smaller of the visible and blocked shares, plus one sample's worth; a unanimous one
  // one ray's worth of the rays it was given).
  double uncertain = se >= 0.5 ? 0.5 : (V > 0 && V < 1 ? std::min(V, 1 - V) + 1.0 / (K + 1) : se);
  double error = errorGeometry * V + rho * transfer * uncertain;
  if (error > tau) {
    Decision d = splitLarger(r, s);
    if (d != Decision::Keep) {
      out.decision = d;
      return out;
    }
  }
  // Blocked as far as its rays tell. Dropping every such link loses the share its rays missed,
  // always on the same side (1–6 % too little light on a shadowed receiver, more at small K),
  // while the partly visible ones are refined: a choice made on an estimate biases it. So the
  // last round plays Russian roulette: such a link survives with probability
  // P = min(1, ρ·T/τ) and then counts 1/P times, which is unbiased and keeps few of them.
  // Earlier rounds keep them all for the next round to judge.
  double weight = 1;
  if (!(V > 0) && (transfer > 0 || sourceRadiosity > 0) && m_settings.last) {
    const double survive = std::min(1.0, rho * transfer / tau);
    Rng roulette(m_settings.seed + 0x9E3779B97F4A7C15ull * std::uint64_t(2 * m_settings.round + 2),
                 m_h.key(r), m_h.key(s));
    if (!(roulette.uniform() < survive)) return out;  // Drop
    weight = 1 / survive;
  }
  // The decision above rests on those rays (or on last round's value); the value the last
  // round keeps comes from fresh ones. Reusing them biases toward the unanimous cases, which
  // are kept as they are while partly blocked links are refined (measured: the Cornell box
  // floor's direct light 1.2 % high at K = 16). Earlier rounds only steer the refinement: they
  // keep a known link's value, and a new unanimous link's decision rays.
  const bool partial = V > 0 && V < 1;
  const bool elements = R.element && S.element;
  const bool freshRays = m_settings.last || (!knownVisibility && partial);
  if (freshRays || !knownVisibility) {
    int n = cast;  // the rays behind the kept value
    if (freshRays) {
      if (knownVisibility && !partial && se > 0 && se < 0.5)
        cast = std::clamp(int(std::lround(1 / se - 1)), K, kConfirmRays * K);
      n = partial ? kPartialRays * K : cast;
      fresh = visibleFraction(r, s, n, 2 * m_settings.round + 1);
      out.rays += n;
    } else {
      fresh = decided;
    }
    V = fresh.visible, se = unanimous(fresh) ? 1.0 / (n + 1) : fresh.standardError;
    out.link.visibility = float(V * weight);
    out.link.visibilityError = float(se * weight);
    for (int k = 0; k < 4; ++k) out.link.quarterVisible[k] = fresh.quarter[k];
    if (elements) receiverShares(r, s, fresh, out.link);
  }
  // Kept whatever the fresh rays say: dropping those that found nothing would lose their
  // expected share (the last round's links with V = 0 are removed after refinement).
  out.decision = Decision::Keep;
  if (elements) {
    out.link.formFactor =
        knownVisibility && c.formFactor > 0 ? c.formFactor : elementFormFactor(r, s, fMean);
    // The ratio Σwv/Σw is biased at small K (measured: 2 % too little light on a shadowed
    // receiver at K = 4). With the unoccluded F known, E[w] = πF/A_s over uniform pairs, so
    // V = 1 − mean(w(1 − v))·A_s/(πF) is unbiased, and exactly 1 when no ray is blocked.
    if (fresh.blockedKernel > 0 && out.link.formFactor > 0) {
      const double scale = S.area / (kPi * out.link.formFactor);
      out.link.visibility = float(std::clamp(1 - fresh.blockedKernel * scale, 0.0, 1.0) * weight);
      out.link.visibilityError = float(fresh.blockedKernelError * scale * weight);
    }
    quarterShares(r, s, out.link);
  }
  if (elements && !(out.link.formFactor > 0)) out.decision = Decision::Drop;
  return out;
}

RefineStats Refiner::refine(std::vector<HLink>& links, SourceState& state,
                            const std::function<void(long long, long long)>& progress) {
  RefineStats stats;
  // The first level is the links given (with what their rays found); later levels are bare
  // (receiver, source) pairs: 8 bytes a candidate instead of a whole link.
  std::vector<HLink> given;
  given.swap(links);
  bool known = !(given.size() == 1 && given[0].receiver == given[0].source);
  // About as many links are kept as were given: growing by doubling from a few would hold up
  // to twice the links at the end (and three times while the last copy is made).
  links.reserve(given.size() + given.size() / 8);
  std::vector<std::pair<int, int>> frontier, next;
  // Candidates are evaluated in chunks, so the outcomes held at once stay bounded whatever the
  // level's size; the splits they ask for are applied after the whole level, in candidate
  // order, so every candidate of a level sees the same hierarchy (and the node numbering is
  // the same whatever the thread count).
  constexpr std::size_t kChunk = std::size_t(1) << 16;
  std::vector<Outcome> outcomes;
  struct Split {
    Decision decision;
    int receiver, source;
  };
  std::vector<Split> splits;
  for (bool first = true; first || !frontier.empty(); first = false) {
    const std::size_t count = first ? given.size() : frontier.size();
    splits.clear();
    for (std::size_t begin = 0; begin < count; begin += kChunk) {
      const std::size_t end = std::min(count, begin + kChunk);
      outcomes.assign(end - begin, Outcome{});
      tbb::parallel_for(tbb::blocked_range<std::size_t>(begin, end, 64),
                        [&](const tbb::blocked_range<std::size_t>& range) {
                          for (std::size_t i = range.begin(); i < range.end(); ++i) {
                            if (first) {
                              outcomes[i - begin] = evaluate(given[i], known, state);
                            } else {
                              HLink l;
                              l.receiver = frontier[i].first, l.source = frontier[i].second;
                              outcomes[i - begin] = evaluate(l, false, state);
                            }
                          }
                        });
      for (const Outcome& o : outcomes) {
        ++stats.evaluated;
        stats.rays += o.rays;
        if (o.decision == Decision::Keep)
          links.push_back(o.link);
        else if (o.decision == Decision::Drop)
          ++stats.dropped;
        else
          splits.push_back({o.decision, o.link.receiver, o.link.source});
      }
    }
    if (first) std::vector<HLink>().swap(given);
    next.clear();
    for (const Split& o : splits) {
      ++stats.splits;
      const int r = o.receiver, s = o.source;
      switch (o.decision) {
        case Decision::SplitReceiver:
          if (m_h[r].element) m_h.split(r);
          for (int k = 0; k < m_h[r].childCount; ++k) next.push_back({m_h.child(r, k), s});
          break;
        case Decision::SplitSource:
          if (m_h[s].element) m_h.split(s);
          for (int k = 0; k < m_h[s].childCount; ++k) next.push_back({r, m_h.child(s, k)});
          break;
        case Decision::SplitBoth:
          for (int a = 0; a < m_h[r].childCount; ++a)
            for (int b = 0; b < m_h[r].childCount; ++b)
              next.push_back({m_h.child(r, a), m_h.child(r, b)});
          break;
        default:
          break;
      }
    }
    growState(m_h, state);
    frontier.swap(next);
    known = false;
    std::size_t bytes = m_settings.fixedBytes + m_h.bytes() + links.capacity() * sizeof(HLink) +
                        (frontier.capacity() + next.capacity()) * sizeof(frontier[0]) +
                        splits.capacity() * sizeof(Split) + outcomes.capacity() * sizeof(Outcome) +
                        state.radiosity.capacity() * (sizeof(Vec3) * 4);
    if (bytes > m_settings.memoryBudget)
      throw HierarchyMemoryError(
          "hierarchical radiosity outgrew " + setting("memory_budget") + " " +
          gib(m_settings.memoryBudget) + " while refining links (" + std::to_string(m_h.size()) +
          " nodes, " + std::to_string(links.size() + frontier.size()) + " links, about " +
          gib(bytes) + "). Raise " + setting("memory_budget") + ", or ask for less: a larger " +
          setting("epsilon") + " or " + setting("min_area"));
    if (progress) progress(stats.evaluated, static_cast<long long>(frontier.size()));
  }
  // Sources split after a link to them was kept (by a later link in this round) get their
  // quarter shares now: without them the gather takes such a source's mean.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, links.size(), 1024),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i < range.end(); ++i) {
                        HLink& l = links[i];
                        if (l.quarterShare[0] < 0 && m_h[l.receiver].element &&
                            m_h[l.source].element && m_h[l.source].childCount == 4)
                          quarterShares(l.receiver, l.source, l);
                      }
                    });
  return stats;
}

}  // namespace radkit
