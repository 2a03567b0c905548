#include "test_scenes.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

namespace radkit::test {

int MeshBuilder::beginSurface(const std::string& name) {
  if (m_mesh.surfaceBegin.empty()) m_mesh.surfaceBegin.push_back(0);
  m_names.push_back(name);
  m_mesh.surfaceBegin.push_back(m_mesh.size());
  return int(m_names.size()) - 1;
}

void MeshBuilder::addPatch(const std::vector<int>& v, int surface) {
  Patch p;
  p.vertexCount = int(v.size());
  for (std::size_t k = 0; k < v.size(); ++k) p.vertex[k] = v[k];
  p.surface = surface;
  computePatchGeometry(m_mesh.vertices, p);
  m_mesh.patches.push_back(p);
  m_mesh.surfaceBegin.back() = m_mesh.size();
}

int MeshBuilder::addRectangle(const std::string& name, const Vec3& corner, const Vec3& e1,
                              const Vec3& e2, int nu, int nv) {
  int s = beginSurface(name);
  int base = int(m_mesh.vertices.size());
  for (int b = 0; b <= nv; ++b)
    for (int a = 0; a <= nu; ++a)
      m_mesh.vertices.push_back(corner + e1 * (double(a) / nu) + e2 * (double(b) / nv));
  auto id = [&](int a, int b) { return base + b * (nu + 1) + a; };
  for (int b = 0; b < nv; ++b)
    for (int a = 0; a < nu; ++a)
      addPatch({id(a, b), id(a + 1, b), id(a + 1, b + 1), id(a, b + 1)}, s);
  return s;
}

int MeshBuilder::addDisk(const std::string& name, const Vec3& centre, const Vec3& normal,
                         double radius, int sides) {
  int s = beginSurface(name);
  Vec3 n = normalize(normal);
  Vec3 u = normalize(std::fabs(n.x) < 0.9 ? cross(n, Vec3{1, 0, 0}) : cross(n, Vec3{0, 1, 0}));
  Vec3 v = cross(n, u);  // (u, v, n) right-handed: increasing angle runs counter-clockwise
  int c = int(m_mesh.vertices.size());
  m_mesh.vertices.push_back(centre);
  for (int k = 0; k < sides; ++k) {
    double phi = 2 * M_PI * k / sides;
    m_mesh.vertices.push_back(centre + (u * std::cos(phi) + v * std::sin(phi)) * radius);
  }
  for (int k = 0; k < sides; ++k) addPatch({c, c + 1 + k, c + 1 + (k + 1) % sides}, s);
  return s;
}

int MeshBuilder::addTriangles(const std::string& name, const std::vector<Vec3>& corners) {
  int s = beginSurface(name);
  for (std::size_t k = 0; k + 2 < corners.size(); k += 3) {
    int base = int(m_mesh.vertices.size());
    for (int q = 0; q < 3; ++q) m_mesh.vertices.push_back(corners[k + q]);
    addPatch({base, base + 1, base + 2}, s);
  }
  return s;
}

MeshBuilder cubeInterior(int n) {
  MeshBuilder b;
  b.addRectangle("bottom", {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, n, n);  // normal +z
  b.addRectangle("top", {0, 0, 1}, {0, 1, 0}, {1, 0, 0}, n, n);     // normal -z
  b.addRectangle("front", {0, 0, 0}, {0, 0, 1}, {1, 0, 0}, n, n);   // y=0, normal +y
  b.addRectangle("back", {0, 1, 0}, {1, 0, 0}, {0, 0, 1}, n, n);    // y=1, normal -y
  b.addRectangle("left", {0, 0, 0}, {0, 1, 0}, {0, 0, 1}, n, n);    // x=0, normal +x
  b.addRectangle("right", {1, 0, 0}, {0, 0, 1}, {0, 1, 0}, n, n);   // x=1, normal -x
  return b;
}

MeshBuilder parallelRectangles(double a, double b, double c, int n) {
  MeshBuilder m;
  m.addRectangle("lower", {0, 0, 0}, {a, 0, 0}, {0, b, 0}, n, n);  // normal +z
  m.addRectangle("upper", {0, 0, c}, {0, b, 0}, {a, 0, 0}, n, n);  // normal -z
  return m;
}

MeshBuilder perpendicularRectangles(double l, double w, double h, int n) {
  MeshBuilder m;
  m.addRectangle("A1", {0, 0, 0}, {l, 0, 0}, {0, w, 0}, n, n);  // normal +z
  m.addRectangle("A2", {0, 0, 0}, {0, 0, h}, {l, 0, 0}, n, n);  // normal +y
  return m;
}

void unitIcosphere(int level, std::vector<Vec3>& v, std::vector<std::array<int, 3>>& f) {
  const double t = (1 + std::sqrt(5.0)) / 2;
  v = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
       {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  for (Vec3& p : v) p = normalize(p);
  f = {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
       {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
       {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int l = 0; l < level; ++l) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      v.push_back(normalize(v[a] + v[b]));
      return mid[key] = int(v.size()) - 1;
    };
    std::vector<std::array<int, 3>> next;
    for (auto& tri : f) {
      int a = midpoint(tri[0], tri[1]), b = midpoint(tri[1], tri[2]), c = midpoint(tri[2], tri[0]);
      next.push_back({tri[0], a, c});
      next.push_back({tri[1], b, a});
      next.push_back({tri[2], c, b});
      next.push_back({a, b, c});
    }
    f.swap(next);
  }
}

MeshBuilder icosphereInterior(int level, double r) {
  std::vector<Vec3> v;
  std::vector<std::array<int, 3>> f;
  unitIcosphere(level, v, f);
  std::vector<Vec3> corners;  // reversed winding: outward-facing faces turned inward
  for (auto& tri : f)
    for (int k : {0, 2, 1}) corners.push_back(v[tri[k]] * r);
  MeshBuilder m;
  m.addTriangles("sphere", corners);
  return m;
}

double c11ParallelRectangles(double X, double Y) {
  double x2 = X * X, y2 = Y * Y;
  return 2 / (M_PI * X * Y) *
         (std::log(std::sqrt((1 + x2) * (1 + y2) / (1 + x2 + y2))) +
          X * std::sqrt(1 + y2) * std::atan(X / std::sqrt(1 + y2)) +
          Y * std::sqrt(1 + x2) * std::atan(Y / std::sqrt(1 + x2)) - X * std::atan(X) -
          Y * std::atan(Y));
}

double c14PerpendicularRectangles(double W, double H) {
  double w2 = W * W, h2 = H * H, s = std::sqrt(h2 + w2);
  double a = (1 + w2) * (1 + h2) / (1 + w2 + h2);
  double b = std::pow(w2 * (1 + w2 + h2) / ((1 + w2) * (w2 + h2)), w2);
  double c = std::pow(h2 * (1 + w2 + h2) / ((1 + h2) * (w2 + h2)), h2);
  return 1 / (M_PI * W) *
         (W * std::atan(1 / W) + H * std::atan(1 / H) - s * std::atan(1 / s) +
          0.25 * std::log(a * b * c));
}

double diskOnAxis(double R, double h) { return R * R / (R * R + h * h); }

double diskOffAxis(double r, double h, double l) {
  double H = h / l, R = r / l, Z = 1 + H * H + R * R;
  return 0.5 * (1 - (1 + H * H - R * R) / std::sqrt(Z * Z - 4 * R * R));
}

double coaxialDisks(double r1, double r2, double h) {
  double R1 = r1 / h, R2 = r2 / h, X = 1 + (1 + R2 * R2) / (R1 * R1);
  return 0.5 * (X - std::sqrt(X * X - 4 * (R2 / R1) * (R2 / R1)));
}

}  // namespace radkit::test
