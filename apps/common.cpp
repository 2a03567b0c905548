#include "apps/common.h"

#include <cstdio>
#include <filesystem>
#include <iostream>

#include "geometry/scene_loader.h"

namespace radkit::app {

std::string defaultScenePath() {
  // The source tree's data/ first (a build run from anywhere), then ./data.
  std::filesystem::path p = std::filesystem::path(RADKIT_DATA_DIR) / "cornell-box.json";
  if (std::filesystem::exists(p)) return p.string();
  return "data/cornell-box.json";
}

void addMeshOptions(CLI::App& command, MeshOptions& options, bool sceneRequired) {
  auto* scene = command.add_option("scene", options.scene,
                                   "Scene file (.json, or .obj with its .mtl)");
  if (sceneRequired) scene->required()->check(CLI::ExistingFile);
  else scene->check(CLI::ExistingFile);
  auto* area = command.add_option("--max-area", options.maxArea,
                                  "Split surfaces so every patch has at most this area (scene units²)")
                   ->check(CLI::PositiveNumber);
  command.add_option("--patches", options.patches, "Split surfaces into about this many patches in total")
      ->check(CLI::PositiveNumber)
      ->excludes(area);
}

Scene loadSceneReporting(const std::string& path) {
  LoadReport report;
  Scene scene = loadScene(path, &report);
  for (const std::string& w : report.warnings) std::cerr << "radkit: warning: " << w << '\n';
  return scene;
}

PatchMesh meshScene(const Scene& scene, const MeshOptions& options) {
  return subdivide(scene, SubdivisionSettings{options.maxArea, options.patches});
}

std::string fmt(const char* format, double value) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, value);
  return buf;
}

void printField(const std::string& label, const std::string& value) {
  std::printf("%22s: %s\n", label.c_str(), value.c_str());
}

}  // namespace radkit::app
