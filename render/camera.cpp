#include "render/camera.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include "util/errors.h"  // InputError

namespace radkit {

PinholeCamera::PinholeCamera(const Camera& c, int width, int height)
    : m_origin(c.position), m_width(width), m_height(height) {
  if (width <= 0 || height <= 0) throw std::invalid_argument("camera: image size must be positive");
  m_forward = normalize(c.lookAt - c.position);
  Vec3 right = cross(m_forward, c.up);
  if (length(right) == 0)
    throw std::invalid_argument("camera: 'up' is parallel to the view direction");
  // Right-handed: image right = forward × up. Looking along +z with +y up, +x is on the
  // viewer's left, as the Cornell box data says.
  m_right = normalize(right);
  m_up = cross(m_right, m_forward);
  m_tanHalfFov = std::tan(c.fovDeg * M_PI / 360.0);
  m_pixelScale = 2 * m_tanHalfFov / m_height;  // square pixels: the same step across and down
  m_halfWidth = m_tanHalfFov * m_width / m_height;
}

Vec3 PinholeCamera::direction(double x, double y) const {
  // sx = (2x/W − 1)·tan(fov/2)·W/H and sy = (1 − 2y/H)·tan(fov/2), with their factors
  // hoisted out: this runs once per camera sample.
  const double sx = x * m_pixelScale - m_halfWidth, sy = m_tanHalfFov - y * m_pixelScale;
  const Vec3 d = m_forward + m_right * sx + m_up * sy;
  return d * (1 / std::sqrt(dot(d, d)));
}

bool PinholeCamera::project(const Vec3& point, double& x, double& y) const {
  Vec3 d = point - m_origin;
  double depth = dot(d, m_forward);
  if (depth <= 0) return false;
  double aspect = double(m_width) / m_height;
  double sx = dot(d, m_right) / depth, sy = dot(d, m_up) / depth;
  x = (sx / (m_tanHalfFov * aspect) + 1) * m_width / 2;
  y = (1 - sy / m_tanHalfFov) * m_height / 2;
  return true;
}

Camera PinholeCamera::framing(const Bounds3& b, const Vec3& side) {
  Camera c;
  Vec3 centre = (b.lo + b.hi) * 0.5;
  double radius = 0.5 * b.diagonal();
  c.lookAt = centre;
  c.fovDeg = 40;
  c.position = centre + side * (radius / std::tan(20 * M_PI / 180) * 1.1);
  // Seen from above or below, +y is the view direction: -z (or +z) is up instead.
  c.up = std::fabs(side.y) > 0.5 ? Vec3{0, 0, -side.y} : Vec3{0, 1, 0};
  return c;
}

namespace {

/// Cells of the depth buffer that scores each side: enough to tell an open box from a
/// closed one, cheap for 10⁵ triangles.
constexpr int kGrid = 64;

/// Cells where the nearest surface, seen orthographically from `side`, shows its front.
long long frontCells(const std::vector<Triangle>& triangles, const std::vector<char>* emitting,
                     const Bounds3& b, int axis, double sign) {
  const int ua = (axis + 1) % 3, va = (axis + 2) % 3;
  const double u0 = b.lo[ua], v0 = b.lo[va];
  const double du = std::max(b.hi[ua] - u0, 1e-300) / kGrid,
               dv = std::max(b.hi[va] - v0, 1e-300) / kGrid;
  std::vector<double> depth(std::size_t(kGrid) * kGrid, -INFINITY);
  std::vector<char> front(std::size_t(kGrid) * kGrid, 0);
  for (std::size_t n = 0; n < triangles.size(); ++n) {
    const Triangle& t = triangles[n];
    // A lamp occludes but does not count: a view into the lamp shows nothing lit.
    const bool counts = !emitting || !(*emitting)[n];
    const double facing = cross(t[1] - t[0], t[2] - t[0])[axis] * sign;
    if (facing == 0) continue;  // edge-on: covers no cell
    double pu[3], pv[3], pd[3];
    for (int k = 0; k < 3; ++k)
      pu[k] = (t[k][ua] - u0) / du, pv[k] = (t[k][va] - v0) / dv, pd[k] = t[k][axis] * sign;
    const double area = (pu[1] - pu[0]) * (pv[2] - pv[0]) - (pu[2] - pu[0]) * (pv[1] - pv[0]);
    if (area == 0) continue;
    const int i0 = std::max(0, int(std::floor(std::min({pu[0], pu[1], pu[2]}) - 0.5)));
    const int i1 = std::min(kGrid - 1, int(std::ceil(std::max({pu[0], pu[1], pu[2]}) - 0.5)));
    const int j0 = std::max(0, int(std::floor(std::min({pv[0], pv[1], pv[2]}) - 0.5)));
    const int j1 = std::min(kGrid - 1, int(std::ceil(std::max({pv[0], pv[1], pv[2]}) - 0.5)));
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const double x = i + 0.5, y = j + 0.5;
        // Barycentric weights of the cell centre.
        const double w1 = ((x - pu[0]) * (pv[2] - pv[0]) - (pu[2] - pu[0]) * (y - pv[0])) / area;
        const double w2 = ((pu[1] - pu[0]) * (y - pv[0]) - (x - pu[0]) * (pv[1] - pv[0])) / area;
        const double w0 = 1 - w1 - w2;
        if (w0 < 0 || w1 < 0 || w2 < 0) continue;
        const double d = w0 * pd[0] + w1 * pd[1] + w2 * pd[2];
        const int cell = j * kGrid + i;
        if (d > depth[cell]) depth[cell] = d, front[cell] = facing > 0 && counts;
      }
  }
  return std::count(front.begin(), front.end(), char(1));
}

void addPolygon(std::vector<Triangle>& out, const std::vector<Vec3>& points, const int* index,
                int count, std::vector<char>* emitting = nullptr, bool emits = false) {
  for (int k = 1; k + 1 < count; ++k) {
    out.push_back({points[index[0]], points[index[k]], points[index[k + 1]]});
    if (emitting) emitting->push_back(emits ? 1 : 0);
  }
}

/// A camera inside a closed scene (no side of its bounding box sees a front face from
/// outside): just inside one end of its longer horizontal axis (radkit's up is +y), looking
/// along that axis at the far end, wide enough to show the far wall whole.
Camera insideCamera(const Bounds3& b) {
  const Vec3 size = b.hi - b.lo, centre = (b.lo + b.hi) * 0.5;
  const int axis = size.x > size.z ? 0 : 2;
  Camera c;
  c.position = centre;
  c.position[axis] = b.lo[axis] + 0.02 * size[axis];
  c.lookAt = centre;
  c.lookAt[axis] = b.hi[axis];
  c.up = {0, 1, 0};
  const double distance = 0.98 * size[axis];
  const double across = std::max(size.y, size[2 - axis] * 3.0 / 4.0);  // 4:3 frames
  c.fovDeg = std::clamp(2 * std::atan(0.55 * across / std::max(distance, 1e-300)) * 180 / M_PI,
                        40.0, 100.0);
  return c;
}

}  // namespace

