// Procedural terrain: a heightfield from ridged multifractal or fBm noise, triangulated into
// a mesh whose faces get a material by slope and height (grass, rock, snow), written as OBJ or
// PLY meshes with a scene file that puts them under a sky (`radkit terrain`, docs/terrain.md).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "noise/noise2d.h"
#include "util/vec3.h"

namespace radkit::terrain {

enum class NoiseType { Ridged, Fbm };

struct TerrainSettings {
  NoiseType type = NoiseType::Ridged;
  FractalSettings fractal;
  int resolution = 257;       ///< vertices along each side
  double size = 4000;         ///< metres along each side (x east, y north, z up)
  double height = 800;        ///< metres between the lowest and highest vertex
  double featureSize = 3000;  ///< metres: the wavelength of the first octave
  double snowLine = 0.7;      ///< fraction of the height above which flat enough faces are snow
  double rockSlopeDeg = 35;   ///< faces steeper than this are rock
  double snowSlopeDeg = 50;   ///< snow holds on faces up to this slope
};

/// Heights z[j·n + i] at x = size·(i/(n−1) − ½), y = size·(j/(n−1) − ½), scaled to
/// [0, height]. Deterministic per settings (seed included); parallel over rows.
struct Heightfield {
  int n = 0;
  double size = 0;
  std::vector<double> z;

  double spacing() const { return size / (n - 1); }
  Vec3 vertex(int i, int j) const {
    return {size * (double(i) / (n - 1) - 0.5), size * (double(j) / (n - 1) - 0.5), z[j * n + i]};
  }
};

Heightfield makeHeightfield(const TerrainSettings& settings);

enum class TerrainMaterial { Grass = 0, Rock = 1, Snow = 2 };
constexpr const char* kTerrainMaterialNames[3] = {"grass", "rock", "snow"};
/// Their reflectances (broadband, as RGB): grass and rock near the visible averages of the
/// ECOSTRESS spectral library's vegetation and granite, fresh snow 0.85 (Warren 1982).
constexpr Vec3 kTerrainReflectance[3] = {
    {0.10, 0.16, 0.06}, {0.30, 0.28, 0.25}, {0.85, 0.85, 0.87}};

/// Two triangles per grid cell (split along the diagonal that is closer to the surface's
/// curvature is not attempted: always (i, j)–(i+1, j+1)), counter-clockwise from above.
struct TerrainMesh {
  std::vector<Vec3> vertices;
  std::vector<std::array<int, 3>> triangles;
  std::vector<TerrainMaterial> material;  ///< per triangle
};

TerrainMesh triangulate(const Heightfield& field, const TerrainSettings& settings);

/// \brief The triangles of one material as a mesh file: `.obj` or `.ply` (ASCII), vertices
/// renumbered to those used, written atomically. Returns the number of triangles written.
std::size_t writeTerrainPart(const std::string& path, const TerrainMesh& mesh,
                             TerrainMaterial material);

}  // namespace radkit::terrain
