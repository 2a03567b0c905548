// PinholeCamera: primary rays for a Camera (position, look-at, up, vertical field of view).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "geometry/patch_mesh.h"
#include "geometry/scene.h"
#include "util/errors.h"
#include "util/setting_names.h"
#include "util/vec3.h"

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

  /// A camera that frames the whole box from the side `side` points to (a unit axis, by
  /// default −z), looking back along it with a 40° field of view.
  static Camera framing(const Bounds3& bounds, const Vec3& side = {0, 0, -1});

 private:
  Vec3 m_origin, m_forward, m_right, m_up;
  double m_tanHalfFov;
  double m_pixelScale = 0, m_halfWidth = 0;  ///< image-plane step per pixel, half the plane's width
  int m_width, m_height;
};

using Triangle = std::array<Vec3, 3>;

/// \brief The camera for a scene that gives none, one function for every image and the
/// viewer: it looks along the axis (±x, ±y, ±z) from which the most front faces are seen
/// unoccluded (an orthographic 64×64 depth buffer per side), and frames the bounding box.
/// An open box is seen through its open side, a closed model from its most front-facing
/// side; ties keep the −z side. Lamps (`emitting`, one flag per triangle) occlude but do not
/// count, so a model under a lamp is not seen from below, into the lamp. When no side sees a
/// front face (a closed room seen from outside) the camera goes inside: just within one end
/// of the longer horizontal axis (+y is up), looking at the far end, its field of view wide
/// enough for the far wall (40–100°). Deterministic.
Camera automaticCamera(const std::vector<Triangle>& triangles,
                       const std::vector<char>* emitting = nullptr);
Camera automaticCamera(const Scene& scene);
Camera automaticCamera(const PatchMesh& mesh);
Camera automaticCamera(const Scene& scene, const PatchMesh& mesh);

/// The scene's camera, or automaticCamera(mesh) when it has none.
Camera sceneCamera(const Scene& scene, const PatchMesh& mesh);

/// \brief The camera an image of the scene is taken with: `given` (parseCamera's text) when not
/// empty, else the scene's, else automaticCamera(scene). `option` names `given` in errors.
Camera chooseCamera(const Scene& scene, const std::string& given = "",
                    const std::string& option = setting("camera"));

/// \brief Parses a --camera value "px,py,pz,lx,ly,lz[,ux,uy,uz[,fov]]" (position, look-at,
/// up, vertical field of view in degrees; up +y and 40° when left out).
/// \throws InputError naming `option` and the fix.
Camera parseCamera(const std::string& option, const std::string& text);

}  // namespace radkit
