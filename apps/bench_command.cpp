// radkit bench: speed figures divided by a reference measured in the same run, as one JSON
// object on stdout (docs/benchmarks.md records the figures).
#include <cstdio>
#include <iostream>
#include <memory>

#include <nlohmann/json.hpp>

#include "apps/common.h"
#include "apps/options.h"
#include "apps/report.h"
#include "geometry/ray_scene.h"
#include "radiosity/ff_benchmark.h"
#include "render/path_benchmark.h"
#include "solvers/sweep_benchmark.h"

namespace radkit::app {

namespace {

struct FormFactorBench {
  MeshOptions mesh;
  FormFactorOptions ff;
  long long referenceRays = 4000000;
};

void runFormFactorBench(FormFactorBench& b) {
  b.ff.finish();
  Scene scene = loadSceneReporting(b.mesh.scene);
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
  PathTraceBenchmarkSettings settings;
};

void runPathTraceBench(PathTraceBench& b) {
  if (b.mesh.scene.empty()) b.mesh.scene = defaultScenePath();
  Scene scene = loadSceneReporting(b.mesh.scene);
  PatchMesh mesh = meshScene(scene, b.mesh);
  RayScene rays(mesh);
  ShadingScene shading(scene, mesh, rays, BsdfSettings{});
  Camera camera = scene.camera ? *scene.camera : PinholeCamera::framing(mesh.bounds());
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
      {"figure", {{"jacobi_bytes_per_second", r.jacobiBytesPerSecond},
                  {"gauss_seidel_bytes_per_second", r.gaussSeidelBytesPerSecond}}},
      {"reference", {{"triad_bytes_per_second", r.triadBytesPerSecond}, {"triad_bytes", r.triadBytes}}},
      {"ratio", {{"jacobi", r.jacobiRatio}, {"gauss_seidel", r.gaussSeidelRatio}}},
      {"target_ratio", 0.7},
      {"peak_memory_bytes", peakMemoryBytes()}};
  std::cout << j.dump(2) << std::endl;
}

}  // namespace

void addBenchCommands(CLI::App& app) {
  CLI::App* bench = app.add_subcommand("bench", "Benchmarks: one JSON object with the figure, its reference and the ratio");
  bench->require_subcommand(1);

  auto ff = std::make_shared<FormFactorBench>();
  CLI::App* f = bench->add_subcommand("formfactors", "Our visibility-ray rate against raw Embree rtcOccluded1 on the same scene");
  addMeshOptions(*f, ff->mesh);
  addFormFactorOptions(*f, ff->ff);
  f->add_option("--reference-rays", ff->referenceRays, "Raw Embree segments for the reference rate")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  f->callback([ff] { runFormFactorBench(*ff); });

  auto path = std::make_shared<PathTraceBench>();
  path->settings.render.width = path->settings.render.height = 128;
  path->settings.render.samplesPerPixel = 64;
  CLI::App* p = bench->add_subcommand("path-trace", "Path-traced rays per second against raw Embree closest hits on the same scene");
  addMeshOptions(*p, path->mesh, false);
  p->add_option("--spp", path->settings.render.samplesPerPixel, "Samples per pixel of the 128x128 image")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  p->callback([path] { runPathTraceBench(*path); });

  auto sweep = std::make_shared<SweepBenchmarkSettings>();
  CLI::App* s = bench->add_subcommand("solver", "Jacobi and Gauss-Seidel sweep bandwidth against a STREAM-like triad");
  s->add_option("--n", sweep->n, "Dense matrix size")->check(CLI::Range(64, 65536))->capture_default_str();
  s->add_option("--repetitions", sweep->repetitions, "Timed rounds of triad, Jacobi step and Gauss-Seidel step (best of each is kept)")->check(CLI::PositiveNumber)->capture_default_str();
  s->add_option("--threads", sweep->threads, "Threads (0: all cores)")->check(CLI::NonNegativeNumber)->capture_default_str();
  s->callback([sweep] { runSolverBench(*sweep); });
}

}  // namespace radkit::app