Camera automaticCamera(const std::vector<Triangle>& triangles, const std::vector<char>* emitting) {
  Bounds3 b;
  for (const Triangle& t : triangles)
    for (const Vec3& p : t) b.extend(p);
  if (b.empty()) return PinholeCamera::framing(Bounds3{{-1, -1, -1}, {1, 1, 1}});
  // −z first: the old default, kept on ties.
  const int axes[6] = {2, 2, 0, 0, 1, 1};
  const double signs[6] = {-1, 1, -1, 1, 1, -1};
  int best = 0;
  long long bestCells = -1;
  for (int k = 0; k < 6; ++k) {
    const long long cells = frontCells(triangles, emitting, b, axes[k], signs[k]);
    if (cells > bestCells) best = k, bestCells = cells;
  }
  // No side sees a lit front from outside: a closed room, or a box whose only front faces
  // are lamps. The view from outside would be black.
  if (bestCells == 0) return insideCamera(b);
  Vec3 side{0, 0, 0};
  side[axes[best]] = signs[best];
  return PinholeCamera::framing(b, side);
}

Camera automaticCamera(const Scene& scene) {
  std::vector<Triangle> triangles;
  std::vector<char> emitting;
  for (const Surface& s : scene.surfaces)
    for (const Face& f : s.faces)
      addPolygon(triangles, s.vertices, f.vertices.data(), int(f.vertices.size()), &emitting,
                 s.material >= 0 && scene.materials[s.material].emits());
  return automaticCamera(triangles, &emitting);
}

