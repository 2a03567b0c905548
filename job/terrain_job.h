// `radkit terrain` as one library call: a procedural landscape (ridged multifractal or fBm
// heightfield) written as meshes by material (grass, rock, snow by slope and height) and a
// scene file that puts them under a sky, ready for a run (docs/terrain.md); optionally the
// landscape rendered by ray marching and by Embree and compared.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

#include "terrain/heightfield.h"
#include "terrain/landscape.h"

namespace radkit {

struct TerrainJobSettings {
  terrain::TerrainSettings settings;  ///< its `type` is set from `type`
  std::string type = "ridged";        ///< "ridged" (multifractal) or "fbm"
  std::string format = "obj";         ///< mesh files: "obj" or "ply"
  /// The scene's sky: a model of sky/registry.cpp, with parameters as "name:key=value;..."
  /// (the model's registry example when none are given).
  std::string sky = "physical";
  double sunElevation = 35, sunAzimuth = 150;  ///< degrees; azimuth clockwise from north
  int skySamples = 128, sunSamples = 16;       ///< the scene's sky and sun rays per patch
  bool image = false;                          ///< render the landscape both ways and compare
  terrain::LandscapeSettings landscape;
  double exposure = 0;  ///< 0: automatic
  std::string out = "out/terrain";
};

struct TerrainJobResult {
  std::string out;
  nlohmann::json report;  ///< report.json as written
};

/// \brief Writes the meshes, terrain.json, heightmap.png (and the landscape images) and
/// report.json into `out`, all or nothing. \throws std::invalid_argument for an unknown type,
/// format or sky.
TerrainJobResult runTerrainJob(const TerrainJobSettings& settings);

}  // namespace radkit
