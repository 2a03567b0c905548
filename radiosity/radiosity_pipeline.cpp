#include "radiosity/radiosity_pipeline.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "radiosity/form_factor_storage.h"
#include "solvers/kernels.h"
#include "solvers/registry.h"
#include "util/format.h"
#include "util/params.h"
#include "util/setting_names.h"

namespace radkit {

namespace {
std::string sci(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2g", v);
  return buf;
}

/// The limits docs/numerical-stability.md measured, checked on this run.
std::vector<std::string> numericalWarnings(const Scene& scene, const PipelineResult& r) {
  std::vector<std::string> out;
  // Ray ends are lifted by the ray offset; features near that size neither block nor are
  // blocked reliably (a 1e-6 blocker in a 1 m room stopped blocking at all).
  const double offset = r.rays->epsilon();
  int tiny = 0;
  for (const Patch& p : r.mesh.patches) tiny += std::sqrt(p.area) < 100 * offset;
  if (tiny > 0)
    out.push_back(std::to_string(tiny) + " patches are smaller than 100× the ray offset (" +
                  sci(offset) + " " + scene.units +
                  "): occlusion by and of them is not resolved (single-precision ray tests). "
                  "Fix: model features at least 1e-4 of the scene's size, or split the scene");
  // A row sum above 1 (visibility noise) creates light; reflection amplifies it by up to
  // ρ/(1 − ρ) in the solution.
  double rhoMax = 0;
  for (int c = 0; c < 3; ++c)
    for (double v : r.system.reflectance[c]) rhoMax = std::max(rhoMax, v);
  const double excess = std::max(0.0, r.formFactors->diagnostics.rowSumMax - 1);
  const double amplified = excess * rhoMax / (1 - rhoMax);
  if (amplified > 1e-2) {  // the 1 % the run's accuracy targets
    // The worst row's largest term: a patch larger than its distance from the row's patch
    // breaks the small-patch approximation, whatever the visibility rays say.
    const std::vector<double> rows = rowSums(r.formFactors->matrix);
    const int i = int(std::max_element(rows.begin(), rows.end()) - rows.begin());
    int j = -1;
    double fMax = 0;
    forEachNonZero(r.formFactors->matrix, [&](int row, int col, double v) {
      if (row == i && v > fMax) fMax = v, j = col;
    });
    const std::string head = "form-factor rows sum to up to 1 + " + sci(excess) +
                             "; with reflectance up to " + sci(rhoMax) + " this can add up to " +
                             sci(amplified) + " relative energy";
    const Patch* from = &r.mesh.patches[i];
    const Patch* to = j >= 0 ? &r.mesh.patches[j] : nullptr;
    const double distance = to ? length(to->centroid - from->centroid) : 0;
    if (to && std::sqrt(to->area) > distance) {
      out.push_back(
          head + ": patch " + std::to_string(i) + " of \"" + scene.surfaces[from->surface].name +
          "\" sees patch " + std::to_string(j) + " of \"" + scene.surfaces[to->surface].name +
          "\", " + sci(std::sqrt(to->area)) + " " + scene.units + " across but only " +
          sci(distance) + " " + scene.units +
          " away, too large for its form factor to be estimated (the mesh, not visibility "
          "noise). Fix: split \"" +
          scene.surfaces[to->surface].name + "\" finer: " + setting("max_area") + " " +
          sci(distance * distance) + " or more " + setting("patches"));
    } else {
      out.push_back(head + " (visibility noise). Fix: raise " + setting("ff_samples") +
                    " or refine the mesh");
    }
  }
  return out;
}

}  // namespace

std::vector<SolverChoice> parseSolverList(const std::string& text) {
  std::vector<SolverChoice> out;
  std::stringstream list(text);
  std::string item;
  while (std::getline(list, item, ',')) {
    if (item.empty()) continue;
    const PluginChoice choice = splitPluginChoice(item);
    SolverChoice c{choice.name, choice.parameters};
    makeSolver(c.name, Params::parse(c.parameters));  // validates name and keys now
    out.push_back(c);
  }
  if (out.empty())
    throw std::invalid_argument(setting("solvers") + ": give at least one solver name");
  return out;
}

/// The median relative noise above which hemisphere's image shows its patches (a 5 % step
/// between neighbours is visible on a smooth wall).
constexpr double kHemisphereNoiseLimit = 0.05;

std::string hemisphereNoiseWarning(double noise, int samples) {
  // SE falls as 1/sqrt(K): the K that brings the median to the limit, to a power of two.
  const double need = samples * (noise / kHemisphereNoiseLimit) * (noise / kHemisphereNoiseLimit);
  long k = 1;
  while (k < need) k *= 2;
  return "hemisphere form factors are noisy: the median patch's gathered light has a standard "
         "error of " +
         sci(100 * noise) + " % at K = " + std::to_string(samples) +
         " rays per patch (the image will be a patchwork). Fix: " + setting("ff_samples") + " " +
         std::to_string(k) + " or more, or " + setting("ff") + " point-polygon";
}

double gatheredLightNoise(const FormFactorMatrix& f, const PatchMesh& mesh,
                          const std::vector<Vec3>& b, int samples, std::vector<double>* variance) {
  const std::size_t n = mesh.size();
  std::vector<double> first(n, 0.0), second(n, 0.0);
  auto sum = [](const Vec3& v) { return v.x + v.y + v.z; };
  forEachNonZero(f, [&](int i, int j, double fij) {
    const double bj = sum(b[j]);
    first[i] += fij * bj, second[i] += fij * bj * bj;
  });
  if (variance) variance->assign(n, 0.0);
  std::vector<std::pair<double, double>> relative;  // (SE/H, area) of lit patches
  double lit = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double var = std::max(0.0, second[i] - first[i] * first[i]) / samples;
    if (variance) (*variance)[i] = var;
    if (!(first[i] > 0)) continue;
    relative.push_back({std::sqrt(var) / first[i], mesh.patches[i].area});
    lit += mesh.patches[i].area;
  }
  if (relative.empty()) return 0;
  std::sort(relative.begin(), relative.end());
  double area = 0;
  for (const auto& [rel, a] : relative)
    if ((area += a) >= lit / 2) return rel;
  return relative.back().first;
}

