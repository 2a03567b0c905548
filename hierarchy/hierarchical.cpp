#include "hierarchy/hierarchical.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <sstream>
#include <stdexcept>
#include <unordered_map>

#include <tbb/parallel_for.h>

#include "geometry/subdivision.h"
#include "hierarchy/element_daylight.h"
#include "hierarchy/refine.h"
#include "util/sampling.h"
#include "util/setting_names.h"

namespace radkit {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

/// Largest channel of any node's B: the size the gather's rounding error is relative to.
double maxRadiosity(const SourceState& state) {
  double m = 0;
  for (const Vec3& b : state.radiosity) m = std::max(m, maxComponent(b));
  return m;
}

std::string num(double v) {
  std::ostringstream s;
  s.precision(3);
  s << v;
  return s.str();
}

/// Intermediate rounds only steer refinement: their radiosity need not be closer than this.
constexpr double kRoundTolerance = 1e-3;

/// Leaf elements as patches; vertices are shared within a surface where their coordinates are
/// identical (midpoints of a shared edge are computed from the same two points), so smooth
/// shading can average across element boundaries.
PatchMesh leafMesh(const Hierarchy& h, const std::vector<int>& leaves) {
  PatchMesh mesh;
  const int surfaces = static_cast<int>(h.base().surfaceBegin.size()) - 1;
  mesh.surfaceBegin.assign(surfaces + 1, 0);
  mesh.cullBack = h.base().cullBack;
  struct Key {
    double x, y, z;
    // Bitwise, as Hash is: equal keys must hash alike (== on doubles would merge −0 and 0).
    // NOLINTNEXTLINE(bugprone-suspicious-memory-comparison,cert-exp42-c,cert-flp37-c)
    bool operator==(const Key& o) const { return std::memcmp(this, &o, sizeof(Key)) == 0; }
  };
  struct Hash {
    std::size_t operator()(const Key& k) const {
      std::uint64_t a, b, c;
      std::memcpy(&a, &k.x, 8), std::memcpy(&b, &k.y, 8), std::memcpy(&c, &k.z, 8);
      return a * 0x9e3779b97f4a7c15ULL ^ (b + 0x7f4a7c159e3779b9ULL) * 31 ^ c;
    }
  };
  std::unordered_map<Key, int, Hash> index;
  int current = -1;
  mesh.patches.reserve(leaves.size());
  for (int n : leaves) {
    int s = h.surfaceOf(n);
    if (s != current) index.clear(), current = s;
    const HPolygon poly = h.polygon(n);
    Patch p;
    p.vertexCount = poly.count;
    p.surface = s;
    for (int k = 0; k < poly.count; ++k) {
      Key key{poly.v[k].x, poly.v[k].y, poly.v[k].z};
      auto [it, added] = index.emplace(key, static_cast<int>(mesh.vertices.size()));
      if (added) mesh.vertices.push_back(poly.v[k]);
      p.vertex[k] = it->second;
    }
    p.normal = poly.normal;
    p.centroid = h[n].centre;
    p.area = h[n].area;
    mesh.patches.push_back(p);
    ++mesh.surfaceBegin[s + 1];
  }
  for (int s = 0; s < surfaces; ++s) mesh.surfaceBegin[s + 1] += mesh.surfaceBegin[s];
  return mesh;
}

/// Rays per leaf for the enclosure test and escape estimate; emitters, whose escaping power
/// dominates the estimate's error and which are few, get more.
constexpr int kClosureRays = 32;
/// Light leaving the surfaces, as a multiple of the emitted light, beyond which τ follows it
/// (the Cornell box sends out about 2 times its emission, a furnace at ρ = 0.95 20 times).
constexpr double kAmplification = 10;
constexpr int kEmitterClosureRays = 1024;
/// Share of a surface's rays that may miss for it to count as closed (seams, not openings).
constexpr double kSeamMisses = 1e-3;
/// An emitting leaf casts rays in proportion to its share of the emitted power, up to this
/// many for the whole emission: the escape of a scene whose light comes from one small lamp
/// (mirror-spot: 1 cm²) is then known to about 0.2 %, not 1 %.
constexpr double kEmitterRayBudget = 65536;
constexpr int kMaxEmitterClosureRays = 65536;
int closureRays(const Hierarchy& h, int n, double emitted) {
  const SurfaceRadiometry& r = h.radiometry(n);
  const double e = maxComponent(r.emission);
  if (!(e > 0) || r.daylightOnly) return kClosureRays;
  const double share = emitted > 0 ? e * h[n].area / emitted : 0.0;
  return int(std::clamp(std::ceil(kEmitterRayBudget * share), double(kEmitterClosureRays),
                        double(kMaxEmitterClosureRays)));
}

/// Row-sum targets for the leaves. Each leaf (tested once) casts K stratified,
/// cosine-distributed rays; a ray that misses the front of every face escapes. A surface is
/// closed when almost none of all its leaves' rays escape, so a leaf that sees an opening opens
/// the whole surface (one leaf's K rays can miss a small opening). Leaves of closed surfaces
/// obey Σ_j F_ij = 1 exactly (Siegel & Howell): target 1, which the solve enforces
/// (HierarchicalSystem). Elsewhere no target: a ray estimate of each leaf's row sum was tried
/// (fresh rays where a few escaped) and put 1-3 % too much light on real models, since what
/// the links miss is mostly dim light from nearby clusters and the fill brings the mean light.
/// The same rays estimate each leaf's escape fraction 1 − Σ_j F_ij (the share that misses
/// every face's front), for an energy balance that does not rely on the links.
std::vector<float> closedLeaves(const Hierarchy& h, const RayScene& rays, std::uint64_t seed,
                                std::vector<char>& leafClosed, std::vector<char>& tested,
                                std::vector<float>& escape, std::vector<char>& hidden,
                                std::vector<int>& raysCast, double emitted) {
  leafClosed.resize(h.size(), 0);
  hidden.resize(h.size(), 0);
  tested.resize(h.size(), 0);
  escape.resize(h.size(), 0.0f);
  raysCast.resize(h.size(), 0);
  std::vector<int> todo;
  for (int n = 0; n < h.size(); ++n)
    if (h[n].element && h[n].isLeaf() && !tested[n]) todo.push_back(n);
  const PatchMesh& base = h.base();
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, todo.size(), 64),
      [&](const tbb::blocked_range<std::size_t>& range) {
        std::vector<double> u;
        std::vector<int> scratch;
        for (std::size_t i = range.begin(); i < range.end(); ++i) {
          const int n = todo[i];
          const HPolygon p = h.polygon(n);
          Rng rng(seed, h.key(n), 0x636c6f736564ULL);
          const int K = closureRays(h, n, emitted);
          raysCast[n] = K;
          latinHypercube(K, 4, rng, u, scratch);
          Frame frame(p.normal);
          int misses = 0, backs = 0;
          for (int k = 0; k < K; ++k) {
            const double* q = &u[std::size_t(k) * 4];
            Vec3 x = samplePatchUniform(p.v, p.count, q[0], q[1]) + p.normal * rays.epsilon();
            Vec3 d = frame.toWorld(sampleCosineHemisphere(q[2], q[3]));
            std::optional<RayHit> hit = rays.closestHit(x, d, 0.0);
            const bool front = hit && dot(base.patches[hit->patch].normal, d) < 0;
            misses += !front;
            backs += hit && !front;
          }
          leafClosed[n] = misses == 0;
          hidden[n] =
              backs == K;  // sees only the backs of faces (a floor under a block): nothing sees it
          escape[n] = float(misses) / float(K);
          tested[n] = 1;
        }
      });
  // Rays that slip through the seams between faces (single-precision tests at shared edges)
  // must not open a closed surface: a surface is closed when at most kSeamMisses of its rays
  // miss. An opening that large changes its row sums by at most that much.
  std::vector<double> cast(h.base().surfaceBegin.size(), 0), misses(cast.size(), 0);
  for (int n = 0; n < h.size(); ++n) {
    // A hidden leaf's rays hit the backs of faces enclosing it, not an opening.
    if (!h[n].element || !h[n].isLeaf() || hidden[n]) continue;
    const double K = raysCast[n];
    cast[h.surfaceOf(n)] += K;
    misses[h.surfaceOf(n)] += escape[n] * K;
  }
  std::vector<float> target(h.size(), 0.0f);
  for (int n = 0; n < h.size(); ++n)
    if (h[n].element && h[n].isLeaf() && !hidden[n] &&
        misses[h.surfaceOf(n)] <= kSeamMisses * cast[h.surfaceOf(n)])
      target[n] = 1;
  return target;
}

}  // namespace

