// Gauss–Legendre quadrature over planar patches, adaptive where the integrand varies (near a
// shared edge, where the point-to-polygon integrand has a logarithmic derivative singularity).
#pragma once

#include <cmath>
#include <vector>

#include "radiosity/contour.h"
#include "util/vec3.h"

namespace radkit {

/// Nodes and weights of the n-point Gauss–Legendre rule on [0, 1] (weights sum to 1).
struct GaussLegendreRule {
  std::vector<double> nodes, weights;
};

/// \brief The n-point rule, n >= 1, by Newton iteration on the Legendre polynomial P_n.
GaussLegendreRule gaussLegendre(int n);

/// A planar triangle or convex quad as a polynomial map of the unit square:
/// a quad by its bilinear map, a triangle by the Duffy (collapsed square) map
/// P(s,t) = v0 + s(v1 − v0) + s t (v2 − v1), whose Jacobian s|(v1−v0)×(v2−v1)| vanishes at
/// the collapsed vertex.
class PatchChart {
 public:
  PatchChart(const Vec3* v, int count);
  Vec3 point(double s, double t) const;
  /// |∂P/∂s × ∂P/∂t|: area element per unit parameter area.
  double jacobian(double s, double t) const;

 private:
  Vec3 m_v[4];
  bool m_quad;
};

/// How finely point-polygon integrates over patch i.
struct QuadratureSettings {
  int order =
      4;  ///< Gauss–Legendre points per axis per cell (1: midpoint, no refinement);
          ///< 4, not 2: |Q4 − Q3| bounds the kept rule far more tightly (docs/formfactors.md)
  double tolerance = 1e-6;  ///< accept a cell when |Q_order − Q_order−1| <= its share (in F)
  int maxDepth = 10;        ///< quadtree depth limit per cell
  /// A cell farther than farRatio × its diameter from the target's bounding sphere takes the
  /// order-n rule without an error estimate: there the integrand is smooth on the cell's
  /// scale and the rule's error falls as (diameter/distance)^(2n).
  double farRatio = 2.0;
  /// Per-pair selection (pair_rule.h): a pair whose patches lie wholly in front of each other
  /// takes the cheapest tensor rule of level <= pairLevels whose error bound is at most
  /// `tolerance` relative to F_ij; the others, the adaptive cubature above. 0: adaptive for all.
  int pairLevels = 8;
};

/// Bounding sphere of what the integrand looks at (the target patch).
struct TargetSphere {
  Vec3 centre;
  double radius = 0;
};

/// Work counters of one integration.
struct QuadratureStats {
  long long evaluations = 0;
  int deepest = 0;
};

/// Adaptive cubature of f over one chart: a cell is accepted when the rules of order n and
/// n − 1 agree within its tolerance; otherwise it splits in four, each child with half the
/// tolerance (so cells along a singular edge stop at width ~ sqrt(tolerance)).
class AdaptiveCubature {
 public:
  AdaptiveCubature(const QuadratureSettings& settings);

  /// \brief ∫ f dA over a convex polygon (3..kMaxPolygonVertices−1 vertices; more than four are
  /// fanned into triangles), absolute tolerance `tolerance` in the units of the integral.
  template <typename F>
  double integrate(const Vec3* poly, int count, double tolerance, F&& f, QuadratureStats& st,
                   const TargetSphere& target = {{0, 0, 0}, INFINITY}) const;

 private:
  template <typename F>
  double rule(const PatchChart& c, const GaussLegendreRule& r, double s0, double s1, double t0,
              double t1, F& f, QuadratureStats& st) const;
  template <typename F>
  double cell(const PatchChart& c, double s0, double s1, double t0, double t1, double tol,
              int depth, F& f, QuadratureStats& st, const TargetSphere& target) const;
  bool isFar(const PatchChart& c, double s0, double s1, double t0, double t1,
             const TargetSphere& target) const;

  QuadratureSettings m_settings;
  GaussLegendreRule m_high, m_low;
};

// ---- template definitions ----

template <typename F>
double AdaptiveCubature::rule(const PatchChart& c, const GaussLegendreRule& r, double s0, double s1,
                              double t0, double t1, F& f, QuadratureStats& st) const {
  double ds = s1 - s0, dt = t1 - t0, sum = 0;
  for (std::size_t a = 0; a < r.nodes.size(); ++a) {
    double s = s0 + ds * r.nodes[a];
    for (std::size_t b = 0; b < r.nodes.size(); ++b) {
      double t = t0 + dt * r.nodes[b];
      sum += r.weights[a] * r.weights[b] * c.jacobian(s, t) * f(c.point(s, t));
    }
  }
  st.evaluations += static_cast<long long>(r.nodes.size() * r.nodes.size());
  return sum * ds * dt;
}

template <typename F>
double AdaptiveCubature::cell(const PatchChart& c, double s0, double s1, double t0, double t1,
                              double tol, int depth, F& f, QuadratureStats& st,
                              const TargetSphere& target) const {
  double high = rule(c, m_high, s0, s1, t0, t1, f, st);
  if (m_settings.order < 2 || depth >= m_settings.maxDepth) return high;
  if (isFar(c, s0, s1, t0, t1, target)) return high;
  double low = rule(c, m_low, s0, s1, t0, t1, f, st);
  if (std::fabs(high - low) <= tol) return high;
  if (depth + 1 > st.deepest) st.deepest = depth + 1;
  double sm = 0.5 * (s0 + s1), tm = 0.5 * (t0 + t1);
  return cell(c, s0, sm, t0, tm, tol / 2, depth + 1, f, st, target) +
         cell(c, sm, s1, t0, tm, tol / 2, depth + 1, f, st, target) +
         cell(c, s0, sm, tm, t1, tol / 2, depth + 1, f, st, target) +
         cell(c, sm, s1, tm, t1, tol / 2, depth + 1, f, st, target);
}

template <typename F>
double AdaptiveCubature::integrate(const Vec3* poly, int count, double tolerance, F&& f,
                                   QuadratureStats& st, const TargetSphere& target) const {
  if (count < 3) return 0.0;
  if (count <= 4) return cell(PatchChart(poly, count), 0, 1, 0, 1, tolerance, 0, f, st, target);
  // Fan triangulation; each triangle gets the share of the tolerance of its area.
  double total = 0, sum = 0;
  for (int k = 1; k + 1 < count; ++k)
    total += length(cross(poly[k] - poly[0], poly[k + 1] - poly[0]));
  for (int k = 1; k + 1 < count && total > 0; ++k) {
    Vec3 tri[3] = {poly[0], poly[k], poly[k + 1]};
    double share = length(cross(tri[1] - tri[0], tri[2] - tri[0])) / total;
    sum += cell(PatchChart(tri, 3), 0, 1, 0, 1, tolerance * share, 0, f, st, target);
  }
  return sum;
}

}  // namespace radkit
