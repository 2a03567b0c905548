#include "apps/common.h"

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <stdexcept>

#include "apps/console.h"
#include "geometry/scene_loader.h"
#include "job/job.h"
#include "render/camera.h"
#include "util/format.h"
#include "util/output_folder.h"
#include "viewer/viewer.h"  // parseSize (viewer.h has no VTK)

namespace radkit::app {

namespace {

CLI::Validator finiteNumber(bool allowZero) {
  return CLI::Validator(
      [allowZero](std::string& text) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (text.empty() || end != text.c_str() + text.size())
          return "'" + text + "' is not a number";
        if (!std::isfinite(v))
          return "'" + text + "' is not a finite number. Fix: give a decimal number";
        if (allowZero ? v < 0 : v <= 0)
          return "'" + text + "' must be " + (allowZero ? ">= 0" : "> 0");
        return "";
      },
      allowZero ? "FINITE >= 0" : "FINITE > 0");
}

}  // namespace

const CLI::Validator FinitePositive = finiteNumber(false);
const CLI::Validator FiniteNonNegative = finiteNumber(true);

CLI::Validator FiniteRange(double lo, double hi) {
  return CLI::Validator(
      [lo, hi](std::string& text) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (text.empty() || end != text.c_str() + text.size())
          return "'" + text + "' is not a number";
        if (!(v >= lo && v <= hi))  // false for NaN
          return "'" + text + "' is not a number in [" + fmt("%g", lo) + ", " + fmt("%g", hi) + "]";
        return "";
      },
      "FINITE in [" + fmt("%g", lo) + " - " + fmt("%g", hi) + "]");
}

const CLI::Validator Unsigned = CLI::Validator(
    [](std::string& text) -> std::string {
      if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos)
        return "'" + text + "' is not a whole number >= 0";
      errno = 0;
      std::strtoull(text.c_str(), nullptr, 10);
      if (errno == ERANGE) return "'" + text + "' is larger than 18446744073709551615";
      return "";
    },
    "UINT >= 0");

std::string defaultScenePath() {
  // The source tree's data/ first (a build run from anywhere), then ./data.
  std::filesystem::path p = std::filesystem::path(RADKIT_DATA_DIR) / "cornell-box.json";
  if (std::filesystem::exists(p)) return p.string();
  return "data/cornell-box.json";
}

void addMeshOptions(CLI::App& command, MeshOptions& options, bool sceneRequired) {
  auto* scene =
      command.add_option("scene", options.scene, "Scene file (.json, or .obj with its .mtl)");
  if (sceneRequired)
    scene->required()->check(CLI::ExistingFile);
  else
    scene->check(CLI::ExistingFile);
  auto* area = command
                   .add_option("--max-area", options.maxArea,
                               "Split surfaces so every patch has at most this area (scene units²)")
                   ->check(FinitePositive);
  command
      .add_option("--patches", options.patches,
                  "Split surfaces into about this many patches in total")
      ->check(CLI::Range(1, int(kMaxPatches)))
      ->excludes(area);
  std::vector<std::string> units;
  for (const auto& unit : knownUnits()) units.push_back(unit.first);
  command
      .add_option(
          "--units", options.load.units,
          "Length unit of the scene's coordinates (default: the scene file's \"units\", else m); "
          "areas and powers in reports are converted to m² and W")
      ->check(CLI::IsMember(units));
  command.add_flag(
      "--repair", options.load.repair,
      "Repair meshes instead of refusing them: weld duplicate vertices, drop duplicate and "
      "degenerate faces, cut non-manifold edges and vertices, stitch borders, orient; each "
      "change is reported (docs/bring-your-own-model.md)");
  command.add_flag_function(
      "--skip-self-intersections",
      [&options](std::int64_t) { options.load.selfIntersections = false; },
      "Skip the self-intersection check of every surface (a warning when found; about 8 s a "
      "million triangles), for meshes known to be clean (docs/formats.md)");
}

void addImageSizeOptions(CLI::App& command, int& width, int& height, const std::string& what) {
  auto* size = command.add_option_function<std::string>(
      "--size",
      [&width, &height](const std::string& text) {
        viewer::parseSize(text, width, height, 16, 8192);
      },
      "Size of " + what + " WIDTHxHEIGHT (default " + std::to_string(width) + "x" +
          std::to_string(height) + ")");
  command
      .add_option_function<int>(
          "--image-size",
          [&width, &height](const int& n) {
            width = height = n;
            std::cerr << "radkit: warning: --image-size is deprecated: use --size " << n << "x" << n
                      << " (the spelling of render and view)\n";
          },
          "Deprecated: --size NxN")
      ->check(CLI::Range(16, 8192))
      ->excludes(size);
}

void addCameraOption(CLI::App& command, std::string& camera) {
  command.add_option(
      "--camera", camera,
      "Camera px,py,pz,lx,ly,lz[,ux,uy,uz[,fov]]: position, look-at, up (default 0,1,0), vertical "
      "field of view in degrees (default 40); replaces the scene's. Without either, the camera "
      "looks into the scene from its most front-facing side");
}

Scene loadSceneReporting(const std::string& path, const LoadOptions& load, LoadReport* out,
                         const std::string& camera) {
  Progress bar;
  Scene scene = loadJobScene(path, load, camera, consoleLog(bar), out);
  bar.finish();
  return scene;
}

PatchMesh meshScene(const Scene& scene, const MeshOptions& options) {
  return subdivideScene(
      scene, SubdivisionSettings{options.maxArea, options.patches},
      [](const std::string& w) { std::cerr << "radkit: warning: " << w << '\n'; });
}

std::string fmt(const char* format, double value) { return formatValue(format, value); }

void printField(const std::string& label, const std::string& value) {
  std::printf("%22s: %s\n", label.c_str(), value.c_str());
}

void printLogLine(const std::string& line) {
  std::fprintf(stderr, "%s%s\n", line.rfind("warning: ", 0) == 0 ? "radkit: " : "", line.c_str());
}

}  // namespace radkit::app
