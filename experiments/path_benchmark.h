// The path-tracing benchmark: camera paths per second, and the rays they cast per second,
// against the raw Embree closest-hit rate on random rays in the same scene and run.
#pragma once

#include <cstdint>

#include <nlohmann/json_fwd.hpp>

#include "render/path_tracer.h"

namespace radkit {

struct PathTraceBenchmarkSettings {
  PathTraceSettings render;           ///< the image traced (its size and spp set the work)
  long long referenceRays = 2000000;  ///< random rays for the reference rate
  std::uint64_t seed = 7;             ///< the reference rays' stream
};

struct PathTraceBenchmark {
  int threads = 0;
  int width = 0, height = 0, samplesPerPixel = 0;
  // Ours: renderPathTraced, wall clock (includes shading, sampling and the pixel-centre ray).
  long long paths = 0, rays = 0;
  double seconds = 0, pathsPerSecond = 0, raysPerSecond = 0;
  // Reference: Visibility::closestHit on rays from uniformly random points on random
  // patches (area-weighted) in cosine-distributed directions on their front side: the
  // shape of a path tracer's bounce rays. Generated before timing, traced in parallel.
  long long referenceRays = 0;
  double referenceSeconds = 0, referenceRaysPerSecond = 0, referenceHitFraction = 0;
  double ratio = 0;  ///< raysPerSecond / referenceRaysPerSecond
};

/// \brief Renders once and times the reference, both with the current TBB arena's threads.
PathTraceBenchmark benchmarkPathTracer(const ShadingScene& scene, const Camera& camera,
                                       const PathTraceBenchmarkSettings& settings);

/// \brief One JSON object: figure (paths/s, rays/s), reference (Embree rays/s), ratio.
nlohmann::json toJson(const PathTraceBenchmark& b);

}  // namespace radkit
