#include "hierarchy/refine.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <tbb/parallel_for.h>

#include "geometry/sampling.h"
#include "radiosity/contour.h"

namespace radkit {

namespace {

constexpr double kPi = 3.14159265358979323846;
/// Relative accuracy of an element-to-element form factor's cubature.
constexpr double kFormFactorTolerance = 1e-3;
/// Nodes of the 2-point Gauss-Legendre rule on [0, 1]: where F is sampled over a receiver.
const double kGauss2[2] = {0.5 - 0.5 / std::sqrt(3.0), 0.5 + 0.5 / std::sqrt(3.0)};
constexpr int kPartialRays = 4;
/// Weight of the source's radiosity range in a link's error. The range bounds the error of
/// using the source's mean; at weight 4 the Cornell box's worst surface moved from 2.50 % to
/// 2.16 % of the photon reference for 12 % more time (16: 2.03 %, 38 % more).
constexpr double kSourceSpreadWeight = 4.0;

double angleBetween(const Vec3& a, const Vec3& b) {
  return std::acos(std::clamp(dot(a, b), -1.0, 1.0));
}

/// Largest and smallest max(0, n·w) over normals within `cone` of `axis` and directions within
/// `spread` of w: the cosine bounds of a node seen along directions near w.
std::pair<double, double> cosineBounds(const Vec3& axis, double cone, const Vec3& w, double spread) {
  double phi = angleBetween(axis, w);
  double hi = std::max(0.0, std::cos(std::max(0.0, phi - cone - spread)));
  double lo = std::max(0.0, std::cos(std::min(kPi, phi + cone + spread)));
  return {lo, hi};
}

std::string gib(std::size_t bytes) {
  std::ostringstream s;
  s.precision(3);
  s << double(bytes) / double(1ull << 30) << " GiB";
  return s.str();
}

}  // namespace

void growState(const Hierarchy& h, SourceState& state) {
  std::size_t old = state.radiosity.size();
  state.radiosity.resize(h.size());
  state.powerVector.resize(h.size());
  state.radiosityMin.resize(h.size());
  state.radiosityMax.resize(h.size());
  for (std::size_t n = old; n < state.radiosity.size(); ++n) {
    int parent = h[int(n)].parent;
    state.radiosity[n] = parent >= 0 ? state.radiosity[parent] : Vec3{};
    state.radiosityMin[n] = state.radiosityMax[n] = maxComponent(state.radiosity[n]);
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
  const HPolygon& pr = m_h.polygon(r);
  const HPolygon& ps = m_h.polygon(s);
  // Only the part of r in front of s sees s's front: integrate over that part, so the
  // integrand has no kink inside the domain.
  Vec3 domain[kMaxPolygonVertices];
  int count = clipToHalfSpace(pr.v, pr.count, m_h[s].centre, ps.normal, domain);
  if (count < 3) return 0.0;
  auto integrand = [&](const Vec3& x) { return pointToPolygonFormFactor(x, pr.normal, ps.v, ps.count); };
  QuadratureStats stats;
  const double area = m_h[r].area;
  TargetSphere target{m_h[s].centre, m_h[s].radius};
  // Relative accuracy: a link's F need not be known better than the error its oracle allows,
  // and the four-point estimate already has it to (size/distance)⁴ for distant pairs.
  const double tolerance = std::max(kFormFactorTolerance * estimate, QuadratureSettings{}.tolerance) * area;
  return m_cubature.integrate(domain, count, tolerance, integrand, stats, target) / area;
}

void Refiner::quarterShares(int r, int s, HLink& link) const {
  link.quarterShare[0] = -1;
  const HNode& S = m_h[s];
  if (S.childCount != 4) return;
  const HPolygon& pr = m_h.polygon(r);
  PatchChart chart(pr.v, pr.count);
  double f[4] = {0, 0, 0, 0}, total = 0;
  for (int k = 0; k < 4; ++k) {
    const HPolygon& q = m_h.polygon(S.firstChild + k);
    for (double a : kGauss2)
      for (double b : kGauss2) {
        Vec3 x = chart.point(a, b);
        if (dot(x - m_h[S.firstChild + k].centre, q.normal) > 0)
          f[k] += chart.jacobian(a, b) * pointToPolygonFormFactor(x, pr.normal, q.v, q.count);
      }
    total += f[k];
  }
  if (!(total > 0)) return;
  for (int k = 0; k < 4; ++k) link.quarterShare[k] = float(f[k] / total);
}

std::pair<double, double> Refiner::visibleFraction(int r, int s, int K) const {
  Rng rng(m_settings.seed, m_h[r].key, m_h[s].key);
  std::vector<double> u;
  std::vector<int> scratch;
  latinHypercube(K, 6, rng, u, scratch);
  double sumW = 0, sumWV = 0, sumW2V = 0, sumW2 = 0;
  for (int k = 0; k < K; ++k) {
    const double* q = &u[std::size_t(k) * 6];
    Vec3 nx, ny;
    Vec3 x = m_h.samplePoint(r, q[0], q[1], q[2], nx);
    Vec3 y = m_h.samplePoint(s, q[3], q[4], q[5], ny);
    Vec3 d = y - x;
    double r2 = dot(d, d);
    if (!(r2 > 0)) continue;
    // The kernel cosθ_x cosθ_y / r² (per unit r² again for the unnormalised d).
    double w = std::max(0.0, dot(nx, d)) * std::max(0.0, -dot(ny, d)) / (r2 * r2);
    if (!(w > 0)) continue;
    bool visible = !m_visibility.occluded(x, nx, y, ny);
    sumW += w;
    sumW2 += w * w;
    if (visible) sumWV += w, sumW2V += w * w;
  }
  if (!(sumW > 0)) return {1.0, 0.5};  // no sample pair faces both ways: nothing known
  double V = sumWV / sumW;
  // Σ w_k²(v_k − V)² with v_k ∈ {0, 1}, expanded.
  double var = sumW2V * (1 - 2 * V) + V * V * sumW2;
  return {V, std::sqrt(std::max(0.0, var)) / sumW};
}

Refiner::Outcome Refiner::evaluate(const HLink& c, bool knownVisibility, const SourceState& state) const {
  Outcome out;
  out.link = c;
  const int r = c.receiver, s = c.source;
  const HNode& R = m_h[r];
  const HNode& S = m_h[s];
  if (r == s) {
    out.decision = R.element ? Decision::Drop : Decision::SplitBoth;  // a plane never sees itself
    return out;
  }
  const double rho = R.reflectanceMax;
  const double tau = m_settings.threshold;
  const double sourceRadiosity = maxComponent(state.radiosity[s]);
  double transfer = 0, errorGeometry = 0;  // W, with full visibility
  double fMean = 0;
  const Vec3 toSource = S.centre - R.centre;
  const double dist = length(toSource);
  const bool overlapping = !(dist > R.radius + S.radius);

  if (R.element && S.element) {
    const HPolygon& pr = m_h.polygon(r);
    const HPolygon& ps = m_h.polygon(s);
    const double tol = 1e-3 * m_visibility.epsilon();
    bool sInFront = false, rInFront = false;
    for (int k = 0; k < ps.count; ++k) sInFront |= dot(ps.v[k] - R.centre, pr.normal) > tol;
    for (int k = 0; k < pr.count; ++k) rInFront |= dot(pr.v[k] - S.centre, ps.normal) > tol;
    if (!sInFront || !rInFront) return out;  // Drop
    // Point values over r: the mean of the 2×2 Gauss points estimates F_rs; the spread of
    // those and of points near each corner and at the centre says how much F varies over r
    // (symmetric points alone miss it: directly opposite squares give four equal values).
    // Points behind s's plane see nothing of its front.
    auto pointValue = [&](const Vec3& x) {
      return dot(x - S.centre, ps.normal) > 0 ? pointToPolygonFormFactor(x, pr.normal, ps.v, ps.count) : 0.0;
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
    for (int k = 0; k <= pr.count; ++k) {
      // Corners pulled a hundredth toward the centroid: a corner on s's edge is singular.
      Vec3 x = k < pr.count ? pr.v[k] * 0.99 + R.centre * 0.01 : R.centre;
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
      transfer = std::clamp(maxComponent(intensity) * projectedArea(m_h, r, w) / clusterTransfer(m_h, r, s).denominator,
                            tMin, tMax);
      errorGeometry = rho * 0.5 * (tMax - tMin);
    }
  }

  // The source's own variation: the receiver may see only its brighter or darker part.
  if (sourceRadiosity > 0)
    errorGeometry += kSourceSpreadWeight * rho * transfer * (state.radiosityMax[s] - state.radiosityMin[s]) / sourceRadiosity;
  if (errorGeometry > tau) {
    out.decision = splitLarger(r, s);
    if (out.decision != Decision::Keep) return out;
  }
  double V = c.visibility, se = c.visibilityError;
  if (!knownVisibility) {
    std::tie(V, se) = visibleFraction(r, s, m_settings.raysPerLink);
    out.rays = m_settings.raysPerLink;
    // A partly blocked link gets kPartialRays times as many rays: the ratio estimate of its
    // visible share is biased low by O(1/K) (measured: 1 % of the Cornell box floor's row
    // sum at K = 16, gone at K = 1 024), and these links carry the shadows.
    if (V > 0 && V < 1) {
      std::tie(V, se) = visibleFraction(r, s, kPartialRays * m_settings.raysPerLink);
      out.rays += kPartialRays * m_settings.raysPerLink;
    }
    out.link.visibility = float(V);
    out.link.visibilityError = float(se);
  }
  // A partly blocked link may hide a shadow boundary: refine it first (its uncertainty counts
  // the smaller of the visible and blocked shares, plus one sample's worth).
  const int K = m_settings.raysPerLink;
  double uncertain = se >= 0.5 ? 0.5 : (V < 1 ? std::min(V, 1 - V) + 1.0 / (K + 1) : 0.0);
  double error = errorGeometry * V + rho * transfer * uncertain;
  if (error > tau) {
    Decision d = splitLarger(r, s);
    if (d != Decision::Keep) {
      out.decision = d;
      return out;
    }
  }
  // Blocked: dropped once its possible share is within τ. A source still dark (its light not
  // yet known in an early round) keeps the link, so the next round can judge it.
  if (!(V > 0) && (transfer > 0 || sourceRadiosity > 0)) return out;
  out.decision = Decision::Keep;
  if (R.element && S.element) {
    out.link.formFactor = knownVisibility && c.formFactor > 0 ? c.formFactor : elementFormFactor(r, s, fMean);
    quarterShares(r, s, out.link);
  }
  if (R.element && S.element && !(out.link.formFactor > 0) && V > 0) out.decision = Decision::Drop;
  return out;
}

RefineStats Refiner::refine(std::vector<HLink>& links, SourceState& state,
                            const std::function<void(long long, long long)>& progress) {
  RefineStats stats;
  std::vector<HLink> frontier;
  frontier.swap(links);
  bool known = !(frontier.size() == 1 && frontier[0].receiver == frontier[0].source);
  std::vector<Outcome> outcomes;
  std::vector<HLink> next;
  auto candidate = [](int r, int s) {
    HLink l;
    l.receiver = r, l.source = s;
    return l;
  };
  while (!frontier.empty()) {
    outcomes.assign(frontier.size(), Outcome{});
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, frontier.size(), 64),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        for (std::size_t i = range.begin(); i < range.end(); ++i)
                          outcomes[i] = evaluate(frontier[i], known, state);
                      });
    // Apply the decisions serially in candidate order: new nodes get the same numbers
    // whatever the thread count.
    next.clear();
    for (const Outcome& o : outcomes) {
      ++stats.evaluated;
      stats.rays += o.rays;
      const int r = o.link.receiver, s = o.link.source;
      switch (o.decision) {
        case Decision::Keep: links.push_back(o.link); break;
        case Decision::Drop: ++stats.dropped; break;
        case Decision::SplitReceiver:
          ++stats.splits;
          if (m_h[r].element) m_h.split(r);
          for (int k = 0; k < m_h[r].childCount; ++k) next.push_back(candidate(m_h.child(r, k), s));
          break;
        case Decision::SplitSource:
          ++stats.splits;
          if (m_h[s].element) m_h.split(s);
          for (int k = 0; k < m_h[s].childCount; ++k) next.push_back(candidate(r, m_h.child(s, k)));
          break;
        case Decision::SplitBoth:
          ++stats.splits;
          for (int a = 0; a < m_h[r].childCount; ++a)
            for (int b = 0; b < m_h[r].childCount; ++b) next.push_back(candidate(m_h.child(r, a), m_h.child(r, b)));
          break;
      }
    }
    growState(m_h, state);
    frontier.swap(next);
    known = false;
    std::size_t bytes = m_settings.fixedBytes + m_h.bytes() +
                        (links.capacity() + frontier.capacity() + next.capacity()) * sizeof(HLink) +
                        outcomes.capacity() * sizeof(Outcome) +
                        state.radiosity.capacity() * (sizeof(Vec3) * 4);
    if (bytes > m_settings.memoryBudget)
      throw HierarchyMemoryError("hierarchical radiosity outgrew --memory-budget " + gib(m_settings.memoryBudget) +
                                 " while refining links (" + std::to_string(m_h.size()) + " nodes, " +
                                 std::to_string(links.size() + frontier.size()) + " links, about " + gib(bytes) +
                                 "). Raise --memory-budget, or ask for less: a larger --epsilon or --min-area");
    if (progress) progress(stats.evaluated, static_cast<long long>(frontier.size()));
  }
  return stats;
}

}  // namespace radkit
