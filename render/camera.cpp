#include "render/camera.h"

#include <cmath>
#include <stdexcept>

namespace radkit {

PinholeCamera::PinholeCamera(const Camera& c, int width, int height)
    : m_origin(c.position), m_width(width), m_height(height) {
  if (width <= 0 || height <= 0) throw std::invalid_argument("camera: image size must be positive");
  m_forward = normalize(c.lookAt - c.position);
  Vec3 right = cross(m_forward, c.up);
  if (length(right) == 0) throw std::invalid_argument("camera: 'up' is parallel to the view direction");
  // Right-handed: image right = forward × up. Looking along +z with +y up, +x is on the
  // viewer's left, as the Cornell box data says.
  m_right = normalize(right);
  m_up = cross(m_right, m_forward);
  m_tanHalfFov = std::tan(c.fovDeg * M_PI / 360.0);
}

Vec3 PinholeCamera::direction(double x, double y) const {
  double aspect = double(m_width) / m_height;
  double sx = (2 * x / m_width - 1) * m_tanHalfFov * aspect;
  double sy = (1 - 2 * y / m_height) * m_tanHalfFov;
  return normalize(m_forward + m_right * sx + m_up * sy);
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

Camera PinholeCamera::framing(const Bounds3& b) {
  Camera c;
  Vec3 centre = (b.lo + b.hi) * 0.5;
  double radius = 0.5 * b.diagonal();
  c.lookAt = centre;
  c.fovDeg = 40;
  c.position = centre - Vec3{0, 0, radius / std::tan(20 * M_PI / 180) * 1.1};
  c.up = {0, 1, 0};
  return c;
}

}  // namespace radkit
