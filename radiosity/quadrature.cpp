// Gauss–Legendre nodes and the patch charts used by the adaptive cubature.
#include "radiosity/quadrature.h"

#include <algorithm>
#include <stdexcept>

namespace radkit {

GaussLegendreRule gaussLegendre(int n) {
  if (n < 1) throw std::invalid_argument("Gauss-Legendre order must be >= 1");
  GaussLegendreRule rule;
  rule.nodes.resize(n);
  rule.weights.resize(n);
  for (int i = 0; i < n; ++i) {
    // Newton on P_n from the Chebyshev-like guess; P_n by the three-term recurrence.
    double x = std::cos(M_PI * (i + 0.75) / (n + 0.5)), dp = 1;
    for (int iter = 0; iter < 100; ++iter) {
      double p0 = 1, p1 = x;
      for (int k = 2; k <= n; ++k) {
        double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (x * p1 - p0) / (x * x - 1);
      double step = p1 / dp;
      x -= step;
      if (std::fabs(step) < 1e-16) break;
    }
    // Map [-1, 1] to [0, 1]: node (1 − x)/2, weight 1/((1 − x²) P_n'(x)²).
    rule.nodes[i] = 0.5 * (1 - x);
    rule.weights[i] = 1.0 / ((1 - x * x) * dp * dp);
  }
  return rule;
}

PatchChart::PatchChart(const Vec3* v, int count) : m_quad(count == 4) {
  if (count != 3 && count != 4) throw std::invalid_argument("PatchChart needs 3 or 4 vertices");
  for (int k = 0; k < count; ++k) m_v[k] = v[k];
}

Vec3 PatchChart::point(double s, double t) const {
  if (m_quad)
    return m_v[0] * ((1 - s) * (1 - t)) + m_v[1] * (s * (1 - t)) + m_v[2] * (s * t) +
           m_v[3] * ((1 - s) * t);
  return m_v[0] + (m_v[1] - m_v[0]) * s + (m_v[2] - m_v[1]) * (s * t);
}

double PatchChart::jacobian(double s, double t) const {
  if (m_quad) {
    Vec3 ds = (m_v[1] - m_v[0]) * (1 - t) + (m_v[2] - m_v[3]) * t;
    Vec3 dt = (m_v[3] - m_v[0]) * (1 - s) + (m_v[2] - m_v[1]) * s;
    return length(cross(ds, dt));
  }
  return s * length(cross(m_v[1] - m_v[0], m_v[2] - m_v[1]));
}

bool AdaptiveCubature::isFar(const PatchChart& c, double s0, double s1, double t0, double t1,
                             const TargetSphere& target) const {
  if (!std::isfinite(target.radius)) return false;
  Vec3 centre = c.point(0.5 * (s0 + s1), 0.5 * (t0 + t1));
  double radius = 0;
  for (Vec3 corner : {c.point(s0, t0), c.point(s1, t0), c.point(s1, t1), c.point(s0, t1)})
    radius = std::max(radius, length(corner - centre));
  double gap = length(target.centre - centre) - target.radius - radius;
  return gap > m_settings.farRatio * 2 * radius;
}

AdaptiveCubature::AdaptiveCubature(const QuadratureSettings& settings)
    : m_settings(settings),
      m_high(gaussLegendre(std::max(1, settings.order))),
      m_low(gaussLegendre(std::max(1, settings.order - 1))) {}

}  // namespace radkit
