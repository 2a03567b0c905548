#include "radiosity/radiosity_pipeline.h"

#include <chrono>
#include <sstream>
#include <stdexcept>

#include "solvers/registry.h"

namespace radkit {

namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }
}  // namespace

std::vector<SolverChoice> parseSolverList(const std::string& text) {
  std::vector<SolverChoice> out;
  std::stringstream list(text);
  std::string item;
  while (std::getline(list, item, ',')) {
    if (item.empty()) continue;
    SolverChoice c;
    auto colon = item.find(':');
    c.name = item.substr(0, colon);
    if (colon != std::string::npos) {
      c.parameters = item.substr(colon + 1);
      for (char& ch : c.parameters)
        if (ch == ';') ch = ',';
    }
    makeSolver(c.name, SolverParams::parse(c.parameters));  // validates name and keys now
    out.push_back(c);
  }
  if (out.empty()) throw std::invalid_argument("--solvers: give at least one solver name");
  return out;
}

SolveResult runSolver(const SolverChoice& choice, const RadiositySystem& system, const SolverSettings& stopping,
                      const PipelineLog& log) {
  std::unique_ptr<Solver> solver = makeSolver(choice.name, SolverParams::parse(choice.parameters));
  SolveResult result = solve(*solver, system, stopping);
  if (log.progress) log.progress("solve " + choice.name, 1.0);
  return result;
}

PipelineResult runPipeline(const Scene& scene, const PipelineSettings& settings, const PipelineLog& log) {
  PipelineResult r;
  auto say = [&](const std::string& line) {
    if (log.message) log.message(line);
  };
  auto t = Clock::now();
  r.mesh = subdivide(scene, settings.mesh);
  r.seconds.mesh = since(t);
  if (r.mesh.size() == 0) throw std::invalid_argument("the scene has no patches");

  t = Clock::now();
  r.rays = std::make_unique<RayScene>(r.mesh);
  r.seconds.rayScene = since(t);

  t = Clock::now();
  r.formFactors = std::make_unique<FormFactorResult>(
      computeFormFactors(r.mesh, *r.rays, settings.formFactors, [&](const std::string& m) { say(m); },
                         [&](double f) {
                           if (log.progress) log.progress("form factors", f);
                         }));
  r.seconds.formFactors = since(t);

  r.system = makeRadiositySystem(scene, r.mesh, r.formFactors->matrix);
  if (settings.solvers.empty()) return r;  // form factors only

  t = Clock::now();
  for (const SolverChoice& choice : settings.solvers) {
    r.solves.push_back(runSolver(choice, r.system, settings.stopping, log));
    const SolveResult& s = r.solves.back();
    say(s.solver + ": " + s.reason);
  }
  r.seconds.solve = since(t);

  t = Clock::now();
  r.radiosity = toVec3(r.solves.front().radiosity);
  r.irradiance = irradiance(r.formFactors->matrix, r.solves.front().radiosity);
  r.surfaces = surfaceResults(scene, r.mesh, r.radiosity, r.irradiance);
  r.energy = energyBalance(scene, r.mesh, r.formFactors->matrix, r.radiosity, r.irradiance);
  r.seconds.results = since(t);
  return r;
}

}  // namespace radkit