GatherOrder parseGatherOrder(const std::string& name) {
  if (name == "jacobi") return GatherOrder::Jacobi;
  if (name == "gauss-seidel") return GatherOrder::GaussSeidel;
  throw std::invalid_argument(setting("gather") + " '" + name +
                              "' is not an ordering: use jacobi or gauss-seidel");
}

void validateHierarchicalSettings(const HierarchicalSettings& s) {
  if (!(s.epsilon >= kMinEpsilon) || s.epsilon >= 1)
    throw std::invalid_argument(setting("epsilon") + " " + num(s.epsilon) +
                                " is not a link error threshold: use a number in [" +
                                num(kMinEpsilon) +
                                ", 1), for example 1e-4 (smaller is more accurate and slower)");
  if (!(s.minArea >= 0) || !std::isfinite(s.minArea))
    throw std::invalid_argument(
        setting("min_area") + " " + num(s.minArea) +
        " is not an area: use a positive area in scene units², or 0 for the default");
  if (s.raysPerLink < 1 || s.raysPerLink > 4096)
    throw std::invalid_argument(setting("hr_rays") + " " + std::to_string(s.raysPerLink) +
                                " must be between 1 and 4096 (default 16)");
  if (s.rounds < 1 || s.rounds > 8)
    throw std::invalid_argument(setting("hr_rounds") + " " + std::to_string(s.rounds) +
                                " must be between 1 and 8 (default 3)");
  if (!(s.stopping.tolerance > 0) || !std::isfinite(s.stopping.tolerance))
    throw std::invalid_argument(setting("tol") + " " + num(s.stopping.tolerance) +
                                " must be a positive number, e.g. 1e-6");
}

