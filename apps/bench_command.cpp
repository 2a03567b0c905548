// radkit bench: speed figures divided by a reference measured in the same run, as one JSON
// object on stdout (docs/benchmarks.md records the figures).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>

#include <nlohmann/json.hpp>

#include "apps/common.h"
#include "apps/options.h"
#include "experiments/ff_benchmark.h"
#include "experiments/path_benchmark.h"
#include "experiments/sweep_benchmark.h"
#include "geometry/ray_scene.h"
#include "hierarchy/hierarchical.h"
#include "job/report.h"
#include "render/camera.h"
#include "util/process_memory.h"

namespace radkit::app {

namespace {

struct FormFactorBench {
  MeshOptions mesh;
  FormFactorOptions ff;
  long long referenceRays = 4000000;
};

void runFormFactorBench(FormFactorBench& b) {
  b.ff.finish();
  Scene scene = loadSceneReporting(b.mesh.scene, b.mesh.load);
  PatchMesh mesh = meshScene(scene, b.mesh);
  RayScene rays(mesh);
  FormFactorBenchmarkSettings s;
  s.formFactors = b.ff.settings;
  s.referenceRays = b.referenceRays;
  nlohmann::json j = toJson(benchmarkFormFactors(mesh, rays, s));
  j["scene"] = scene.name;
  std::cout << j.dump(2) << std::endl;
}

struct PathTraceBench {
  MeshOptions mesh;
  std::string camera;
  PathTraceBenchmarkSettings settings;
};

void runPathTraceBench(PathTraceBench& b) {
  if (b.mesh.scene.empty()) b.mesh.scene = defaultScenePath();
  Scene scene = loadSceneReporting(b.mesh.scene, b.mesh.load, nullptr, b.camera);
  PatchMesh mesh = meshScene(scene, b.mesh);
  RayScene rays(mesh);
  ShadingScene shading(scene, mesh, rays, BsdfSettings{});
  Camera camera = sceneCamera(scene, mesh);
  nlohmann::json j = toJson(benchmarkPathTracer(shading, camera, b.settings));
  j["scene"] = scene.name;
  std::cout << j.dump(2) << std::endl;
}

void runSolverBench(const SweepBenchmarkSettings& s) {
  SweepBenchmarkResult r = runSweepBenchmark(s);
  nlohmann::json j{
      {"benchmark", "solver sweep bandwidth"},
      {"n", r.n},
      {"threads", r.threads},
      {"repetitions", r.repetitions},
      {"matrix_bytes", r.matrixBytes},
      {"figure",
       {{"jacobi_bytes_per_second", r.jacobiBytesPerSecond},
        {"gauss_seidel_bytes_per_second", r.gaussSeidelBytesPerSecond}}},
      {"reference",
       {{"triad_bytes_per_second", r.triadBytesPerSecond}, {"triad_bytes", r.triadBytes}}},
      {"ratio", {{"jacobi", r.jacobiRatio}, {"gauss_seidel", r.gaussSeidelRatio}}},
      {"target_ratio", 0.7},
      {"peak_memory_bytes", peakMemoryBytes()}};
  std::cout << j.dump(2) << std::endl;
}

}  // namespace

struct HierarchicalBench {
  std::string scene;
  HierarchicalSettings settings;
  int densePatches = 4000;
};

/// The hierarchy against a dense run of the same scene in the same process: seconds and peak
/// memory of each (the peak reset in between), their ratios, and the largest surface difference.
void runHierarchicalBench(HierarchicalBench& b) {
  Scene scene = loadSceneReporting(b.scene);
  using Clock = std::chrono::steady_clock;
  resetPeakMemory();
  const std::size_t baseline = peakMemory();
  Clock::time_point t = Clock::now();
  HierarchicalResult h = solveHierarchical(scene, b.settings);
  const double hSeconds = std::chrono::duration<double>(Clock::now() - t).count();
  const std::size_t hPeak = peakMemory();
  std::vector<SurfaceResult> hSurfaces = h.surfaces;
  long long links = static_cast<long long>(h.system->links().size()), leaves = h.leaves.size(),
            rays = h.raysCast;
  h = HierarchicalResult{};
  resetPeakMemory();
  PipelineSettings dense;
  dense.mesh.targetPatches = b.densePatches;
  t = Clock::now();
  PipelineResult d = runPipeline(scene, dense);
  const double dSeconds = std::chrono::duration<double>(Clock::now() - t).count();
  const std::size_t dPeak = peakMemory();
  double worst = 0;
  for (std::size_t s = 0; s < hSurfaces.size(); ++s)
    for (int c = 0; c < 3; ++c)
      if (d.surfaces[s].radiosity[c] > 0)
        worst =
            std::max(worst, std::fabs(hSurfaces[s].radiosity[c] / d.surfaces[s].radiosity[c] - 1));
  nlohmann::json j{
      {"scene", scene.name},
      {"hierarchical",
       {{"epsilon", b.settings.epsilon},
        {"leaves", leaves},
        {"links", links},
        {"rays", rays},
        {"seconds", hSeconds},
        {"peak_bytes", hPeak}}},
      {"dense", {{"patches", d.mesh.size()}, {"seconds", dSeconds}, {"peak_bytes", dPeak}}},
      {"baseline_peak_bytes", baseline},
      {"time_ratio", hSeconds / dSeconds},
      {"memory_ratio_above_baseline",
       double(hPeak - baseline) / double(std::max(dPeak, baseline + 1) - baseline)},
      {"largest_surface_difference", worst}};
  std::cout << j.dump(2) << std::endl;
}

void addBenchCommands(CLI::App& app) {
  CLI::App* bench = app.add_subcommand(
      "bench", "Benchmarks: one JSON object with the figure, its reference and the ratio");
  bench->require_subcommand(1);

  auto ff = std::make_shared<FormFactorBench>();
  CLI::App* f = bench->add_subcommand(
      "formfactors", "Our visibility-ray rate against raw Embree rtcOccluded1 on the same scene");
  addMeshOptions(*f, ff->mesh);
  addFormFactorOptions(*f, ff->ff);
  // The segments are stored (about 30 B each) before they are timed.
  f->add_option("--reference-rays", ff->referenceRays, "Raw Embree segments for the reference rate")
      ->check(CLI::Range(1LL, 100000000LL))
      ->capture_default_str();
  f->callback([ff] { runFormFactorBench(*ff); });

  auto path = std::make_shared<PathTraceBench>();
  path->settings.render.width = path->settings.render.height = 128;
  path->settings.render.samplesPerPixel = 64;
  CLI::App* p = bench->add_subcommand(
      "path-trace",
      "Path-traced rays per second against raw Embree closest hits on the same scene");
  addMeshOptions(*p, path->mesh, false);
  addCameraOption(*p, path->camera);
  p->add_option("--spp", path->settings.render.samplesPerPixel,
                "Samples per pixel of the 128x128 image")
      ->check(CLI::Range(1, 1 << 20))
      ->capture_default_str();
  p->callback([path] { runPathTraceBench(*path); });

  auto sweep = std::make_shared<SweepBenchmarkSettings>();
  CLI::App* s = bench->add_subcommand(
      "solver", "Jacobi and Gauss-Seidel sweep bandwidth against a STREAM-like triad");
  s->add_option("--n", sweep->n, "Dense matrix size")
      ->check(CLI::Range(64, 65536))
      ->capture_default_str();
  s->add_option("--repetitions", sweep->repetitions,
                "Timed rounds of triad, Jacobi step and Gauss-Seidel step (best of each is kept)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  // --threads 1000000 took 936 MB (TBB's arena for the request) before TBB capped the workers.
  s->add_option("--threads", sweep->threads, "Threads (0: all cores)")
      ->check(CLI::Range(0, 1024))
      ->capture_default_str();
  s->callback([sweep] { runSolverBench(*sweep); });

  auto hier = std::make_shared<HierarchicalBench>();
  CLI::App* h = bench->add_subcommand(
      "hierarchical",
      "Hierarchical radiosity against a dense run of the same scene: time and memory ratios");
  h->add_option("scene", hier->scene, "Scene file")->required()->check(CLI::ExistingFile);
  h->add_option("--epsilon", hier->settings.epsilon, "Link error threshold")->capture_default_str();
  h->add_option("--dense-patches", hier->densePatches, "Patches of the dense run")
      ->check(CLI::Range(1, int(kMaxPatches)))
      ->capture_default_str();
  h->callback([hier] { runHierarchicalBench(*hier); });
}

}  // namespace radkit::app