namespace {

/// The sky's light on every patch, and its ρ-fold added to the system's emission.
void addDaylight(const Scene& scene, const PipelineSettings& settings, PipelineResult& r,
                 const PipelineLog& log) {
  r.sky = std::make_unique<SkyModel>(*scene.sky);
  r.daylight = std::make_unique<Daylight>(
      computeDaylight(r.mesh, *r.rays, *r.sky, settings.formFactors.seed));
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < r.mesh.size(); ++i)
      r.system.emission[c][i] += r.system.reflectance[c][i] * r.daylight->total(i)[c];
  if (log.progress) log.progress("daylight", 1.0);
}

}  // namespace

void addDaylightToSurfaces(const PatchMesh& mesh, const Daylight& d,
                           std::vector<SurfaceResult>& surfaces,
                           const std::vector<int>* daylightIndex) {
  for (std::size_t s = 0; s < surfaces.size(); ++s) {
    SurfaceResult& out = surfaces[s];
    double area = 0, svf = 0;
    Vec3 light{0, 0, 0};
    for (int i = mesh.surfaceBegin[s]; i < mesh.surfaceBegin[s + 1]; ++i) {
      const int k = daylightIndex ? (*daylightIndex)[i] : i;
      const double a = mesh.patches[i].area;
      area += a, svf += d.skyViewFactor[k] * a, light += d.total(k) * a;
    }
    out.daylit = true;
    if (area > 0) out.skyViewFactor = svf / area, out.daylight = light / area;
    out.daylightIlluminance = kLumensPerWatt * luminance(out.daylight);
  }
}