std::size_t defaultHierarchicalMemoryBudget() {
  const std::size_t machine = availableMachineMemory();
  return machine > 0 ? machine / 4 * 3 : std::size_t(8) << 30;
}

HierarchicalResult solveHierarchical(const Scene& scene, const HierarchicalSettings& settings,
                                     const PipelineLog& log) {
  std::vector<SurfaceRadiometry> radiometry;
  for (const Surface& s : scene.surfaces) {
    const Material& m = scene.materials[s.material];
    radiometry.push_back({m.diffuseAlbedo(), m.emission});
  }
  validateHierarchicalSettings(settings);
  Clock::time_point start = Clock::now();
  PatchMesh base = subdivide(scene, SubdivisionSettings{});
  double meshSeconds = since(start);
  std::vector<StageMemory> memory;
  markStageMemory(memory, "input faces");
  // With a sky, daylight is estimated on every leaf element by default (the solve below), so
  // refinement follows sun shadow edges inside large faces. Per input face instead
  // (settings.elementDaylight false), it is constant over each face's elements and a sunlit
  // scene wants faces no larger than the shadow detail it should show (docs/daylight.md).
  std::unique_ptr<SkyModel> sky;
  std::unique_ptr<Daylight> daylight;
  std::vector<Vec3> faceDaylight;
  double daylightSeconds = 0;
  const bool perElement = scene.sky && settings.elementDaylight;
  if (scene.sky) {
    start = Clock::now();
    sky = std::make_unique<SkyModel>(*scene.sky);
    if (!perElement) {
      const RayScene rays(base);
      daylight = std::make_unique<Daylight>(computeDaylight(base, rays, *sky, settings.seed));
      for (int f = 0; f < base.size(); ++f) faceDaylight.push_back(daylight->total(f));
      if (log.progress) log.progress("daylight", 1.0);
      markStageMemory(memory, "daylight");
    }
    daylightSeconds = since(start);
  }
  HierarchicalResult r = solveHierarchical(std::move(base), std::move(radiometry), settings, log,
                                           scene.sky && !perElement ? &faceDaylight : nullptr,
                                           perElement ? sky.get() : nullptr);
  r.memory.insert(r.memory.begin(), memory.begin(), memory.end());
  r.seconds.inputFaces = meshSeconds;
  r.seconds.daylight += daylightSeconds;
  start = Clock::now();
  std::vector<int> leafFace(r.leaves.size());
  for (int i = 0; i < r.leaves.size(); ++i) leafFace[i] = (*r.hierarchy)[r.leafNodes[i]].face;
  if (perElement) daylight = std::move(r.daylight);
  // The daylight arriving at leaf i: its own (per element) or its input face's.
  auto leafDaylight = [&](int i) {
    return perElement ? daylight->total(i) : faceDaylight[leafFace[i]];
  };
  if (daylight)
    for (int i = 0; i < r.leaves.size(); ++i) r.irradiance[i] += leafDaylight(i);
  r.surfaces = surfaceResults(scene, r.leaves, r.radiosity, r.irradiance);
  {
    std::vector<double> area(scene.surfaces.size(), 0.0);
    r.zeroIrradianceShare.assign(scene.surfaces.size(), 0.0);
    for (int i = 0; i < r.leaves.size(); ++i) {
      const Patch& p = r.leaves.patches[i];
      area[p.surface] += p.area;
      if (!(maxComponent(r.irradiance[i]) > 0)) r.zeroIrradianceShare[p.surface] += p.area;
    }
    for (std::size_t k = 0; k < area.size(); ++k)
      if (area[k] > 0) r.zeroIrradianceShare[k] /= area[k];
  }
  if (daylight)
    addDaylightToSurfaces(r.leaves, *daylight, r.surfaces, perElement ? nullptr : &leafFace);
  // Power bookkeeping as for a dense run, with each leaf's escape fraction measured by rays
  // rather than taken from the links (an emitter, ρ = 0, gathers through coarse links that
  // need not add up), so the balance checks the links' transport independently.
  const double m2 = scene.metresPerUnit() * scene.metresPerUnit();
  EnergyBalance& e = r.energy;
  Vec3 variance;
  for (int i = 0; i < r.leaves.size(); ++i) {
    const Patch& p = r.leaves.patches[i];
    const Material& m = scene.materials[scene.surfaces[p.surface].material];
    double a = p.area * m2, q = r.escape[i];
    e.emitted += m.emission * a;
    if (daylight) e.emitted += leafDaylight(i) * a;  // the light the scene takes in
    e.absorbed += mul(Vec3{1, 1, 1} - m.diffuseAlbedo(), r.irradiance[i]) * a;
    e.escaped += r.radiosity[i] * (a * q);
    Vec3 power = r.radiosity[i] * a;
    const double K = r.escapeRays[i];
    variance += mul(power, power) * (std::max(q * (1 - q), 0.25 / K) / K);
  }
  r.escapedStandardError = {std::sqrt(variance.x), std::sqrt(variance.y), std::sqrt(variance.z)};
  for (int c = 0; c < 3; ++c)
    if (e.emitted[c] > 0)
      e.relativeImbalance =
          std::max(e.relativeImbalance,
                   std::fabs(e.emitted[c] - e.absorbed[c] - e.escaped[c]) / e.emitted[c]);
  r.seconds.results += since(start);
  r.sky = std::move(sky);
  r.daylight = std::move(daylight);
  return r;
}

