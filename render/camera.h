// PinholeCamera: primary rays for a Camera (position, look-at, up, vertical field of view).
#pragma once

#include "geometry/scene.h"
#include "geometry/vec3.h"

namespace radkit {

class PinholeCamera {
 public:
  /// \param width, height image size in pixels (> 0); the field of view is vertical.
  PinholeCamera(const Camera& camera, int width, int height);

  /// Unit direction through image point (x, y) in pixels, (0, 0) the top-left corner.
  Vec3 direction(double x, double y) const;
  /// Inverse of direction(): the image point (x, y) where `point` appears; false when the
  /// point is behind the camera.
  bool project(const Vec3& point, double& x, double& y) const;
  const Vec3& origin() const { return m_origin; }
  int width() const { return m_width; }
  int height() const { return m_height; }

  /// A camera that frames the whole scene from the -z side (for scenes with no camera).
  static Camera framing(const Bounds3& bounds);

 private:
  Vec3 m_origin, m_forward, m_right, m_up;
  double m_tanHalfFov;
  int m_width, m_height;
};

}  // namespace radkit
