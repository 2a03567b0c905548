#include "experiments/path_benchmark.h"
#include "util/threads.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>

#include <nlohmann/json.hpp>

namespace radkit {

namespace {

struct Ray {
  Vec3 origin, dir;
};

/// Random bounce-like rays: area-weighted patch, uniform point on it, cosine direction.
std::vector<Ray> referenceRays(const ShadingScene& scene, long long count, std::uint64_t seed) {
  const PatchMesh& mesh = scene.mesh();
  std::vector<double> cdf;
  double total = 0;
  for (const Patch& p : mesh.patches) cdf.push_back(total += p.area);
  std::vector<Ray> rays(std::size_t(std::max(0LL, count)));
  Rng rng(seed, 0, 0);
  for (Ray& r : rays) {
    const double u = rng.uniform() * total;
    const std::size_t k = std::min(
        cdf.size() - 1, std::size_t(std::upper_bound(cdf.begin(), cdf.end(), u) - cdf.begin()));
    const Patch& p = mesh.patches[k];
    Vec3 v[4];
    for (int c = 0; c < p.vertexCount; ++c) v[c] = mesh.vertex(p, c);
    const Vec3 point = samplePatchUniform(v, p.vertexCount, rng.uniform(), rng.uniform());
    const double u1 = rng.uniform(), u2 = rng.uniform();
    r.dir = Frame(p.normal).toWorld(sampleCosineHemisphere(u1, u2));
    r.origin = point + p.normal * scene.rays().epsilon();
  }
  return rays;
}

}  // namespace

PathTraceBenchmark benchmarkPathTracer(const ShadingScene& scene, const Camera& camera,
                                       const PathTraceBenchmarkSettings& s) {
  PathTraceBenchmark b;
  b.threads = activeThreads();
  b.width = s.render.width;
  b.height = s.render.height;
  b.samplesPerPixel = s.render.samplesPerPixel;
  const MonteCarloImage img = renderPathTraced(scene, camera, s.render);
  b.paths = img.paths;
  b.rays = img.rays + (long long)(img.image.width) * img.image.height;  // + the pixel-centre rays
  b.seconds = img.seconds;
  b.pathsPerSecond = b.paths / b.seconds;
  b.raysPerSecond = b.rays / b.seconds;

  const std::vector<Ray> rays = referenceRays(scene, s.referenceRays, s.seed);
  const auto start = std::chrono::steady_clock::now();
  const long long hits = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, rays.size(), 4096), 0LL,
      [&](const tbb::blocked_range<std::size_t>& r, long long n) {
        for (std::size_t i = r.begin(); i != r.end(); ++i)
          if (scene.rays().closestHit(rays[i].origin, rays[i].dir, 0.0)) ++n;
        return n;
      },
      [](long long a, long long c) { return a + c; });
  b.referenceSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  b.referenceRays = (long long)rays.size();
  b.referenceRaysPerSecond = b.referenceRays / b.referenceSeconds;
  b.referenceHitFraction = b.referenceRays > 0 ? double(hits) / b.referenceRays : 0;
  b.ratio = b.raysPerSecond / b.referenceRaysPerSecond;
  return b;
}

nlohmann::json toJson(const PathTraceBenchmark& b) {
  return {{"benchmark", "path tracing"},
          {"threads", b.threads},
          {"image",
           {{"width", b.width}, {"height", b.height}, {"samples_per_pixel", b.samplesPerPixel}}},
          {"figure",
           {{"paths_per_second", b.pathsPerSecond},
            {"rays_per_second", b.raysPerSecond},
            {"rays_per_path", double(b.rays) / std::max(1LL, b.paths)},
            {"paths", b.paths},
            {"rays", b.rays},
            {"seconds", b.seconds}}},
          {"reference",
           {{"what", "Embree closest-hit on random cosine rays from random patch points"},
            {"rays_per_second", b.referenceRaysPerSecond},
            {"rays", b.referenceRays},
            {"seconds", b.referenceSeconds},
            {"hit_fraction", b.referenceHitFraction}}},
          {"ratio", b.ratio},
          {"paths_per_reference_ray", b.pathsPerSecond / b.referenceRaysPerSecond}};
}

}  // namespace radkit
