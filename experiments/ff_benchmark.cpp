// Benchmark: visibility rays inside point-polygon versus raw Embree occlusion rays.
#include "experiments/ff_benchmark.h"
#include "util/threads.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/task_arena.h>

#include <chrono>
#include <fstream>
#include <nlohmann/json.hpp>

#include "radiosity/form_factors.h"
#include "radiosity/patch_pairs.h"
#include "util/process_memory.h"
#include "util/sampling.h"

namespace radkit {

namespace {
struct Segment {
  Vec3 origin, direction;
};

/// Lifted segments between random points of random facing patch pairs.
std::vector<Segment> referenceSegments(const PatchMesh& mesh, const RayScene& scene,
                                       long long count, std::uint64_t seed) {
  PatchTable table(mesh);
  std::vector<Segment> segments(static_cast<std::size_t>(count));
  const int n = table.size();
  tbb::parallel_for(tbb::blocked_range<long long>(0, count, 4096),
                    [&](const tbb::blocked_range<long long>& r) {
                      Rng rng(seed, std::uint64_t(r.begin()), 0);
                      for (long long k = r.begin(); k < r.end(); ++k) {
                        int i = 0, j = 0;
                        for (int attempt = 0; attempt < 1000; ++attempt) {
                          i = int(rng.nextBits() % std::uint64_t(n));
                          j = int(rng.nextBits() % std::uint64_t(n));
                          if (i != j && table.facing(i, j)) break;
                        }
                        const PatchInfo& a = table[i];
                        const PatchInfo& b = table[j];
                        Vec3 x = samplePatchUniform(a.v, a.count, rng.uniform(), rng.uniform());
                        Vec3 y = samplePatchUniform(b.v, b.count, rng.uniform(), rng.uniform());
                        Vec3 p = liftToward(x, a.normal, y, scene.epsilon());
                        Vec3 q = liftToward(y, b.normal, x, scene.epsilon());
                        segments[std::size_t(k)] = {p, q - p};
                      }
                    });
  return segments;
}

}  // namespace

FormFactorBenchmark benchmarkFormFactors(const PatchMesh& mesh, const RayScene& scene,
                                         const FormFactorBenchmarkSettings& settings) {
  using Clock = std::chrono::steady_clock;
  FormFactorBenchmark b;
  b.patches = mesh.size();
  b.threads = activeThreads();

  Clock::time_point start = Clock::now();
  FormFactorResult ff = computeFormFactors(mesh, scene, settings.formFactors);
  b.formFactorSeconds = std::chrono::duration<double>(Clock::now() - start).count();
  b.diagnostics = ff.diagnostics;
  b.matrixBytes = ff.diagnostics.matrixBytes;
  b.raysCast = ff.diagnostics.raysCast;
  b.raySeconds = ff.diagnostics.rayThreadSeconds / b.threads;
  b.raysPerSecond = ff.diagnostics.raysPerSecond;
  b.raysPerSecondOverall = b.formFactorSeconds > 0 ? b.raysCast / b.formFactorSeconds : 0;
  b.pairs = ff.diagnostics.pairsFacing;
  for (const auto& [phase, seconds] : ff.diagnostics.phaseSeconds)
    if (phase == "compute") b.computeSeconds = seconds;
  b.pairsPerSecond = b.computeSeconds > 0 ? b.pairs / b.computeSeconds : 0;
  double geometry = ff.diagnostics.geometryThreadSeconds / b.threads;
  b.pairsPerGeometrySecond = geometry > 0 ? b.pairs / geometry : 0;
  ff.matrix = FormFactorMatrix{};  // release F before the reference allocates its segments

  if (mesh.size() >= 2 && settings.referenceRays > 0) {
    std::vector<Segment> segments =
        referenceSegments(mesh, scene, settings.referenceRays, settings.seed);
    start = Clock::now();
    long long blocked = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, segments.size(), 1024), 0LL,
        [&](const tbb::blocked_range<std::size_t>& r, long long count) {
          for (std::size_t k = r.begin(); k < r.end(); ++k)
            count += scene.occludedRaw(segments[k].origin, segments[k].direction, 0.0, 1.0);
          return count;
        },
        [](long long x, long long y) { return x + y; });
    b.referenceSeconds = std::chrono::duration<double>(Clock::now() - start).count();
    b.referenceRays = static_cast<long long>(segments.size());
    b.referenceRaysPerSecond = b.referenceRays / b.referenceSeconds;
    b.referenceOccludedFraction = double(blocked) / double(b.referenceRays);
    b.ratio = b.raysPerSecond / b.referenceRaysPerSecond;
  }
  b.peakResidentBytes = peakMemory();
  return b;
}

nlohmann::json toJson(const FormFactorBenchmark& b) {
  return {
      {"benchmark", "formfactors"},
      {"patches", b.patches},
      {"threads", b.threads},
      {"figure",
       {{"name", "visibility rays per second inside point-polygon"},
        {"rays", b.raysCast},
        {"seconds", b.raySeconds},
        {"rays_per_second", b.raysPerSecond}}},
      {"reference",
       {{"name", "raw Embree rtcOccluded1 on random patch-to-patch segments"},
        {"rays", b.referenceRays},
        {"seconds", b.referenceSeconds},
        {"rays_per_second", b.referenceRaysPerSecond},
        {"occluded_fraction", b.referenceOccludedFraction}}},
      {"ratio", b.ratio},
      {"pairs",
       {{"name", "facing patch pairs per second of the compute phase (F_ij and F_ji)"},
        {"pairs", b.pairs},
        {"compute_seconds", b.computeSeconds},
        {"pairs_per_second", b.pairsPerSecond},
        {"pairs_per_geometry_second", b.pairsPerGeometrySecond}}},
      {"form_factor_seconds", b.formFactorSeconds},
      {"rays_per_second_overall", b.raysPerSecondOverall},
      {"matrix_bytes", b.matrixBytes},
      {"peak_resident_bytes", b.peakResidentBytes},
      {"form_factors", toJson(b.diagnostics)},
  };
}

}  // namespace radkit
