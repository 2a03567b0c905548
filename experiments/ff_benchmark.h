// The form-factor benchmark: our visibility-ray rate inside point-polygon against raw Embree
// occlusion rays on the same scene and thread count, measured in the same run.
#pragma once

#include <cstdint>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "geometry/patch_mesh.h"
#include "geometry/ray_scene.h"
#include "radiosity/form_factor_diagnostics.h"
#include "radiosity/form_factor_method.h"

namespace radkit {

struct FormFactorBenchmarkSettings {
  FormFactorSettings formFactors;     ///< the run measured (method should be point-polygon)
  long long referenceRays = 4000000;  ///< raw Embree segments for the reference rate
  std::uint64_t seed = 7;             ///< segment endpoints of the reference
};

struct FormFactorBenchmark {
  int patches = 0;
  int threads = 0;
  // Ours: rays cast by the method, divided by the time spent in its ray phase (thread
  // seconds / threads; includes sampling the segment ends and the Visibility call).
  long long raysCast = 0;
  double raySeconds = 0;
  double raysPerSecond = 0;
  double formFactorSeconds = 0;     ///< wall time of the whole computeFormFactors
  double raysPerSecondOverall = 0;  ///< raysCast / formFactorSeconds
  // Reference: rtcOccluded1 (RayScene::occludedRaw) on random segments between uniformly
  // random points of random facing patch pairs, ends lifted as Visibility::occluded does;
  // segments generated before timing.
  long long referenceRays = 0;
  double referenceSeconds = 0;
  double referenceRaysPerSecond = 0;
  double referenceOccludedFraction = 0;
  double ratio = 0;  ///< raysPerSecond / referenceRaysPerSecond (target >= 0.8)
  // Pairs: facing patch pairs (each computed once, both directions by reciprocity) per
  // second of the compute phase, and of the geometry part alone (thread seconds / threads).
  long long pairs = 0;
  double computeSeconds = 0;
  double pairsPerSecond = 0;
  double pairsPerGeometrySecond = 0;
  std::size_t matrixBytes = 0;
  std::size_t peakResidentBytes = 0;  ///< VmHWM of the process after the run (Linux)
  FormFactorDiagnostics diagnostics;
};

/// \brief Runs computeFormFactors on the mesh, then the raw Embree reference, both with the
/// current TBB arena's threads. `scene` must be built from `mesh`.
FormFactorBenchmark benchmarkFormFactors(const PatchMesh& mesh, const RayScene& scene,
                                         const FormFactorBenchmarkSettings& settings);

/// \brief The result as one JSON object (figure, reference, ratio, seconds, memory).
nlohmann::json toJson(const FormFactorBenchmark& b);

}  // namespace radkit
