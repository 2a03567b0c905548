// The main job as one library call: load a scene, mesh it, solve it by the dense or the
// hierarchical method, and write the run folder (docs/formats.md). `radkit run`, `radkit
// solvers`, `radkit formfactors`, `radkit view`'s default run and the Python module's run()
// all call runJob; a front end only maps its options onto JobSettings and shows JobResult.
#pragma once

#include <nlohmann/json.hpp>

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "geometry/scene.h"
#include "geometry/scene_loader.h"
#include "hierarchy/hierarchical.h"
#include "hierarchy/link_matrix.h"
#include "radiosity/adaptive.h"
#include "radiosity/radiosity_pipeline.h"

namespace radkit {

/// Which outputs the job writes (docs/formats.md lists each file).
enum class JobKind {
  Run,          ///< every output: patches, surfaces, convergence, radiosity.vtp, F, the image
  Solvers,      ///< several solvers on one F: convergence and solution-<solver>.csv
  FormFactors,  ///< F and its diagnostics only, no solve
};

/// "run", "solvers" or "formfactors": the command that writes a job of this kind.
const char* jobKindName(JobKind kind);

/// The dense method (F for every patch pair) or hierarchical radiosity with clustering.
enum class JobMethod { Dense, Hierarchical };

/// A run of the dense method without a mesh size gets about this many patches: on the Cornell
/// box surface radiosities lie within 0.6 % of a 32 000-patch run (docs/run.md), in about 13 s
/// on two cores.
constexpr int kDefaultRunPatches = 4000;

struct JobSettings {
  JobKind kind = JobKind::Run;
  std::string scene;  ///< the scene file (.json, or .obj with its MTL)
  LoadOptions load;   ///< units, repair, the self-intersection check
  /// "px,py,pz,lx,ly,lz[,ux,uy,uz[,fov]]" replaces the scene's camera (images, report.json).
  std::string camera;
  /// The run folder, replaced as a whole when the run succeeds; empty: out/<scene name> for
  /// kind Run, an error for the others.
  std::string out;
  /// A speed-accuracy preset (radiosity/presets.h); every setting given below wins over it.
  std::string preset;

  // Settings a preset or the method chooses when they are not given.
  std::optional<JobMethod> method;  ///< unset: the preset's method, else dense
  /// Dense: patch size or count; unset: the preset's, else kDefaultRunPatches for kind Run
  /// (adaptive runs start from a quarter of their budget) and one patch per input face for
  /// the others.
  std::optional<SubdivisionSettings> mesh;
  /// Unset: the preset's, else point-polygon; "name:key=value;..." also sets
  /// formFactors.parameters, the method's own.
  std::optional<std::string> formFactorMethod;
  std::optional<int> formFactorSamples;  ///< unset: the preset's, else the method's own K
  std::optional<double> tolerance;  ///< unset: the preset's, else SolverSettings' (Solvers: 1e-10)
  /// Unset: SolverSettings' for dense solvers, kDefaultHierarchicalSweeps for the hierarchy.
  std::optional<long> maxIterations;
  /// Unset: 8 GiB for a dense F, defaultHierarchicalMemoryBudget() for the hierarchy.
  std::optional<std::size_t> memoryBudget;
  std::uint64_t seed = 1;  ///< every random stream derives from it

  /// The dense method's other form-factor settings: its method, samples, memoryBudget and seed
  /// are the fields above.
  FormFactorSettings formFactors;
  /// Solvers in order, the first gives the solution; empty: gauss-seidel, or for kind Solvers
  /// every registered solver. Kind FormFactors runs none.
  std::vector<SolverChoice> solvers;
  /// Norm and time limit of every solve; tolerance and maxIterations are the fields above.
  SolverSettings stopping;
  /// Dense, kind Run: refine the mesh where radiosity changes most, re-solve, repeat.
  std::optional<AdaptiveSettings> adaptive;

  /// The hierarchical method's own settings: its seed, memoryBudget and stopping are the
  /// fields above.
  HierarchicalSettings hierarchical;
  /// Hierarchical: links drawn at random and checked against a Monte Carlo reference
  /// (links_check.csv); 0: none.
  int checkLinks = 0;
  LinkColour linkColour = LinkColour::FormFactor;  ///< links.png's colour

  // Outputs.
  bool writeMatrix = false;  ///< also formfactors.mtx (Matrix Market text, about 25 B per entry)
  bool render = true;        ///< kind Run: render.png
  bool photometric = false;  ///< surfaces.csv with luminance and illuminance
  bool smooth = false;       ///< dense render.png interpolated between patches
  int imageWidth = 512, imageHeight = 512;
};

/// What a job did: the folder, report.json as written, and the solution in memory.
struct JobResult {
  std::string out;  ///< the run folder written
  Scene scene;
  nlohmann::json report;
  JobMethod method = JobMethod::Dense;
  std::unique_ptr<PipelineResult> dense;             ///< the dense method's result
  std::unique_ptr<HierarchicalResult> hierarchical;  ///< the hierarchical method's result
  double seconds = 0;                                ///< wall clock of the whole job
  double matrixSeconds = 0;                          ///< dense: writing formfactors.bin (and .mtx)
};

/// \brief The settings a job runs with: the preset's, then the ones given, then each method's
/// defaults; the optional fields come back set. \throws std::invalid_argument for settings
/// that disagree (a hierarchical preset with the dense method, a dense preset with the
/// hierarchical method, a hierarchical job of a kind other than Run, adaptive refinement
/// with the hierarchy) or are unusable.
JobSettings resolveJobSettings(const JobSettings& given);

/// \brief Runs the job: loads and checks the scene, solves, writes every output of its kind
/// into a staging folder and publishes it as `out` in one step; on any error nothing is
/// written. Progress, warnings ("warning: ...") and other lines go to `log`.
/// \throws InputError for bad input (the message names the file, the element and the fix),
/// std::invalid_argument for unusable settings, std::runtime_error when a solve diverges.
JobResult runJob(const JobSettings& settings, const PipelineLog& log = {});

/// \brief The same on a scene already loaded (by loadJobScene, or built in memory): its
/// settings.load is not used, and `loaded` (what loading reported) goes into report.json.
/// An empty settings.scene names the scene by scene.file.
JobResult runJob(Scene scene, const JobSettings& settings, const PipelineLog& log = {},
                 const LoadReport& loaded = {});

/// out/NAME for a run without an output folder, NAME being the scene's name made one safe
/// path component: separators, control characters and a leading dot become '_' ("../../x"
/// gives out/_._.._x).
std::string defaultOutFolder(const std::string& sceneName);

/// \brief Loads a scene as a job does: a camera text (JobSettings::camera) replaces the
/// scene's, warnings go to log.message ("warning: ..."), and stages of loading that take
/// over a second report progress.
Scene loadJobScene(const std::string& path, const LoadOptions& load, const std::string& camera,
                   const PipelineLog& log, LoadReport* report = nullptr);

}  // namespace radkit
