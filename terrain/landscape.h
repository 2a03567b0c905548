// Landscape images of a heightfield under the atmosphere's sun and sky, two ways: real-time
// heightfield ray marching with soft shadows, and Embree on the exported triangles
// with shadow rays to the sun's disc as the reference. Both shade alike (Lambertian albedo by
// material, sun with transmittance, an isotropic sky term) and add aerial perspective from the
// same atmosphere, so their difference is the marcher's hits and shadows alone.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "atmosphere/atmosphere.h"
#include "geometry/patch_mesh.h"
#include "terrain/heightfield.h"

namespace radkit::terrain {

/// The heightfield as the piecewise-linear surface of its triangulation (triangulate()'s
/// diagonal), so marching and Embree see the same surface.
class TerrainSurface {
 public:
  TerrainSurface(const Heightfield& field, const TerrainSettings& settings);
  /// Height at (x, y) inside the field; the triangle there in `triangle` if given.
  double height(double x, double y, int* triangle = nullptr) const;
  bool inside(double x, double y) const;
  /// Steepest gradient of any triangle: the bound that makes marching steps safe.
  double maxGradient() const { return m_maxGradient; }
  const TerrainMesh& mesh() const { return m_mesh; }
  Vec3 normal(int triangle) const { return m_normals[triangle]; }
  double spacing() const { return m_field.spacing(); }
  double top() const { return m_top; }
  const Heightfield& field() const { return m_field; }

 private:
  Heightfield m_field;
  TerrainMesh m_mesh;
  std::vector<Vec3> m_normals;
  double m_maxGradient = 0, m_top = 0;
};

struct MarchHit {
  double t = 0;
  int triangle = -1;
};

/// \brief First hit of the ray o + t·d (unit d) with the surface: steps of the gap below the
/// ray over the fastest the gap can close (maxGradient), which cannot step over a peak, then
/// the exact intersection with the triangle below once the gap is small. `steps` counts them.
std::optional<MarchHit> marchTerrain(const TerrainSurface& surface, const Vec3& o, const Vec3& d,
                                     int maxSteps, int* steps = nullptr);

/// \brief The real-time soft shadow: march from x towards the sun and keep the
/// smallest angle α = gap/t by which the ray clears the terrain; the visible share of a disc
/// of angular radius δ is taken as clamp(½ + α/(2δ), 0, 1).
double softShadow(const TerrainSurface& surface, const Vec3& x, const Vec3& sun, double radius,
                  int maxSteps);

/// The triangles as a PatchMesh (one surface per material present, in material order).
PatchMesh terrainPatchMesh(const TerrainMesh& mesh);

struct LandscapeSettings {
  int width = 512, height = 288;
  double sunElevationDeg = 35, sunAzimuthDeg = 150;
  int maxSteps = 1024;     ///< marching steps per ray
  int sunSamples = 16;     ///< reference: shadow rays to the sun's disc per pixel
  int aerialSamples = 16;  ///< samples along each view ray for aerial perspective
  bool aerialPerspective = true;
  atmosphere::SkySettings sky;
  std::uint64_t seed = 1;
};

struct LandscapeImage {
  std::vector<Vec3> radiance;  ///< row-major, top row first
  std::vector<double> depth;   ///< hit distance, −1 for the sky
  double seconds = 0;
  long long rays = 0;   ///< primary and shadow rays (marched or cast)
  long long steps = 0;  ///< marching steps (the marcher only)
  /// Thread-seconds spent finding hits and shadows, apart from shading and the atmosphere
  /// (which both renderers share): what the two methods' costs differ by.
  double visibilitySeconds = 0;
};

/// Camera rays: the unit direction through pixel (x, y), (0, 0) the top-left corner.
using RayDirection = std::function<Vec3(double x, double y)>;

/// \brief Renders by ray marching (`reference` false) or with Embree (true). Parallel over
/// rows; deterministic for a given seed.
LandscapeImage renderLandscape(const TerrainSurface& surface, const atmosphere::Atmosphere& air,
                               const Vec3& eye, const RayDirection& camera,
                               const LandscapeSettings& settings, bool reference);

}  // namespace radkit::terrain
