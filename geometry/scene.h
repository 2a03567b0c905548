// Scene: what a scene file describes (materials, named surfaces, camera), before meshing.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "geometry/face_indices.h"
#include "util/params.h"
#include "util/vec3.h"

namespace radkit {

/// A material: a BSDF by registry name (bsdf/registry.cpp) with the parameters the scene gave
/// it, emission in W/m² per channel (>= 0) and sidedness. What radiosity needs from the BSDF
/// is cached by resolveMaterial() when the scene is loaded.
struct Material {
  std::string name;
  Vec3 emission{0, 0, 0};
  bool twoSided = false;
  std::string bsdf = "lambert";
  Params params;  ///< the BSDF's own keys, as given

  // Set by resolveMaterial() from the BSDF:
  Vec3 albedo{0.5, 0.5, 0.5};  ///< diffuse albedo ρ_d, what the radiosity system uses
  bool delta = false;          ///< every lobe a Dirac delta (mirror, glass)
  std::string description;     ///< the BSDF's one-line description

  bool emits() const { return emission.x > 0 || emission.y > 0 || emission.z > 0; }
  /// The albedo of the Lambertian part, which is what the radiosity system uses (Lambert's
  /// reflectance, Phong's kd, (1 − metallic)·base for Cook-Torrance, zero for mirrors and glass).
  Vec3 diffuseAlbedo() const { return albedo; }
  bool isSpecular() const { return delta; }
};

/// \brief Checks material.params with its BSDF (unknown keys, ranges) and caches albedo, delta
///        and description. \throws ParamError with the BSDF's message (no file or name).
void resolveMaterial(Material& material);

/// \brief A checked material of BSDF `bsdf` (tests, generated scenes); params as "key=v, ...".
Material makeMaterial(const std::string& name, const std::string& bsdf, const std::string& params,
                      const Vec3& emission = {0, 0, 0});

/// One face of a surface: indices into Surface::vertices, counter-clockwise seen from the
/// front side (normal by the right-hand rule). Three or four vertices after loading, held
/// inline (face_indices.h: 24 bytes a face, no allocation).
struct Face {
  FaceIndices vertices;
};

/// A named surface: a polygon or a mesh with one material. Faces that share an edge share
/// its vertex indices, so subdivision can keep the surface free of T-junctions.
struct Surface {
  std::string name;
  int material = -1;  ///< index into Scene::materials
  std::vector<Vec3> vertices;
  std::vector<Face> faces;
  std::string source;  ///< where it came from, for messages: "scene.json: surfaces[3]"
  /// Set by addBackSides on both sides of a two-sided surface: rays ignore the back of its
  /// faces, so each of the two coincident copies is hit from its own side only.
  bool cullBack = false;
};

/// Pinhole camera; fovDeg is the full vertical field of view.
struct Camera {
  Vec3 position{0, 0, 1};
  Vec3 lookAt{0, 0, 0};
  Vec3 up{0, 1, 0};
  double fovDeg = 39.3077;
};

/// Daylight: a sky, and optionally the sun, lighting the scene from outside it (the "sky" key,
/// docs/daylight.md). Plain data; daylight/ turns it into radiance and patch irradiance.
struct SkyDescription {
  std::string model = "uniform";  ///< a sky model of sky/registry.cpp ("type" in the file)
  /// The model's own keys, as given (checked when loaded); by default a black uniform sky.
  Params parameters = Params({{"radiance", 0.0}});
  bool sun = false;
  double sunElevationDeg = 45, sunAzimuthDeg = 180;  ///< azimuth clockwise from north
  /// The sun's normal irradiance (W/m² per channel), for a model that does not compute it
  /// (SkyRadiance::computesSun).
  Vec3 sunIrradiance{0, 0, 0};
  double sunAngularRadiusDeg = 0.2665;
  Vec3 up{0, 0, 1};              ///< the zenith in scene coordinates
  Vec3 north{0, 1, 0};           ///< azimuth 0 (made perpendicular to up)
  double groundReflectance = 0;  ///< below the horizon: radiance ρ_g E_h / π (0: black)
  int samples = 256;             ///< sky rays per patch
  int sunSamples = 16;           ///< shadow rays to the sun's disc per patch
};

struct Scene {
  std::string name;
  std::string units = "m";  ///< length unit of every coordinate; areas are in units²
  std::string file;         ///< path the scene was loaded from
  std::vector<Material> materials;
  std::vector<Surface> surfaces;
  std::optional<Camera> camera;
  std::optional<SkyDescription> sky;

  Bounds3 bounds() const;
  /// Metres per scene unit ("mm" -> 1e-3), for converting areas and emission to SI.
  double metresPerUnit() const;
  int findMaterial(const std::string& materialName) const;  ///< -1 when absent
  /// Per surface: whether its material reflects on both sides (what image modes need).
  std::vector<bool> twoSidedSurfaces() const;
};

/// \brief Radiosity's view of two-sided materials: every surface whose material is two-sided
/// gets a copy "NAME (back)" with its faces reversed, so both sides exchange light as surfaces
/// of their own (own patches, own radiosity), and both are marked cullBack. Only for the
/// radiosity methods; the image modes and photon mapping read two_sided from the material.
/// Returns the number of surfaces added.
int addBackSides(Scene& scene);

}  // namespace radkit
