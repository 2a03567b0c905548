#include "render/smooth_radiosity.h"

#include <algorithm>
#include <cmath>

namespace radkit {

std::array<double, 4> meanValueCoordinates(const Vec3* poly, int n, const Vec3& x) {
  std::array<double, 4> w{0, 0, 0, 0};
  Vec3 d[4];
  double r[4];
  for (int i = 0; i < n; ++i) {
    d[i] = poly[i] - x;
    r[i] = length(d[i]);
    if (r[i] < 1e-300) {  // at a vertex
      w[i] = 1;
      return w;
    }
  }
  // tan(α/2) of the angle at x between two corners, from its cosine.
  auto tanHalf = [&](int a, int b) {
    const double c = std::clamp(dot(d[a], d[b]) / (r[a] * r[b]), -1.0, 1.0);
    return std::sqrt(std::max(0.0, (1 - c) / (1 + c)));
  };
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    w[i] = (tanHalf((i + n - 1) % n, i) + tanHalf(i, (i + 1) % n)) / r[i];
    sum += w[i];
  }
  for (int i = 0; i < n; ++i) w[i] = sum > 0 ? w[i] / sum : 1.0 / n;
  return w;
}

SmoothRadiosity::SmoothRadiosity(const PatchMesh& mesh, const std::vector<Vec3>& radiosity,
                                 const SmoothSettings& s, const std::vector<double>& error)
    : m_mesh(mesh), m_patch(radiosity), m_corner(mesh.size()) {
  // Patches around each vertex, compressed rows.
  std::vector<int> start(mesh.vertices.size() + 1, 0), around;
  for (const Patch& p : mesh.patches)
    for (int k = 0; k < p.vertexCount; ++k) ++start[p.vertex[k] + 1];
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) start[v + 1] += start[v];
  around.resize(start.back());
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (int i = 0; i < mesh.size(); ++i)
    for (int k = 0; k < mesh.patches[i].vertexCount; ++k)
      around[fill[mesh.patches[i].vertex[k]]++] = i;

  const double cosCrease = std::cos(s.creaseAngleDeg * M_PI / 180);
  auto sigma = [&](int i) {
    return error.empty() ? s.relativeError * luminance(radiosity[i]) : error[i];
  };
  // Symmetric, so two patches that average with each other see the same shared corner value.
  auto agree = [&](int i, int j) {
    const Patch &a = mesh.patches[i], &b = mesh.patches[j];
    if (a.surface != b.surface || dot(a.normal, b.normal) < cosCrease) return false;
    const double gap = std::fabs(luminance(radiosity[i]) - luminance(radiosity[j]));
    return gap <= s.errorMultiple * std::hypot(sigma(i), sigma(j));
  };
  for (int i = 0; i < mesh.size(); ++i) {
    const Patch& p = mesh.patches[i];
    for (int k = 0; k < p.vertexCount; ++k) {
      // Accumulate departures from B_i: a patch among equals gets B_i back exactly.
      Vec3 sum;
      double weight = 0;
      const int v = p.vertex[k];
      for (int a = start[v]; a < start[v + 1]; ++a) {
        const int j = around[a];
        if (j != i && !agree(i, j)) continue;
        sum += (radiosity[j] - radiosity[i]) * mesh.patches[j].area;
        weight += mesh.patches[j].area;
      }
      m_corner[i][k] = weight > 0 ? radiosity[i] + sum / weight : radiosity[i];
    }
  }
}

Vec3 SmoothRadiosity::at(int patch, const Vec3& point) const {
  const Patch& p = m_mesh.patches[patch];
  Vec3 poly[4];
  for (int k = 0; k < p.vertexCount; ++k) poly[k] = m_mesh.vertex(p, k);
  const std::array<double, 4> w = meanValueCoordinates(poly, p.vertexCount, point);
  Vec3 b = m_patch[patch];
  for (int k = 0; k < p.vertexCount; ++k) b += (m_corner[patch][k] - m_patch[patch]) * w[k];
  return b;
}

std::vector<Vec3> smoothCornerValues(const std::vector<Vec3>& points,
                                     const std::vector<std::vector<int>>& polygons,
                                     const std::vector<int>& surface,
                                     const std::vector<Vec3>& perPatch,
                                     const SmoothSettings& settings) {
  PatchMesh mesh;
  mesh.vertices = points;
  for (std::size_t i = 0; i < polygons.size(); ++i) {
    Patch p;
    p.surface = surface[i];
    if (polygons[i].size() == 3 || polygons[i].size() == 4) {
      p.vertexCount = int(polygons[i].size());
      for (int k = 0; k < p.vertexCount; ++k) p.vertex[k] = polygons[i][k];
      computePatchGeometry(mesh.vertices, p);
    }
    mesh.patches.push_back(p);
  }
  const SmoothRadiosity smooth(mesh, perPatch, settings);
  std::vector<Vec3> out;
  for (std::size_t i = 0; i < polygons.size(); ++i)
    for (std::size_t k = 0; k < polygons[i].size(); ++k)
      out.push_back(mesh.patches[i].vertexCount > 0 ? smooth.corners(int(i))[k] : perPatch[i]);
  return out;
}

std::vector<double> smoothCornerValues(const std::vector<Vec3>& points,
                                       const std::vector<std::vector<int>>& polygons,
                                       const std::vector<int>& surface,
                                       const std::vector<double>& perPatch,
                                       const SmoothSettings& settings) {
  std::vector<Vec3> grey;
  for (double v : perPatch) grey.push_back({v, v, v});
  std::vector<double> out;
  for (const Vec3& v : smoothCornerValues(points, polygons, surface, grey, settings))
    out.push_back(v.x);
  return out;
}

}  // namespace radkit