HierarchicalResult solveHierarchical(PatchMesh base, std::vector<SurfaceRadiometry> surfaces,
                                     const HierarchicalSettings& settings, const PipelineLog& log,
                                     const std::vector<Vec3>* daylight, const SkyModel* sky) {
  validateHierarchicalSettings(settings);
  const bool perElement = sky != nullptr && settings.elementDaylight;
  const bool byFace = daylight != nullptr && !perElement;
  if (byFace) {
    std::vector<SurfaceRadiometry> perFace;
    perFace.reserve(base.size());
    for (int f = 0; f < base.size(); ++f) {
      const SurfaceRadiometry& s = surfaces[base.patches[f].surface];
      perFace.push_back({s.reflectance, s.emission + mul(s.reflectance, (*daylight)[f]),
                         !(maxComponent(s.emission) > 0)});
    }
    surfaces = std::move(perFace);
  }
  HierarchicalResult r;
  auto say = [&](const std::string& line) {
    if (log.message) log.message(line);
  };
  double totalArea = 0, emitted = 0, emissionNorm = 0;
  for (int f = 0; f < base.size(); ++f) {
    const Patch& p = base.patches[f];
    const SurfaceRadiometry& s = surfaces[byFace ? f : p.surface];
    totalArea += p.area;
    emitted += p.area * maxComponent(s.emission);
    emissionNorm = std::max(emissionNorm, maxComponent(s.emission));
  }
  const char* const noDaylight =
      "no light enters the scene: the sky and sun reach no surface that reflects";
  if (!(emitted > 0) && !perElement)
    throw std::invalid_argument(
        byFace ? noDaylight
               : "the scene emits no light: give at least one material an \"emission\" above 0");
  r.minArea = settings.minArea > 0 ? settings.minArea : kDefaultMinAreaFraction * totalArea;
  if (r.minArea > totalArea)
    throw std::invalid_argument(
        setting("min_area") + " " + num(r.minArea) + " is larger than the whole scene (" +
        num(totalArea) + " scene units²): use at most " + num(totalArea * 1e-3) +
        ", or 0 for the default (" + num(kDefaultMinAreaFraction) + " of the scene's area)");

  Clock::time_point t = Clock::now();
  const int faces = base.size();
  r.hierarchy = std::make_unique<Hierarchy>(std::move(base), std::move(surfaces), byFace);
  Hierarchy& h = *r.hierarchy;
  r.seconds.hierarchy = since(t);
  markStageMemory(r.memory, "hierarchy");
  say("hierarchy: " + std::to_string(faces) + " input faces, " + std::to_string(h.size()) +
      " nodes, " + num(r.seconds.hierarchy) + " s");
  t = Clock::now();
  r.rays = std::make_unique<RayScene>(h.base());
  r.seconds.rayScene = since(t);
  markStageMemory(r.memory, "ray scene");
  // Daylight per element: the input faces' first, which set the emitted power (τ) as the
  // faces' own daylight does per face.
  std::unique_ptr<ElementDaylight> elementDaylight;
  if (perElement) {
    elementDaylight = std::make_unique<ElementDaylight>(*r.rays, *sky, settings.seed);
    elementDaylight->sampleNewLeaves(h);
    emitted = 0;
    emissionNorm = 0;
    for (int f = 0; f < faces; ++f) {
      const double e = maxComponent(elementDaylight->emission()[h.faceNode(f)]);
      emitted += h.base().patches[f].area * e;
      emissionNorm = std::max(emissionNorm, e);
    }
    if (log.progress) log.progress("daylight", 1.0);
    markStageMemory(r.memory, "daylight");
    if (!(emitted > 0)) throw std::invalid_argument(noDaylight);
  }

  // Start from B = E at the input faces.
  SourceState& state = r.state;
  state.radiosity.resize(h.size());
  state.powerVector.resize(h.clusterCount());
  state.radiosityMin.resize(h.size());
  state.radiosityMax.resize(h.size());
  for (int n = 0; n < h.size(); ++n)
    if (h[n].element)
      state.radiosity[n] =
          elementDaylight ? elementDaylight->emission()[n] : h.radiometry(n).emission;

  RefineSettings rs;
  rs.minArea = r.minArea;
  rs.raysPerLink = settings.raysPerLink;
  rs.seed = settings.seed;
  rs.memoryBudget = settings.memoryBudget;
  // The input mesh (twice: ours and Embree's, ~ 64 B per triangle in its BVH) stays resident.
  rs.fixedBytes = std::size_t(faces) * (sizeof(Patch) + 3 * sizeof(Vec3) + 64);
  std::vector<HLink> links;
  std::vector<char> leafClosed, tested;
  std::vector<float> escape;
  std::vector<char> hidden;
  std::vector<int> escapeRays;
  r.solve.solver = "hierarchical";
  r.solve.description = std::string("hierarchical radiosity with clustering, ") +
                        (settings.order == GatherOrder::Jacobi ? "Jacobi" : "Gauss-Seidel") +
                        " gather, push-pull, epsilon " + num(settings.epsilon) + ", min area " +
                        num(r.minArea) + ", K=" + std::to_string(settings.raysPerLink) +
                        " rays per link, seed " + std::to_string(settings.seed);
  Clock::time_point solveStart = Clock::now();
  long iteration = 0;
  // The dense solvers' rules (solvers/solver.h): exit reasons, a spectral-radius estimate,
  // stagnation at the rounding floor and a history decimated so it stays bounded.
  ConvergenceMonitor monitor;
  monitor.startResidual = std::numeric_limits<double>::min();
  HistoryRow lastRow;
  bool lastKept = true;  // the decimated history must still end with the last sweep
  auto stop = [&](const std::string& exit, const std::string& reason) {
    r.solve.exit = exit;
    r.solve.reason = reason;
    if (!lastKept) r.solve.history.push_back(lastRow), lastKept = true;
  };
  double amplification = 1;  // light leaving the surfaces over light emitted, from the last solve
  for (int round = 0; round < settings.rounds; ++round) {
    HierarchicalRound info;
    info.epsilon = settings.epsilon * std::pow(4.0, settings.rounds - 1 - round);
    // τ is a share of the emitted power. Where the surfaces send out far more than that (a
    // closed box at ρ = 0.999999 sends out 10⁶ times its emission) every link's error grows
    // with B and refinement would run until memory ran out: τ follows the light leaving the
    // surfaces once it exceeds kAmplification times the emission.
    rs.threshold = info.epsilon * emitted * std::max(1.0, amplification / kAmplification);
    rs.round = round;
    rs.last = round + 1 == settings.rounds;
    t = Clock::now();
    Refiner refiner(h, *r.rays, rs);
    if (links.empty()) {
      pull(h, state);
      links = refiner.rootLinks();
    }
    // Progress: the share of the candidates known so far that are settled (new candidates
    // appear as links split, so it can step back).
    RefineStats stats = refiner.refine(links, state, [&](long long settled, long long pending) {
      if (log.progress)
        log.progress("links, epsilon " + num(info.epsilon),
                     double(settled) / double(settled + pending));
    });
    // New leaves get daylight of their own, and leaves whose daylight varies across them (a sun
    // shadow edge) are split while that variation is above τ.
    double daylightSeconds = 0;
    if (elementDaylight) {
      const double before = elementDaylight->seconds();
      elementDaylight->refine(h, rs.threshold, r.minArea);
      growState(h, state);
      daylightSeconds = elementDaylight->seconds() - before;
    }
    // After the last refinement every source's light is known: links still kept blocked for a
    // dark source carry nothing.
    if (round + 1 == settings.rounds)
      links.erase(std::remove_if(links.begin(), links.end(),
                                 [](const HLink& l) { return !(l.visibility > 0); }),
                  links.end());
    std::vector<float> closed = closedLeaves(h, *r.rays, settings.seed, leafClosed, tested, escape,
                                             hidden, escapeRays, emitted);
    r.system.reset();
    r.system = std::make_unique<HierarchicalSystem>(h, std::move(links), settings.order, state,
                                                    closed, hidden);
    if (elementDaylight) r.system->setEmission(&elementDaylight->emission());
    links.clear();  // moved from; the next round starts from the system's links
    r.system->setVisibleArea(state);
    pull(h, state);
    info.refineSeconds = since(t) - daylightSeconds;
    info.rays = stats.rays;
    info.links = static_cast<long long>(r.system->links().size());
    info.nodes = h.size();
    r.raysCast += stats.rays;

    t = Clock::now();
    const bool last = round + 1 == settings.rounds;
    const double tolerance =
        last ? settings.stopping.tolerance : std::max(settings.stopping.tolerance, kRoundTolerance);
    const long maxSweeps = last ? settings.stopping.maxIterations : 1000;
    // New links, a new system: its rate is measured afresh.
    monitor.restart(double(iteration), since(solveStart));
    for (long sweep = 0;; ++sweep) {
      const std::string after = " after " + std::to_string(iteration) + " sweeps";
      if (sweep >= maxSweeps) {
        if (last)
          stop("max_iterations", "not converged: maximum iterations (" + std::to_string(maxSweeps) +
                                     ") reached with change " + num(r.solve.residual) +
                                     " > tolerance " + num(tolerance) + monitor.rateText());
        break;
      }
      if (since(solveStart) >= settings.stopping.maxSeconds) {
        stop("time_limit", "not converged: time limit " + num(settings.stopping.maxSeconds) +
                               " s reached" + after + " with change " + num(r.solve.residual) +
                               monitor.rateText());
        break;
      }
      HierarchicalSystem::Change c = r.system->sweep(state);
      ++iteration, ++info.sweeps;
      const double residual = c.max / emissionNorm;
      r.solve.residual = residual;
      const double seconds = since(solveStart);
      monitor.update(residual, double(iteration), seconds);
      lastRow = {iteration, seconds, residual, c.power, double(iteration)};
      if (log.progress)
        log.progress("solve, epsilon " + num(info.epsilon),
                     std::clamp(std::log(residual) / std::log(tolerance), 0.0, 1.0));
      if (!std::isfinite(residual) || residual > 1e12) {
        stop("diverged", "diverged: the change grew to " + num(residual) + " after " +
                             std::to_string(iteration) + " sweeps" + monitor.rateText());
      } else if (residual <= tolerance) {
        if (last) r.solve.converged = true, stop("converged", "converged");
      } else if (iteration - monitor.bestSweeps >= kStagnationSweeps &&
                 monitor.stagnated(double(iteration), maxRadiosity(state) / emissionNorm)) {
        stop("stagnated", "stagnated: no change below " + num(monitor.best) + " for " +
                              num(kStagnationSweeps) + " sweeps" + " after " +
                              std::to_string(iteration) + " sweeps" + monitor.rateText() +
                              " (rounding error: tolerance " + num(tolerance) +
                              " is below what this system reaches; raise " + setting("tol") + ")");
      } else if (last && monitor.overBudget(residual, tolerance, double(maxSweeps - sweep - 1),
                                            settings.stopping.maxSeconds - seconds)) {
        // Only the last round: the earlier ones are capped at 1000 sweeps anyway, and their
        // light steers the next round's threshold.
        r.solve.predictedSweeps = monitor.predicted;
        stop("predicted_over_budget",
             monitor.overBudgetText(residual, tolerance, settings.stopping, iteration));
      }
      const bool done = residual <= tolerance || !r.solve.exit.empty();
      lastKept = monitor.keep(iteration, residual) || done;
      if (lastKept) r.solve.history.push_back(lastRow);
      if (done) break;
    }
    info.solveSeconds = since(t);
    r.seconds.refine += info.refineSeconds;
    r.seconds.solve += info.solveSeconds;
    {
      double leaving = 0;
      for (int n = 0; n < h.size(); ++n)
        if (h[n].isLeaf() && h[n].element) leaving += h[n].area * maxComponent(state.radiosity[n]);
      amplification = leaving / emitted;
    }
    r.rounds.push_back(info);
    say("hierarchy: epsilon " + num(info.epsilon) + ", " + std::to_string(info.links) + " links, " +
        std::to_string(info.nodes) + " nodes, " + std::to_string(info.rays) + " rays, " +
        std::to_string(info.sweeps) + " sweeps, " + num(info.refineSeconds + info.solveSeconds) +
        " s");
    if (r.solve.exit == "diverged" || r.solve.exit == "stagnated" || r.solve.exit == "time_limit")
      break;
    if (round + 1 < settings.rounds) {
      // The next round refines these links; the system's per-node arrays go before it does.
      links = r.system->releaseLinks();
      r.system.reset();
    }
  }
  r.threshold = rs.threshold;  // the last round's
  r.solve.iterations = iteration;
  r.solve.seconds = since(solveStart);
  r.solve.residual = r.solve.history.empty() ? 0 : r.solve.history.back().residual;
  r.solve.checkedResidual = r.solve.residual;
  r.solve.spectralRadius = monitor.rate;
  markStageMemory(r.memory, "links and solve");

  t = Clock::now();
  r.leafNodes = h.leavesByFace();
  const std::size_t leaves = r.leafNodes.size();
  std::vector<Vec3> nodeH = r.system->leafIrradiance(state);
  r.rowSums.reserve(leaves);
  for (int n : r.leafNodes) r.rowSums.push_back(r.system->rowSum(n));
  const std::size_t linkBytes = r.system->bytes();
  // The outputs need the links themselves only; the gather's arrays go before the leaves'
  // results and mesh are made.
  if (!settings.keepGatherArrays) r.system->releaseGatherArrays();
  r.irradiance.reserve(leaves);
  for (int n : r.leafNodes) r.irradiance.push_back(nodeH[n]);
  std::vector<Vec3>().swap(nodeH);
  r.radiosity.reserve(leaves), r.escape.reserve(leaves), r.escapeRays.reserve(leaves);
  for (int n : r.leafNodes) {
    r.radiosity.push_back(state.radiosity[n]);
    r.escape.push_back(escape[n]);
    r.escapeRays.push_back(escapeRays[n]);
  }
  r.leaves = leafMesh(h, r.leafNodes);
  for (const HLink& l : r.system->links()) ++r.linksByKind[static_cast<int>(linkKind(h, l))];
  if (elementDaylight) {
    r.daylight = std::make_unique<Daylight>(elementDaylight->leafDaylight(h, r.leafNodes));
    r.daylightPerLeaf = true;
    r.daylightSplits = elementDaylight->splits();
    r.daylightElements = elementDaylight->sampled();
    r.seconds.daylight = elementDaylight->seconds();
    elementDaylight.reset();  // it casts its rays in r.rays
  }
  if (!settings.keepGatherArrays) r.rays.reset();
  r.hierarchyBytes = h.bytes() + state.radiosity.capacity() * sizeof(Vec3) +
                     state.powerVector.capacity() * sizeof(state.powerVector[0]) +
                     (state.radiosityMin.capacity() + state.radiosityMax.capacity() +
                      state.visibleArea.capacity()) *
                         sizeof(double);
  r.linkBytes = linkBytes;
  for (int c = 0; c < 3; ++c) {
    r.solve.radiosity[c].resize(r.radiosity.size());
    for (std::size_t i = 0; i < r.radiosity.size(); ++i)
      r.solve.radiosity[c][i] = r.radiosity[i][c];
  }
  r.seconds.results = since(t);
  markStageMemory(r.memory, "results");
  return r;
}

}  // namespace radkit
