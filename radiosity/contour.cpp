// Lambert's contour formula for the point-to-polygon form factor.
#include "radiosity/contour.h"

#include <cmath>
#include <stdexcept>
#include <vector>

#include "util/target_clones.h"

namespace radkit {

int clipToHalfSpace(const Vec3* in, int count, const Vec3& x, const Vec3& n, Vec3* out) {
  int m = 0;
  for (int k = 0; k < count; ++k) {
    const Vec3& a = in[k];
    const Vec3& b = in[(k + 1) % count];
    double da = dot(a - x, n), db = dot(b - x, n);
    if (da >= 0) out[m++] = a;
    // The edge crosses the plane strictly: keep the crossing point.
    if ((da >= 0) != (db >= 0)) {
      double t = da / (da - db);
      out[m++] = a + (b - a) * t;
    }
  }
  return m;
}

namespace {
/// atan2(y, x) for y >= 0 without branches, so that the loop over edges vectorises (glibc's
/// atan2 took a quarter of the adaptive contour's time). The argument is reduced to
/// |z| <= tan(π/8), where atan z = z + z t P(t), t = z², P of degree 10: least squares on
/// 200 Chebyshev nodes of (atan √t/√t − 1)/t in 40-digit arithmetic, relative error of the
/// reduced atan 1.1e-16. The reductions (π/4 +, π/2 −, π −) add about an ulp of π.
inline double atan2Upper(double y, double x) {
  constexpr double kP[11] = {-0.33333333333333331,  0.19999999999995652,   -0.14285714284691381,
                             0.11111111017100327,   -0.090909046476956801, 0.076921846993717777,
                             -0.066645313698050088, 0.058583118105011531,  -0.050862548858231431,
                             0.039253696320618564,  -0.019202529268412281};
  const double ax = std::fabs(x);
  const double hi = y > ax ? y : ax, lo = y > ax ? ax : y;  // atan(lo/hi) in [0, π/4]
  // Above tan(π/8): atan(a) = π/4 + atan((a − 1)/(a + 1)), a = lo/hi, one division.
  const bool upper = lo > 0.41421356237309503 * hi;
  const double num = upper ? lo - hi : lo, den = upper ? lo + hi : hi;
  const double z = num / (den > 0 ? den : 1.0), t = z * z;
  double p = kP[10];
  for (int k = 9; k >= 0; --k) p = p * t + kP[k];
  double angle = z + z * t * p + (upper ? M_PI / 4 : 0.0);
  angle = y > ax ? M_PI / 2 - angle : angle;
  return x < 0 ? M_PI - angle : angle;
}

RADKIT_TARGET_CLONES
double contourSum(const double* px, const double* py, const double* pz, const Vec3& n, int edges) {
  // Edge k runs from point k to point k + 1 (relative to x); padding edges are degenerate.
  double sum = 0;
  for (int k = 0; k < edges; ++k) {
    const double ax = px[k], ay = py[k], az = pz[k];
    const double bx = px[k + 1], by = py[k + 1], bz = pz[k + 1];
    const double cx = ay * bz - az * by, cy = az * bx - ax * bz, cz = ax * by - ay * bx;
    const double c = std::sqrt(cx * cx + cy * cy + cz * cz);
    const double gamma = atan2Upper(c, ax * bx + ay * by + az * bz);
    // c = 0: x on the edge's line, the edge subtends no area.
    sum += c > 0 ? gamma * (n.x * cx + n.y * cy + n.z * cz) / (c > 0 ? c : 1.0) : 0.0;
  }
  return sum;
}
}  // namespace

double unclippedContourFormFactor(const Vec3& x, const Vec3& n, const Vec3* polygon, int count) {
  // Lambert's contour integral (Cohen & Wallace ch. 4): each edge contributes the angle γ_k
  // it subtends at x times the cosine between n and the normal of the plane through x and
  // the edge. Unnormalized vectors give the same angle (atan2 of |a×b| and a·b) and the
  // same plane normal. The vertices relative to x are laid out as arrays, closed by the
  // first vertex and padded to whole vectors of 4 with copies of it (edges of length 0).
  constexpr int kStack = kMaxPolygonVertices + 4;
  double fixed[3 * kStack];
  std::vector<double> heap;
  const int edges = (count + 3) / 4 * 4;
  double* p = fixed;
  if (edges + 1 > kStack) heap.resize(3 * std::size_t(edges + 1)), p = heap.data();
  const int stride = edges + 1 > kStack ? edges + 1 : kStack;
  // 2 · stride stays far below INT_MAX (a polygon has at most a few thousand vertices); the
  // form with a wider type makes GCC 12 warn that the stack buffer may be read uninitialised.
  double *px = p, *py = p + stride,
         *pz = p + 2 * stride;  // NOLINT(bugprone-implicit-widening-of-multiplication-result)
  for (int k = 0; k <= edges; ++k) {
    const Vec3 v = polygon[k < count ? k : 0] - x;
    px[k] = v.x, py[k] = v.y, pz[k] = v.z;
  }
  return std::fabs(contourSum(px, py, pz, n, edges)) / (2 * M_PI);
}

double pointToPolygonFormFactor(const Vec3& x, const Vec3& n, const Vec3* polygon, int count) {
  // Patches take the stack path; long polygons (tests, disks) a heap buffer.
  Vec3 fixed[kMaxPolygonVertices];
  std::vector<Vec3> heap;
  Vec3* clipped = fixed;
  if (count + 1 > kMaxPolygonVertices) {
    heap.resize(std::size_t(count) + 1);
    clipped = heap.data();
  }
  int m = clipToHalfSpace(polygon, count, x, n, clipped);
  if (m < 3) return 0.0;
  return unclippedContourFormFactor(x, n, clipped, m);
}

PlaneToPolygon::PlaneToPolygon(const Vec3& planePoint, const Vec3& n, const Vec3* polygon,
                               int count)
    : m_normal(n) {
  if (count + 1 > kMaxPolygonVertices)
    throw std::invalid_argument("PlaneToPolygon: polygon has too many vertices");
  m_count = clipToHalfSpace(polygon, count, planePoint, n, m_clipped);
}

double pointToPolygonFormFactor(const Vec3& x, const Vec3& n, const std::vector<Vec3>& polygon) {
  return pointToPolygonFormFactor(x, n, polygon.data(), static_cast<int>(polygon.size()));
}

}  // namespace radkit
