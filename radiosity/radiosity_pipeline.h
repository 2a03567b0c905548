// The radiosity pipeline as one call: mesh, ray scene, form factors, solvers, results.
// `radkit run`, `radkit solvers` and lab exercises all go through it.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "daylight/daylight.h"
#include "daylight/sky.h"
#include "geometry/patch_mesh.h"
#include "geometry/ray_scene.h"
#include "geometry/scene.h"
#include "geometry/subdivision.h"
#include "radiosity/form_factors.h"
#include "radiosity/radiosity_solution.h"
#include "solvers/solver.h"

namespace radkit {

/// One solver to run: a registry name and its parameters ("omega=1.2").
struct SolverChoice {
  std::string name = "gauss-seidel";
  std::string parameters;
};

struct PipelineSettings {
  SubdivisionSettings mesh;
  FormFactorSettings formFactors;
  /// Each runs from B = E; the first is "the" solution. None: stop after the form factors.
  std::vector<SolverChoice> solvers{SolverChoice{}};
  SolverSettings stopping;
};

/// Progress reports: a stage name and the fraction done (0..1), or a message line.
struct PipelineLog {
  std::function<void(const std::string& stage, double fraction)> progress;
  std::function<void(const std::string& line)> message;
};

/// Wall seconds per stage, in pipeline order.
struct StageSeconds {
  double mesh = 0, rayScene = 0, formFactors = 0, daylight = 0, solve = 0, results = 0;
};

struct PipelineResult {
  PatchMesh mesh;
  std::unique_ptr<RayScene> rays;
  std::unique_ptr<FormFactorResult> formFactors;  ///< stable address: `system` points into it
  RadiositySystem system;
  std::vector<SolveResult> solves;
  std::vector<Vec3> radiosity;   ///< the first solver's B per patch
  std::vector<Vec3> irradiance;  ///< H = F B, plus the daylight with a sky
  /// With a sky (scene.sky): the sky's model and each patch's daylight, whose ρ-fold is
  /// added to the system's emission (B = E + ρ(FB + D)).
  std::unique_ptr<SkyModel> sky;
  std::unique_ptr<Daylight> daylight;
  std::vector<SurfaceResult> surfaces;
  EnergyBalance energy;
  StageSeconds seconds;
  std::vector<std::string>
      warnings;  ///< numerical limits met by this run (also sent to log.message)
  /// hemisphere only: area-weighted median relative standard error of the gathered light
  /// Σ_j F_ij B_j over lit patches (0 for other methods, whose noise is in visibility alone).
  double formFactorNoise = 0;
};

/// \brief Runs every stage on an already loaded scene. Throws std::invalid_argument for bad
/// settings (unknown solver, K = 0), MemoryBudgetError when F fits no storage.
PipelineResult runPipeline(const Scene& scene, const PipelineSettings& settings,
                           const PipelineLog& log = {});

/// \brief The same on a mesh made elsewhere (adaptive refinement, a lab's own mesher);
/// settings.mesh is not used.
PipelineResult runPipeline(const Scene& scene, PatchMesh mesh, const PipelineSettings& settings,
                           const PipelineLog& log = {});

/// \brief For a method whose row i is the mean of K draws (hemisphere: B of the patch a ray
/// hits, 0 for a miss), the gathered light H_i = Σ_j F_ij B_j (channels summed) has variance
/// (Σ_j F_ij B_j² − H_i²)/K. Returns the area-weighted median of SE(H_i)/H_i over patches with
/// H_i > 0, and each patch's variance in `variance` if given.
double gatheredLightNoise(const FormFactorMatrix& f, const PatchMesh& mesh,
                          const std::vector<Vec3>& b, int samples,
                          std::vector<double>* variance = nullptr);

/// \brief Fills each surface's daylight fields (sky view factor, daylight, its illuminance)
/// with area-weighted means over its patches; patch i's daylight is d's entry
/// (*daylightIndex)[i] when given (hierarchical leaves take their input face's), else i.
void addDaylightToSurfaces(const PatchMesh& mesh, const Daylight& d,
                           std::vector<SurfaceResult>& surfaces,
                           const std::vector<int>* daylightIndex = nullptr);

/// \brief Solves one system with one solver from B = E, reporting progress after each step.
SolveResult runSolver(const SolverChoice& choice, const RadiositySystem& system,
                      const SolverSettings& stopping, const PipelineLog& log = {});

/// \brief Parses "jacobi,sor:omega=1.2,southwell" (parameters after ':', ';'-separated
/// key=value pairs) into choices; names are checked against the solver registry.
std::vector<SolverChoice> parseSolverList(const std::string& text);

}  // namespace radkit
