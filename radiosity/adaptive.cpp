#include "radiosity/adaptive.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>

#include "daylight/sky.h"
#include "geometry/refine.h"
#include "util/format.h"

namespace radkit {

namespace {

const Material& materialOf(const Scene& scene, const PatchMesh& mesh, int i) {
  return scene.materials[scene.surfaces[mesh.patches[i].surface].material];
}

/// Points on the emitters (corners pulled toward their patch centroid, and centroids), with
/// their normals, at most `perSurface` per emitting surface, spread evenly over the list.
void emitterPoints(const Scene& scene, const PatchMesh& mesh, int perSurface,
                   std::vector<Vec3>& points, std::vector<Vec3>& normals) {
  for (std::size_t s = 0; s < scene.surfaces.size(); ++s) {
    if (!scene.materials[scene.surfaces[s].material].emits()) continue;
    std::vector<Vec3> candidates, candidateNormals;
    for (int i = mesh.surfaceBegin[s]; i < mesh.surfaceBegin[s + 1]; ++i) {
      const Patch& p = mesh.patches[i];
      candidates.push_back(p.centroid);
      for (int k = 0; k < p.vertexCount; ++k)
        candidates.push_back(mesh.vertex(p, k) + (p.centroid - mesh.vertex(p, k)) * 1e-3);
      candidateNormals.insert(candidateNormals.end(), p.vertexCount + 1, p.normal);
    }
    int take = std::min<int>(perSurface, int(candidates.size()));
    for (int k = 0; k < take; ++k) {
      std::size_t pick = std::size_t(k) * candidates.size() / take;
      points.push_back(candidates[pick]);
      normals.push_back(candidateNormals[pick]);
    }
  }
}

/// Which patches to split: the largest indicators above tolerance, within the budget and the
/// per-round fraction, never below the minimum area. Returns the count.
int choosePatches(const PatchMesh& mesh, const std::vector<double>& indicator,
                  const AdaptiveSettings& a, std::vector<char>& split) {
  std::vector<int> order(mesh.patches.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int x, int y) { return indicator[x] > indicator[y]; });
  double minArea = a.minAreaFraction * mesh.totalArea();
  int room = (a.maxPatches - mesh.size()) / 3;  // each split adds three patches
  int cap = std::min(room, std::max(1, int(a.splitFraction * mesh.size())));
  split.assign(mesh.patches.size(), 0);
  int count = 0;
  for (int i : order) {
    if (count >= cap || indicator[i] <= a.tolerance) break;
    if (mesh.patches[i].area < 4 * minArea) continue;
    split[i] = 1;
    ++count;
  }
  return count;
}

}  // namespace

std::vector<double> refinementIndicator(const Scene& scene, const PatchMesh& mesh,
                                        const std::vector<Vec3>& radiosity,
                                        const std::vector<char>& shadowed) {
  std::vector<std::vector<int>> nb = surfaceNeighbours(mesh);
  double power = 0;  // Σ A_k Y(B_k): the scale the indicator is relative to
  for (int i = 0; i < mesh.size(); ++i) power += mesh.patches[i].area * luminance(radiosity[i]);
  std::vector<double> ind(mesh.patches.size(), 0.0);
  if (!(power > 0)) return ind;
  for (int i = 0; i < mesh.size(); ++i) {
    if (materialOf(scene, mesh, i).emits()) continue;
    double y = luminance(radiosity[i]), delta = 0;
    for (int j : nb[i]) delta = std::max(delta, std::fabs(y - luminance(radiosity[j])));
    if (!shadowed.empty() && shadowed[i]) delta = std::max(delta, y);
    ind[i] = mesh.patches[i].area * delta / power;
  }
  return ind;
}

