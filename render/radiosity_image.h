// Camera images of a radiosity solution: primary rays through Embree, flat or smooth
// (vertex-interpolated) shading, exposure and sRGB. Also picking: the patch under a pixel.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "geometry/patch_mesh.h"
#include "geometry/scene.h"
#include "geometry/visibility.h"
#include "render/camera.h"
#include "render/smooth_radiosity.h"
#include "util/canvas.h"

namespace radkit {

struct ImageSettings {
  int width = 512;
  int height = 512;
  int samplesPerAxis = 2;    ///< stratified samples per pixel: samplesPerAxis² (deterministic)
  bool smooth = false;       ///< interpolate radiosity between patches (SmoothRadiosity)
  SmoothSettings smoothing;  ///< crease angle and jump test of the smooth reconstruction
  double exposure = 0;       ///< multiplier on radiance; 0 picks one automatically
  /// Radiance of a ray that leaves the scene along a unit direction (a scene's sky); black
  /// when empty.
  std::function<Vec3(const Vec3& direction)> background;
};

/// Linear radiance image (W/m²/sr per channel) and the patch seen at each pixel centre.
struct RadianceImage {
  int width = 0, height = 0;
  std::vector<Vec3> radiance;  ///< row-major, top row first
  std::vector<int> patch;      ///< -1 where the ray escapes
  double exposure = 1;         ///< the exposure used when this image is tone mapped

  /// Mean over pixels and channels: a whole-image brightness (0 for an empty image).
  double meanRadiance() const {
    double sum = 0;
    for (const Vec3& v : radiance) sum += v.x + v.y + v.z;
    return radiance.empty() ? 0.0 : sum / (3.0 * double(radiance.size()));
  }
};

/// \brief Renders L = B/π of each patch (Lambertian), front sides only (back sides black
/// unless `twoSided[p.surface]`). Parallel over rows; deterministic.
RadianceImage renderRadiosity(const PatchMesh& mesh, const Visibility& rays, const Camera& camera,
                              const std::vector<Vec3>& radiosity, const std::vector<bool>& twoSided,
                              const ImageSettings& settings);

/// \brief render.png of a run: the scene's camera (or one framing the mesh), each surface's
/// two-sidedness from its material, automatic exposure and sRGB, written as PNG.
/// Returns whether any pixel is lit: a black picture (a camera that sees only the backs of
/// walls or unlit surfaces) is for the caller to warn about.
bool writeRadiosityPng(const std::string& path, const Scene& scene, const PatchMesh& mesh,
                       const Visibility& rays, const std::vector<Vec3>& radiosity,
                       const ImageSettings& settings);

/// The warning for a render that came out black, naming the file and the fix.
std::string blackPictureWarning(const std::string& file);

/// Automatic exposure: maps the 95th percentile of non-emitting pixel luminance to 0.8.
double autoExposure(const RadianceImage& image, const std::vector<bool>& pixelEmits);
/// The same, with the emitting pixels found from the patches the image sees.
double autoExposure(const RadianceImage& image, const Scene& scene, const PatchMesh& mesh);

/// Which pixels show an emitting patch (left out of automatic exposure).
std::vector<bool> emitterPixels(const RadianceImage& image, const Scene& scene,
                                const PatchMesh& mesh);

/// Exposure, clamp and the sRGB transfer curve (IEC 61966-2-1).
Canvas toneMap(const RadianceImage& image, double exposure);
double srgbEncode(double linear);

/// \brief The patch seen through pixel (x, y) (pixel centre), or nothing.
std::optional<int> pickPatch(const Visibility& rays, const Camera& camera, int width, int height,
                             int x, int y);

}  // namespace radkit
