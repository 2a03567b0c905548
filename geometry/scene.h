// Scene: what a scene file describes (materials, named surfaces, camera), before meshing.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "geometry/vec3.h"

namespace radkit {

/// How a surface scatters light. Radiosity sees only the diffuse part (diffuseAlbedo());
/// the image modes in render/ see the whole model.
enum class BrdfModel {
  Lambert,       ///< diffuse albedo `reflectance`
  Phong,         ///< energy-normalised Phong: kd = reflectance, ks = specular, shininess
  CookTorrance,  ///< GGX microfacets: baseColor = reflectance, metallic, roughness, F0 or ior
  Mirror,        ///< perfect specular reflection, colour = specular
  Glass,         ///< smooth dielectric (Fresnel reflection and refraction), index ior
};

/// A material. reflectance is the diffuse albedo (or base colour) per RGB channel in [0, 1),
/// emission the emitted radiosity (exitance) in W/m² per channel, >= 0.
struct Material {
  std::string name;
  Vec3 reflectance{0.5, 0.5, 0.5};
  Vec3 emission{0, 0, 0};
  bool twoSided = false;

  BrdfModel brdf = BrdfModel::Lambert;
  Vec3 specular{0, 0, 0};  ///< Phong ks; mirror colour (default 1 for mirrors)
  double shininess = 0;    ///< Phong exponent
  double metallic = 0;     ///< Cook-Torrance, in [0, 1]
  double roughness = 0.5;  ///< Cook-Torrance perceptual roughness in (0, 1]; alpha = roughness²
  Vec3 f0{0.04, 0.04, 0.04};  ///< Cook-Torrance normal-incidence Fresnel of the dielectric part
  double ior = 1.5;        ///< glass, or Cook-Torrance when given instead of f0

  bool emits() const { return emission.x > 0 || emission.y > 0 || emission.z > 0; }
  /// The albedo of the Lambertian part, which is what the radiosity system uses: the
  /// reflectance for Lambert and Phong, (1 − metallic)·base for Cook-Torrance (its specular
  /// lobe is left to the image modes), zero for mirrors and glass.
  Vec3 diffuseAlbedo() const;
  bool isSpecular() const { return brdf == BrdfModel::Mirror || brdf == BrdfModel::Glass; }
};

/// "lambert", "phong", "cook-torrance", "mirror", "glass".
const char* brdfName(BrdfModel model);

/// One face of a surface: indices into Surface::vertices, counter-clockwise seen from the
/// front side (normal by the right-hand rule). Three or four vertices after loading.
struct Face {
  std::vector<int> vertices;
};

/// A named surface: a polygon or a mesh with one material. Faces that share an edge share
/// its vertex indices, so subdivision can keep the surface free of T-junctions.
struct Surface {
  std::string name;
  int material = -1;  ///< index into Scene::materials
  std::vector<Vec3> vertices;
  std::vector<Face> faces;
  std::string source;  ///< where it came from, for messages: "scene.json: surfaces[3]"
};

/// Pinhole camera; fovDeg is the full vertical field of view.
struct Camera {
  Vec3 position{0, 0, 1};
  Vec3 lookAt{0, 0, 0};
  Vec3 up{0, 1, 0};
  double fovDeg = 39.3077;
};

struct Scene {
  std::string name;
  std::string units = "m";  ///< length unit of every coordinate; areas are in units²
  std::string file;         ///< path the scene was loaded from
  std::vector<Material> materials;
  std::vector<Surface> surfaces;
  std::optional<Camera> camera;

  Bounds3 bounds() const;
  /// Metres per scene unit ("mm" -> 1e-3), for converting areas and emission to SI.
  double metresPerUnit() const;
  int findMaterial(const std::string& materialName) const;  ///< -1 when absent
};

}  // namespace radkit