std::vector<char> shadowBoundaryPatches(const Scene& scene, const PatchMesh& mesh,
                                        const Visibility& visibility, int perSurface,
                                        const SkyModel* sky) {
  const bool sun = sky && sky->hasSun();
  const Vec3 sunDirection = sun ? sky->sunDirection() : Vec3{0, 0, 1};
  std::vector<Vec3> points, normals;
  emitterPoints(scene, mesh, perSurface, points, normals);
  std::vector<char> shadowed(mesh.patches.size(), 0);
  tbb::parallel_for(0, mesh.size(), [&](int i) {
    if (materialOf(scene, mesh, i).emits()) return;
    const Patch& p = mesh.patches[i];
    for (std::size_t q = 0; q < points.size() && !shadowed[i]; ++q) {
      if (dot(points[q] - p.centroid, p.normal) <= 0) continue;  // behind the patch
      int seen = 0;
      for (int k = 0; k < p.vertexCount; ++k) {
        Vec3 corner = mesh.vertex(p, k) + (p.centroid - mesh.vertex(p, k)) * 1e-3;
        seen += !visibility.occluded(corner, p.normal, points[q], normals[q]);
      }
      shadowed[i] = seen > 0 && seen < p.vertexCount;
    }
    if (sun && !shadowed[i] && dot(sunDirection, p.normal) > 0) {
      // The sun's shadow edges: corners that disagree on a clear line to the sun's centre.
      int seen = 0;
      for (int k = 0; k < p.vertexCount; ++k) {
        const Vec3 corner = mesh.vertex(p, k) + (p.centroid - mesh.vertex(p, k)) * 1e-3;
        seen += !visibility.closestHit(corner + p.normal * visibility.epsilon(), sunDirection, 0);
      }
      shadowed[i] = seen > 0 && seen < p.vertexCount;
    }
  });
  return shadowed;
}

AdaptiveResult solveAdaptive(const Scene& scene, const PipelineSettings& settings,
                             const AdaptiveSettings& adaptive, const PipelineLog& log) {
  auto start = Clock::now();
  AdaptiveResult r;
  auto t = Clock::now();
  PatchMesh mesh = subdivide(scene, settings.mesh);
  double meshSeconds = secondsSince(t);
  for (int round = 0;; ++round) {
    AdaptiveRound info;
    info.patches = mesh.size();
    info.seconds.mesh = meshSeconds;
    PipelineSettings one = settings;
    if (!one.solvers.empty()) one.solvers.resize(1);  // the first solver solves each round
    PipelineResult m = runPipeline(scene, mesh, one, log);
    info.seconds = m.seconds;
    info.seconds.mesh = meshSeconds;
    t = Clock::now();
    std::vector<char> shadowed;
    if (adaptive.shadowBoundaries)
      shadowed = shadowBoundaryPatches(scene, mesh, *m.rays, adaptive.emitterPoints, m.sky.get());
    info.shadowPatches = int(std::count(shadowed.begin(), shadowed.end(), 1));
    std::vector<double> ind = refinementIndicator(scene, mesh, m.radiosity, shadowed);
    info.maxIndicator = ind.empty() ? 0 : *std::max_element(ind.begin(), ind.end());
    std::vector<char> split;
    int count = round < adaptive.maxRounds ? choosePatches(mesh, ind, adaptive, split) : 0;
    r.stopReason = round >= adaptive.maxRounds               ? "maximum rounds reached"
                   : info.maxIndicator <= adaptive.tolerance ? "indicator below tolerance"
                   : count == 0 ? "patch budget or minimum area reached"
                                : "";
    info.split = count;
    if (log.message)
      log.message("adaptive round " + std::to_string(round) + ": " + std::to_string(info.patches) +
                  " patches, " + std::to_string(info.shadowPatches) +
                  " on shadow boundaries, max indicator " + std::to_string(info.maxIndicator) +
                  ", splitting " + std::to_string(count));
    if (count == 0) {
      r.final = std::move(m);
      r.rounds.push_back(info);
      break;
    }
    mesh = refinePatches(mesh, split).mesh;
    meshSeconds = secondsSince(t);
    r.rounds.push_back(info);
  }
  r.seconds = secondsSince(start);
  return r;
}

}  // namespace radkit
