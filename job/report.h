// report.json's pieces: each part of a run described as JSON, and the writers a run folder's
// report and convergence chart share. Every command that writes a report.json builds it here.
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "daylight/daylight.h"
#include "geometry/scene_loader.h"
#include "radiosity/radiosity_pipeline.h"

namespace radkit {

class OutputFolder;

/// [x, y, z] (an RGB triple, a point, a direction).
nlohmann::json vec3Json(const Vec3& v);
/// A value that may not apply (NaN by convention, e.g. a prediction never made) as null;
/// writeJson refuses any other number that is not finite.
nlohmann::json numberOrNull(double v);
nlohmann::json sceneJson(const Scene& scene);
nlohmann::json meshJson(const Scene& scene, const PatchMesh& mesh);
nlohmann::json solveJson(const SolveResult& result);
nlohmann::json energyJson(const EnergyBalance& e);
/// report.json's "load": the loading warnings and what the mesh repair changed.
nlohmann::json loadJson(const LoadReport& report);
/// report.json's "daylight": the sky, the sun and the cost of the patches' daylight.
nlohmann::json daylightJson(const SkyModel& sky, const Daylight& daylight);
/// \brief Writes sky.pfm (render/sky_panorama.h) into `folder` and returns report.json's
/// "sky_panorama": the file, its size and the frame (up, north, east in scene coordinates)
/// that places it, which the viewer reads to draw the sky.
nlohmann::json writeSkyPanorama(OutputFolder& folder, const SkyModel& sky);
nlohmann::json surfacesJson(const std::vector<SurfaceResult>& surfaces);
/// Peak resident memory of this process in bytes (getrusage).
std::size_t peakMemoryBytes();

/// Pretty-printed JSON, written atomically; a number that is not finite is refused.
void writeJson(const std::string& path, const nlohmann::json& j);

/// Writes convergence.csv (output/run_files.h) and convergence.png (residual against work and
/// against seconds).
void writeConvergence(const std::string& csvPath, const std::string& pngPath,
                      const std::vector<SolveResult>& solves, double metresPerUnit);

}  // namespace radkit