SolveResult runSolver(const SolverChoice& choice, const RadiositySystem& system,
                      const SolverSettings& stopping, const PipelineLog& log) {
  std::unique_ptr<Solver> solver = makeSolver(choice.name, Params::parse(choice.parameters));
  SolveResult result = solve(*solver, system, stopping);
  if (log.progress) log.progress("solve " + choice.name, 1.0);
  return result;
}

PipelineResult runPipeline(const Scene& scene, const PipelineSettings& settings,
                           const PipelineLog& log) {
  auto t = Clock::now();
  std::vector<std::string> meshWarnings;
  PatchMesh mesh = subdivide(scene, settings.mesh, &meshWarnings);
  double meshSeconds = secondsSince(t);
  for (const std::string& w : meshWarnings)
    if (log.message) log.message("warning: " + w);
  PipelineResult r = runPipeline(scene, std::move(mesh), settings, log);
  r.warnings.insert(r.warnings.begin(), meshWarnings.begin(), meshWarnings.end());
  r.seconds.mesh = meshSeconds;
  return r;
}

PipelineResult runPipeline(const Scene& scene, PatchMesh mesh, const PipelineSettings& settings,
                           const PipelineLog& log) {
  PipelineResult r;
  auto say = [&](const std::string& line) {
    if (log.message) log.message(line);
  };
  r.mesh = std::move(mesh);
  if (r.mesh.size() == 0) throw std::invalid_argument("the scene has no patches");

  auto t = Clock::now();
  r.rays = std::make_unique<RayScene>(r.mesh);
  r.seconds.rayScene = secondsSince(t);

  t = Clock::now();
  r.formFactors = std::make_unique<FormFactorResult>(computeFormFactors(
      r.mesh, *r.rays, settings.formFactors, [&](const std::string& m) { say(m); },
      [&](double f) {
        if (log.progress) log.progress("form factors", f);
      }));
  r.seconds.formFactors = secondsSince(t);

  r.system = makeRadiositySystem(scene, r.mesh, r.formFactors->matrix);
  if (scene.sky) {
    t = Clock::now();
    addDaylight(scene, settings, r, log);
    r.seconds.daylight = secondsSince(t);
  }
  r.warnings = numericalWarnings(scene, r);
  for (const std::string& w : r.warnings) say("warning: " + w);
  if (settings.solvers.empty()) return r;  // form factors only

  t = Clock::now();
  for (const SolverChoice& choice : settings.solvers) {
    r.solves.push_back(runSolver(choice, r.system, settings.stopping, log));
    const SolveResult& s = r.solves.back();
    say(s.solver + ": " + s.reason);
  }
  r.seconds.solve = secondsSince(t);

  t = Clock::now();
  r.radiosity = toVec3(r.solves.front().radiosity);
  r.irradiance = irradiance(r.formFactors->matrix, r.solves.front().radiosity);
  const std::vector<Vec3>* daylight = nullptr;
  std::vector<Vec3> arriving;
  if (r.daylight) {
    arriving.resize(r.mesh.size());
    for (int i = 0; i < r.mesh.size(); ++i) {
      arriving[i] = r.daylight->total(i);
      r.irradiance[i] += arriving[i];
    }
    daylight = &arriving;
  }
  r.surfaces = surfaceResults(scene, r.mesh, r.radiosity, r.irradiance);
  if (r.daylight) addDaylightToSurfaces(r.mesh, *r.daylight, r.surfaces);
  r.energy =
      energyBalance(scene, r.mesh, r.formFactors->matrix, r.radiosity, r.irradiance, daylight);
  if (formFactorTraits(settings.formFactors.method).rowBudget) {
    r.formFactorNoise = gatheredLightNoise(r.formFactors->matrix, r.mesh, r.radiosity,
                                           settings.formFactors.samples);
    if (r.formFactorNoise > kHemisphereNoiseLimit) {
      r.warnings.push_back(hemisphereNoiseWarning(r.formFactorNoise, settings.formFactors.samples));
      say("warning: " + r.warnings.back());
    }
  }
  r.seconds.results = secondsSince(t);
  return r;
}

}  // namespace radkit
