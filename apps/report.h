// report.json pieces: each output of a run described as JSON, plus console summaries.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

#include "daylight/daylight.h"
#include "radiosity/radiosity_pipeline.h"

namespace radkit {
class OutputFolder;
}

namespace radkit::app {

/// [x, y, z] (an RGB triple, a point, a direction).
nlohmann::json vec3Json(const Vec3& v);
/// A value that may not apply (NaN by convention, e.g. a prediction never made) as null;
/// writeJson refuses any other number that is not finite.
nlohmann::json numberOrNull(double v);
nlohmann::json sceneJson(const Scene& scene);
nlohmann::json meshJson(const Scene& scene, const PatchMesh& mesh);
nlohmann::json solveJson(const SolveResult& result);
nlohmann::json energyJson(const EnergyBalance& e);
/// report.json's "daylight": the sky, the sun and the cost of the patches' daylight.
nlohmann::json daylightJson(const SkyModel& sky, const Daylight& daylight);
/// \brief Writes sky.pfm (render/sky_panorama.h) into `folder` and returns report.json's
/// "sky_panorama": the file, its size and the frame (up, north, east in scene coordinates)
/// that places it, which the viewer reads to draw the sky.
nlohmann::json writeSkyPanorama(OutputFolder& folder, const SkyModel& sky);
nlohmann::json surfacesJson(const std::vector<SurfaceResult>& surfaces);
/// Prints the energy balance ("escaped" followed by `escapedNote`) and one line of radiosity
/// per surface (with cd/m² and lux when photometric).
void printEnergyAndSurfaces(const EnergyBalance& e, const std::vector<SurfaceResult>& surfaces,
                            bool photometric, const std::string& escapedNote = "");
/// Peak resident memory of this process in bytes (getrusage).
std::size_t peakMemoryBytes();

/// Pretty-printed JSON, written atomically.
void writeJson(const std::string& path, const nlohmann::json& j);

/// Writes convergence.csv (output/run_files.h) and convergence.png (residual against work and
/// against seconds).
void writeConvergence(const std::string& csvPath, const std::string& pngPath,
                      const std::vector<SolveResult>& solves, double metresPerUnit);

/// Shows a stage's progress: a redrawn bar when stderr is a terminal, else a line per 10 %.
class Progress {
 public:
  void operator()(const std::string& stage, double fraction);
  void finish();

 private:
  std::string m_stage;
  int m_lastTenth = -1;
  bool m_open = false;
};

}  // namespace radkit::app
