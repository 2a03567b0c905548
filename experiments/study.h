// The speed-accuracy study: runs the pipeline over mesh densities, form-factor methods and
// samples, solvers and tolerances (and adaptive budgets) within a time budget, and measures
// each configuration's error against one reference solution. `radkit study` writes the files.
#pragma once

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "radiosity/adaptive.h"
#include "radiosity/radiosity_pipeline.h"
#include "solvers/registry.h"

namespace radkit {

/// Which setting a configuration varies; the others stay at StudySettings::baseline.
/// Hierarchical rows are run by the caller (hierarchy/ sits above radiosity/) and measured with
/// measureErrors against the same reference.
enum class StudyKnob { Mesh, FormFactors, Solver, Adaptive, Hierarchical };
const char* studyKnobName(
    StudyKnob knob);  ///< "mesh", "formfactors", "solver", "adaptive", "hierarchical"

struct StudyConfig {
  StudyKnob knob = StudyKnob::Mesh;
  PipelineSettings settings;  ///< one solver; mesh.targetPatches set
  AdaptiveSettings adaptive;  ///< Adaptive knob only: settings.mesh is the starting mesh
  double epsilon = 0;         ///< Hierarchical knob only: the link error threshold
  std::string label()
      const;  ///< "N=1000", "monte-carlo K=64", "sor tol=1e-03", "adaptive <=2000", "eps=1e-04"
};

/// One configuration's measurements. Errors are relative, against the study's reference:
/// - surfaceError: max over named surfaces and RGB channels of |B_S − B_S,ref| / B_S,ref;
/// - patchError: Σ_p W_p Σ_c |B_pc − B̄_pc,ref| / Σ_p W_p Σ_c B̄_pc,ref, B̄_ref the area mean of the
///   reference over patch p and W_p the area it was taken over (the accuracy of the patch means
///   a constant-element solution promises);
/// - fieldError: ∫ Σ_c |B_c(x) − B_ref,c(x)| dA / ∫ Σ_c B_ref,c(x) dA of the two
///   piecewise-constant pictures (as rendered without smoothing).
/// Both integrals cut each reference patch into 4×4 pieces and locate each piece's centre on
/// the configuration's mesh (mapPatches' ray), so non-nested meshes are compared by area.
struct StudyRow {
  StudyConfig config;
  bool ran = false;
  std::string note;             ///< why it was skipped, or the solver's stop reason
  double estimatedSeconds = 0;  ///< the planner's estimate before running
  /// What the planner weighed against the budget: the estimate plus what must still follow it
  /// (the reference), and the budget left then. It runs when neededSeconds <= secondsLeft;
  /// NaN for rows that came with another run (the solver knob, the baseline's copy).
  double neededSeconds = std::numeric_limits<double>::quiet_NaN();
  double secondsLeft = std::numeric_limits<double>::quiet_NaN();
  int patches = 0;
  StageSeconds seconds;
  double totalSeconds = 0;  ///< what this configuration would cost run alone
  std::size_t formFactorBytes = 0;
  std::size_t peakBytes = 0;  ///< process peak resident memory during this configuration
  long iterations = 0;
  bool converged = false;
  double surfaceError = 0, patchError = 0, fieldError = 0;
  bool paretoSurface = false, paretoPatch = false;  ///< on the front of error vs totalSeconds
};

/// A solution to compare against: its mesh, B per patch and per-surface means.
struct StudySolution {
  PatchMesh mesh;
  std::vector<Vec3> radiosity;
  std::vector<SurfaceResult> surfaces;
};

/// The reference and its own error estimate (Richardson, from the two finest mesh rungs).
struct StudyReference {
  StudySolution solution;
  StudyRow row;  ///< its cost, with zero errors
  double surfaceErrorEstimate = 0, patchErrorEstimate = 0;
  std::string errorMethod;  ///< how the estimates were made, one paragraph
};

/// \brief Each registered form-factor method and the K its traits give the study.
std::vector<std::pair<std::string, std::vector<int>>> studyFormFactorSamples();

struct StudySettings {
  double maxSeconds = 600;    ///< wall-clock budget for the whole study
  PipelineSettings baseline;  ///< every knob's other settings (one solver)
  std::vector<int> meshLadder{250, 500, 1000, 2000, 4000, 8000, 16000, 32000};
  int knobPatches = 1000;  ///< the mesh the form-factor and solver knobs run on
  /// Every registered form-factor method with its traits' K ladder.
  std::vector<std::pair<std::string, std::vector<int>>> formFactorSamples =
      studyFormFactorSamples();
  std::vector<std::string> solvers = solverNames();  ///< every registered solver
  std::vector<double> tolerances{1e-1, 1e-2, 1e-3, 1e-4, 1e-6};
  std::vector<int> adaptiveBudgets{1000, 2000, 4000};
  int adaptiveStartPatches = 500;
  double referenceTolerance = 1e-9;
};

struct StudyResult {
  std::vector<StudyRow> rows;  ///< in the order run, skipped ones last
  StudyReference reference;
  double seconds = 0;
};

/// \brief Runs the study: cheapest configurations first, each only when its estimate and the
/// reference's still fit the remaining budget (estimates scale measured runs by n² per stage);
/// then the reference at twice the finest mesh rung run (settings.baseline, tolerance
/// referenceTolerance); then every error and both Pareto fronts.
StudyResult runStudy(const Scene& scene, const StudySettings& settings,
                     const PipelineLog& log = {});

/// \brief Seconds the smallest reference (2 × knobPatches) is estimated to take before anything
///        is measured: the study runs its reference whatever the budget says.
double estimateReferenceSeconds(const StudySettings& settings);

/// \brief For each patch of `from`, the patch of `onto` that contains its centroid (a ray from
/// just in front of the centroid back along −n), or −1 when none of the same surface is hit.
std::vector<int> mapPatches(const PatchMesh& from, const PatchMesh& onto,
                            const Visibility& ontoRays);

/// \brief Fills surfaceError, patchError and fieldError of `row` for `solution` against
/// `reference`.
void measureErrors(const StudySolution& solution, const StudySolution& reference, StudyRow& row);

/// \brief Flags the points not dominated by another (lower-or-equal cost and lower error).
std::vector<bool> paretoFront(const std::vector<double>& cost, const std::vector<double>& error);

/// \brief Least-squares slope of log y against log x (the exponent of y ∝ x^p); NaN when fewer
/// than two positive points.
double fitExponent(const std::vector<double>& x, const std::vector<double>& y);

/// One row per configuration and one for the reference; times in seconds, memory in bytes,
/// errors relative to the reference (above), needed_s and left_s what the
/// planner weighed (empty for rows that came with another run).
void writeStudyCsv(const std::string& path, const StudyResult& result);

}  // namespace radkit
