// Options and steps shared by radkit's subcommands.
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <string>

#include "geometry/patch_mesh.h"
#include "geometry/scene.h"
#include "geometry/scene_loader.h"
#include "geometry/subdivision.h"
#include "util/output_folder.h"

namespace radkit::app {

/// Photons `photons` and `render --shading photon-map` emit at most: each is traced and about
/// 1/(1 − ρ) of them stored at 36 B, so 1e8 already needs gigabytes (4e9 was allowed and ran on).
constexpr std::size_t kMaxPhotons = 100000000;

/// The scene and meshing options every geometric subcommand takes.
struct MeshOptions {
  std::string scene;
  double maxArea = 0;
  int patches = 0;
  LoadOptions load;  ///< --units, --repair
};

/// CLI11's PositiveNumber lets NaN through (NaN <= 0 is false) and infinity too; these refuse
/// both at parse time.
extern const CLI::Validator FinitePositive;
extern const CLI::Validator FiniteNonNegative;
/// A finite number in [lo, hi]: CLI::Range lets NaN through for the same reason.
CLI::Validator FiniteRange(double lo, double hi);
/// A whole number >= 0 for unsigned options: CLI11 reads "-1" into an unsigned as 2^64 - 1.
extern const CLI::Validator Unsigned;

/// Adds SCENE (positional; `required` or defaulting to the Cornell box), --max-area/--patches,
/// --units and --repair.
void addMeshOptions(CLI::App& command, MeshOptions& options, bool sceneRequired = true);

/// The measured Cornell box shipped in data/.
std::string defaultScenePath();

/// Adds --camera to a command that draws (an image, render.png, the viewer).
void addCameraOption(CLI::App& command, std::string& camera);

/// `--size WxH` of the images a command writes (one spelling with render and view), and the
/// older `--image-size N` (N×N) kept as a deprecated alias that says so.
void addImageSizeOptions(CLI::App& command, int& width, int& height, const std::string& what);

/// Loads the scene (printing its warnings to stderr, and keeping them in `report` when given)
/// and subdivides it; a mesh beyond kMaxPatches is an InputError naming the option that asked
/// for it. A non-empty `camera` (a --camera value) replaces the scene's camera, so images and
/// report.json agree.
Scene loadSceneReporting(const std::string& path, const LoadOptions& load = {},
                         LoadReport* report = nullptr, const std::string& camera = "");
/// The scene subdivided as the options ask; warnings to stderr, more patches than radkit
/// meshes an InputError naming the option (throwTooManyPatches).
PatchMesh meshScene(const Scene& scene, const MeshOptions& options);

/// One number printed with a printf format ("%.3g").
std::string fmt(const char* format, double value);
/// Prints a line of the library's log to stderr; its warnings ("warning: ...") get the
/// "radkit: " every other warning of the command line starts with.
void printLogLine(const std::string& line);

/// Prints a right-aligned "label: value" line to stdout.
void printField(const std::string& label, const std::string& value);

/// Runs `radkit run SCENE` with default settings into outDir (empty: out/<scene name>);
/// returns the folder written.
std::string runDefaultJob(const std::string& scenePath, const std::string& outDir);

void addMeshCommand(CLI::App& app);
void addViewCommand(CLI::App& app);
void addPipelineCommands(CLI::App& app);
void addBenchCommands(CLI::App& app);
void addStudyCommand(CLI::App& app);
void addRenderCommand(CLI::App& app);
void addBrdfCommand(CLI::App& app);
void addPhotonsCommand(CLI::App& app);
void addTerrainCommand(CLI::App& app);
void addSkyCommand(CLI::App& app);
void addCloudsCommand(CLI::App& app);
void addPillarsCommand(CLI::App& app);

}  // namespace radkit::app