Camera automaticCamera(const PatchMesh& mesh) {
  std::vector<Triangle> triangles;
  for (const Patch& p : mesh.patches)
    addPolygon(triangles, mesh.vertices, p.vertex.data(), p.vertexCount);
  return automaticCamera(triangles);
}

/// The patches' camera with the scene's lamps known.
Camera automaticCamera(const Scene& scene, const PatchMesh& mesh) {
  std::vector<Triangle> triangles;
  std::vector<char> emitting;
  for (const Patch& p : mesh.patches) {
    const bool emits = p.surface >= 0 && std::size_t(p.surface) < scene.surfaces.size() &&
                       scene.surfaces[p.surface].material >= 0 &&
                       scene.materials[scene.surfaces[p.surface].material].emits();
    addPolygon(triangles, mesh.vertices, p.vertex.data(), p.vertexCount, &emitting, emits);
  }
  return automaticCamera(triangles, &emitting);
}

Camera sceneCamera(const Scene& scene, const PatchMesh& mesh) {
  return scene.camera ? *scene.camera : automaticCamera(scene, mesh);
}

Camera chooseCamera(const Scene& scene, const std::string& given, const std::string& option) {
  if (!given.empty()) return parseCamera(option, given);
  return scene.camera ? *scene.camera : automaticCamera(scene);
}

Camera parseCamera(const std::string& option, const std::string& text) {
  const std::string fix =
      ". Fix: give px,py,pz,lx,ly,lz[,ux,uy,uz[,fov]] (position, look-at, up, vertical field "
      "of view in degrees), e.g. 0,1,4,0,1,0";
  std::vector<double> v;
  std::size_t at = 0;
  while (at <= text.size()) {
    const std::size_t comma = std::min(text.find(',', at), text.size());
    const std::string item = text.substr(at, comma - at);
    char* end = nullptr;
    const double x = std::strtod(item.c_str(), &end);
    if (item.empty() || end != item.c_str() + item.size() || !std::isfinite(x))
      throw InputError(option + " '" + text + "': '" + item + "' is not a finite number" + fix);
    v.push_back(x);
    at = comma + 1;
  }
  if (v.size() != 6 && v.size() != 9 && v.size() != 10)
    throw InputError(option + " '" + text + "' has " + std::to_string(v.size()) +
                     " numbers, not 6, 9 or 10" + fix);
  Camera c;
  c.position = {v[0], v[1], v[2]};
  c.lookAt = {v[3], v[4], v[5]};
  c.up = v.size() >= 9 ? Vec3{v[6], v[7], v[8]} : Vec3{0, 1, 0};
  c.fovDeg = v.size() == 10 ? v[9] : 40;
  if (length(c.lookAt - c.position) == 0)
    throw InputError(option + " '" + text + "': the look-at is the position" + fix);
  if (length(cross(c.lookAt - c.position, c.up)) == 0)
    throw InputError(option + " '" + text +
                     "': up is parallel to the view direction. Fix: give another up, e.g. 0,0,1");
  if (!(c.fovDeg > 0 && c.fovDeg < 180))
    throw InputError(option + " '" + text + "': the field of view must lie in (0, 180) degrees" +
                     fix);
  return c;
}

}  // namespace radkit
