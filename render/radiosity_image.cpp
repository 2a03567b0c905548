#include "render/radiosity_image.h"
#include "util/setting_names.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace radkit {

RadianceImage renderRadiosity(const PatchMesh& mesh, const Visibility& rays, const Camera& camera,
                              const std::vector<Vec3>& radiosity, const std::vector<bool>& twoSided,
                              const ImageSettings& s) {
  PinholeCamera cam(camera, s.width, s.height);
  RadianceImage img;
  img.width = s.width;
  img.height = s.height;
  img.radiance.assign(std::size_t(s.width) * s.height, Vec3{});
  img.patch.assign(std::size_t(s.width) * s.height, -1);
  std::optional<SmoothRadiosity> smooth;
  if (s.smooth) smooth.emplace(mesh, radiosity, s.smoothing);
  const int n = std::max(1, s.samplesPerAxis);

  // Radiance leaving the hit patch toward the camera: B/π on the front side (Lambertian).
  auto shade = [&](const Vec3& dir, const RayHit& hit) {
    const Patch& p = mesh.patches[hit.patch];
    if (dot(dir, p.normal) > 0 && !twoSided[p.surface]) return Vec3{};
    if (!s.smooth) return radiosity[hit.patch] / M_PI;
    return smooth->at(hit.patch, cam.origin() + dir * hit.distance) / M_PI;
  };

  tbb::parallel_for(0, s.height, [&](int y) {
    for (int x = 0; x < s.width; ++x) {
      Vec3 sum;
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          Vec3 dir = cam.direction(x + (i + 0.5) / n, y + (j + 0.5) / n);
          if (auto hit = rays.closestHit(cam.origin(), dir, 0.0))
            sum += shade(dir, *hit);
          else if (s.background)
            sum += s.background(dir);
        }
      img.radiance[std::size_t(y) * s.width + x] = sum / double(n * n);
      if (auto hit = rays.closestHit(cam.origin(), cam.direction(x + 0.5, y + 0.5), 0.0))
        img.patch[std::size_t(y) * s.width + x] = hit->patch;
    }
  });
  return img;
}

double autoExposure(const RadianceImage& image, const std::vector<bool>& pixelEmits) {
  std::vector<double> lum;
  for (std::size_t k = 0; k < image.radiance.size(); ++k)
    if (image.patch[k] >= 0 && !pixelEmits[k]) lum.push_back(luminance(image.radiance[k]));
  if (lum.empty()) return 1;
  std::size_t q = std::min(lum.size() - 1, std::size_t(0.95 * lum.size()));
  std::nth_element(lum.begin(), lum.begin() + q, lum.end());
  return lum[q] > 0 ? 0.8 / lum[q] : 1;
}

std::vector<bool> emitterPixels(const RadianceImage& image, const Scene& scene,
                                const PatchMesh& mesh) {
  std::vector<bool> emits(image.patch.size(), false);
  for (std::size_t k = 0; k < emits.size(); ++k)
    emits[k] =
        image.patch[k] >= 0 &&
        scene.materials[scene.surfaces[mesh.patches[image.patch[k]].surface].material].emits();
  return emits;
}

double autoExposure(const RadianceImage& image, const Scene& scene, const PatchMesh& mesh) {
  return autoExposure(image, emitterPixels(image, scene, mesh));
}

double srgbEncode(double v) {
  v = std::clamp(v, 0.0, 1.0);
  return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1 / 2.4) - 0.055;
}

Canvas toneMap(const RadianceImage& image, double exposure) {
  Canvas c(image.width, image.height, {0, 0, 0});
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      Vec3 v = image.radiance[std::size_t(y) * image.width + x] * exposure;
      auto byte = [](double t) { return std::uint8_t(std::lround(255 * srgbEncode(t))); };
      c.set(x, y, {byte(v.x), byte(v.y), byte(v.z)});
    }
  return c;
}

std::optional<int> pickPatch(const Visibility& rays, const Camera& camera, int width, int height,
                             int x, int y) {
  PinholeCamera cam(camera, width, height);
  if (auto hit = rays.closestHit(cam.origin(), cam.direction(x + 0.5, y + 0.5), 0.0))
    return hit->patch;
  return std::nullopt;
}

bool writeRadiosityPng(const std::string& path, const Scene& scene, const PatchMesh& mesh,
                       const Visibility& rays, const std::vector<Vec3>& radiosity,
                       const ImageSettings& settings) {
  const std::vector<bool> twoSided = scene.twoSidedSurfaces();
  Camera camera = sceneCamera(scene, mesh);
  RadianceImage img = renderRadiosity(mesh, rays, camera, radiosity, twoSided, settings);
  writePng(path, toneMap(img, autoExposure(img, scene, mesh)));
  return img.meanRadiance() > 0;
}

std::string blackPictureWarning(const std::string& file) {
  return file +
         " is black: the camera sees no lit surface (the backs of walls, or surfaces no light "
         "reaches). Fix: give the scene a \"camera\", or " +
         setting("camera") + " px,py,pz,lx,ly,lz";
}

}  // namespace radkit
