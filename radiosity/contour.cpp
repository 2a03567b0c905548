// Lambert's contour formula for the point-to-polygon form factor.
#include "radiosity/contour.h"

#include <cmath>

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

double unclippedContourFormFactor(const Vec3& x, const Vec3& n, const Vec3* polygon, int count) {
  // Lambert's contour integral (Cohen & Wallace ch. 4): each edge contributes the angle γ_k
  // it subtends at x times the cosine between n and the normal of the plane through x and
  // the edge. Unnormalized vectors give the same angle (atan2 of |a×b| and a·b) and the
  // same plane normal.
  double sum = 0;
  for (int k = 0; k < count; ++k) {
    Vec3 a = polygon[k] - x;
    Vec3 b = polygon[(k + 1) % count] - x;
    Vec3 c = cross(a, b);
    double cLength = length(c);
    if (cLength <= 0) continue;  // x on the edge's line: the edge subtends no area
    double gamma = std::atan2(cLength, dot(a, b));
    sum += gamma * dot(n, c) / cLength;
  }
  return std::fabs(sum) / (2 * M_PI);
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

double pointToPolygonFormFactor(const Vec3& x, const Vec3& n, const std::vector<Vec3>& polygon) {
  return pointToPolygonFormFactor(x, n, polygon.data(), static_cast<int>(polygon.size()));
}

}  // namespace radkit
