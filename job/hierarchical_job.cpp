// runJob for the hierarchical method: the cluster tree, its links and the gather, and a run's
// outputs with the leaves as patches, plus links.png (and links_check.csv when asked).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <optional>

#include "hierarchy/link_check.h"
#include "hierarchy/link_matrix.h"
#include "hierarchy/refine.h"
#include "job/job_parts.h"
#include "job/report.h"
#include "output/run_files.h"
#include "radiosity/presets.h"
#include "render/hdr_io.h"
#include "render/radiosity_image.h"
#include "util/format.h"
#include "util/output_folder.h"
#include "util/process_memory.h"
#include "util/setting_names.h"

namespace radkit {

namespace {

/// Energy imbalance above which a hierarchical run warns (beyond 4 standard errors).
constexpr double kImbalanceWarning = 0.005;
/// Input-face aspect ratio (longest edge² over area) beyond which the imbalance warning
/// names the face.
constexpr double kSliverAspect = 100;
/// Share of a surface's area without any light above which a hierarchical run warns.
constexpr double kDarkShareWarning = 0.25;

nlohmann::json hierarchyJson(const Scene& scene, const HierarchicalResult& r,
                             const HierarchicalSettings& s) {
  nlohmann::json zeroShares = nlohmann::json::object();
  for (std::size_t k = 0; k < scene.surfaces.size(); ++k)
    if (r.zeroIrradianceShare[k] > 0) zeroShares[scene.surfaces[k].name] = r.zeroIrradianceShare[k];
  const Hierarchy& h = *r.hierarchy;
  long long clusters = 0, elements = 0;
  int deepest = 0;
  for (int n = 0; n < h.size(); ++n) {
    if (h[n].element) {
      ++elements;
      deepest = std::max(deepest, int(h[n].level));
    } else {
      ++clusters;
    }
  }
  nlohmann::json kinds;
  long long total = 0;
  for (int k = 0; k < 4; ++k) {
    kinds[linkKindName(static_cast<LinkKind>(k))] = r.linksByKind[k];
    total += r.linksByKind[k];
  }
  nlohmann::json rounds = nlohmann::json::array();
  for (const HierarchicalRound& round : r.rounds)
    rounds.push_back({{"epsilon", round.epsilon},
                      {"links", round.links},
                      {"nodes", round.nodes},
                      {"rays", round.rays},
                      {"sweeps", round.sweeps},
                      {"refine_seconds", round.refineSeconds},
                      {"solve_seconds", round.solveSeconds}});
  double rowMin = INFINITY, rowMax = 0;
  for (double v : r.rowSums) rowMin = std::min(rowMin, v), rowMax = std::max(rowMax, v);
  return {{"epsilon", s.epsilon},
          {"threshold_power", r.threshold},
          {"min_area", r.minArea},
          {"rays_per_link", s.raysPerLink},
          {"gather", s.order == GatherOrder::Jacobi ? "jacobi" : "gauss-seidel"},
          {"input_faces", h.base().size()},
          {"nodes", h.size()},
          {"clusters", clusters},
          {"elements", elements},
          {"leaves", r.leaves.size()},
          {"deepest_element_level", deepest},
          {"links", total},
          {"links_by_kind", kinds},
          {"rays", r.raysCast},
          {"row_sum_min", rowMin},
          {"row_sum_max", rowMax},
          {"row_sum_largest_error_before_scaling", r.system->largestRowSumError()},
          {"leaves_closed_row_sum_normalised", r.system->normalisedLeaves()},
          {"leaves_open_row_sum_capped", r.system->clampedLeaves()},
          {"leaves_row_sum_target_not_met", r.system->unnormalisedClosedLeaves()},
          {"zero_irradiance_area_share", zeroShares},
          {"cluster_link_landings", r.system->landings()},
          {"cluster_link_landings_estimated", r.system->approximateLandings()},
          {"hierarchy_bytes", r.hierarchyBytes},
          {"link_bytes", r.linkBytes},
          {"memory_budget_bytes", s.memoryBudget},
          {"daylight_per", r.sky ? (r.daylightPerLeaf ? "element" : "face") : "none"},
          {"elements_daylit", r.daylightElements},
          {"elements_split_for_daylight", r.daylightSplits},
          {"rounds", rounds}};
}

/// report.json's "memory": per stage what the process held after it and the peak so far, and
/// the run's peak per input face (the figure that decides how large a scene fits a machine).
nlohmann::json memoryJson(const std::vector<StageMemory>& stages, std::size_t inputFaces) {
  nlohmann::json list = nlohmann::json::array();
  for (const StageMemory& m : stages)
    list.push_back({{"stage", m.stage}, {"resident_bytes", m.resident}, {"peak_bytes", m.peak}});
  const std::size_t peak = stages.empty() ? 0 : stages.back().peak;
  return {
      {"stages", list},
      {"input_faces", inputFaces},
      {"peak_bytes_per_input_face", double(peak) / double(std::max<std::size_t>(1, inputFaces))}};
}

void renderLeaves(OutputFolder& folder, const Scene& scene, const HierarchicalResult& r,
                  const JobSettings& job, const PipelineLog& log) {
  ImageSettings s;
  s.width = job.imageWidth, s.height = job.imageHeight;
  s.smooth = true;          // leaves differ in size by orders of magnitude: flat shading shows the
                            // hierarchy, not the light
  s.samplesPerAxis = 4;     // 16 per pixel: leaves along a shadow edge are far smaller than a
                            // pixel, and 4 alias the edge (render.pfm against a path tracer)
  RayScene rays(r.leaves);  // the image needs the leaf under each pixel
  if (r.sky) s.background = [&](const Vec3& d) { return r.sky->radiance(d); };
  // render.pfm: the same image in linear radiance, for `radkit render --reference` (the path
  // tracer's per-surface errors against this solution).
  const RadianceImage image = renderRadiosity(r.leaves, rays, sceneCamera(scene, r.leaves),
                                              r.radiosity, scene.twoSidedSurfaces(), s);
  writePng(folder.path("render.png"), toneMap(image, autoExposure(image, scene, r.leaves)));
  writePfm(folder.path("render.pfm"), image);
  if (!(image.meanRadiance() > 0) && log.message)
    log.message("warning: " + blackPictureWarning("render.png"));
}

/// Checks a user should see: light that went missing, and surfaces left dark.
std::vector<std::string> hierarchicalWarnings(const Scene& scene, const HierarchicalResult& r) {
  std::vector<std::string> out;
  // Share of each non-emitting surface's area whose leaves received no light at all (exactly
  // 0: no link delivers any). A floor under a block has some; a model wound inward, or faces
  // the links never reached, have most of theirs so.
  std::string darkList;
  for (std::size_t k = 0; k < scene.surfaces.size(); ++k) {
    const Material& m = scene.materials[scene.surfaces[k].material];
    if (maxComponent(m.emission) > 0 || r.zeroIrradianceShare[k] < kDarkShareWarning) continue;
    darkList += (darkList.empty() ? "" : ", ") +
                ("\"" + scene.surfaces[k].name + "\" " +
                 formatValue("%.0f", 100 * r.zeroIrradianceShare[k]) + " %");
  }
  if (!darkList.empty())
    out.push_back(scene.file + ": no light at all reached " + darkList +
                  " of the area. If these surfaces should be lit, check that their faces point "
                  "toward the light (a mesh wound inward needs \"reverse\": true)");
  const double se =
      maxComponent(r.escapedStandardError) / std::max(1e-300, maxComponent(r.energy.emitted));
  if (r.energy.relativeImbalance > std::max(kImbalanceWarning, 4 * se)) {
    // Elements split into quarters keep their face's shape: a sliver stays a sliver.
    const PatchMesh& base = r.hierarchy->base();
    double aspect = 0;
    int worst = -1;
    for (int f = 0; f < base.size(); ++f)
      if (const double a = base.aspectRatio(base.patches[f]); a > aspect) aspect = a, worst = f;
    const std::string sliver =
        aspect > kSliverAspect
            ? " Input faces as elongated as \"" + scene.surfaces[base.patches[worst].surface].name +
                  "\"'s (aspect ratio " + formatValue("%.3g", aspect) +
                  ") stay so when split, and their light is not resolved: split them in the "
                  "scene into pieces no longer than a few times their width."
            : "";
    out.push_back(scene.file + ": the energy balance is off by " +
                  formatValue("%.2g", 100 * r.energy.relativeImbalance) +
                  " % (the escape estimate's standard error is " + formatValue("%.2g", 100 * se) +
                  " %): the links lose or add light. Fix: lower " + setting("epsilon") +
                  ", or raise " + setting("hr_rays") + "." + sliver);
  }
  return out;
}

}  // namespace

JobResult runHierarchicalJob(Scene loadedScene, const LoadReport& loaded, const JobSettings& job,
                             const PipelineLog& log, std::chrono::steady_clock::time_point start,
                             double loadSeconds) {
  JobResult result;
  result.method = JobMethod::Hierarchical;
  result.scene = std::move(loadedScene);
  Scene& scene = result.scene;
  addBackSides(scene);  // two-sided surfaces exchange light on both sides
  result.out = job.out.empty() ? defaultOutFolder(scene.name) : job.out;
  OutputFolder folder(result.out);  // refuses a folder it cannot replace before the work
  std::vector<StageMemory> loadMemory;
  markStageMemory(loadMemory, "load");  // the scene read and checked
  result.hierarchical =
      std::make_unique<HierarchicalResult>(solveHierarchical(scene, job.hierarchical, log));
  HierarchicalResult& r = *result.hierarchical;
  const auto solved = std::chrono::steady_clock::now();
  r.memory.insert(r.memory.begin(), loadMemory.begin(), loadMemory.end());
  if (log.message)
    for (const std::string& w : hierarchicalWarnings(scene, r)) log.message("warning: " + w);
  if (r.solve.reason.rfind("diverged", 0) == 0)
    throw std::runtime_error("hierarchical solve " + r.solve.reason + "; nothing written");

  writePatchesCsv(folder.path("patches.csv"), scene, r.leaves, &r.radiosity);
  std::vector<CellArray> extra{{"level", {}}, {"links", {}}, {"row_sum", r.rowSums}};
  for (int n : r.leafNodes) {
    extra[0].values.push_back((*r.hierarchy)[n].level);
    extra[1].values.push_back(r.system->linkCount(n));
  }
  writePatchesVtp(folder.path("radiosity.vtp"), scene, r.leaves, &r.radiosity, extra);
  std::optional<nlohmann::json> panorama;
  if (r.sky) panorama = writeSkyPanorama(folder, *r.sky);
  writeSurfacesCsv(folder.path("surfaces.csv"), scene, r.surfaces, job.photometric);
  writeConvergence(folder.path("convergence.csv"), folder.path("convergence.png"), {r.solve},
                   scene.metresPerUnit());
  LinkMatrixSettings matrix;
  matrix.colour = job.linkColour;
  matrix.title = scene.name + ": links as blocks of F, " + std::to_string(r.leaves.size()) +
                 " leaves in tree order";
  writeLinkMatrix(folder.path("links.png"), *r.hierarchy, r.system->links(), r.state, matrix);
  if (job.render) renderLeaves(folder, scene, r, job, log);
  nlohmann::json linkCheck;
  if (job.checkLinks > 0) {
    if (log.progress) log.progress("checking links", 0.0);
    const std::vector<LinkCheck> checks =
        checkLinks(*r.hierarchy, *r.system, *r.rays, job.checkLinks, job.hierarchical.seed);
    std::string csv = "receiver,source,kind,model,reference,reference_se,relative_difference,z\n";
    for (const LinkCheck& c : checks)
      csv += std::to_string(c.receiver) + "," + std::to_string(c.source) + "," +
             linkKindName(c.kind) + "," + formatValue("%.9g", c.model) + "," +
             formatValue("%.9g", c.reference) + "," + formatValue("%.3g", c.referenceError) + "," +
             (c.reference > 0 ? formatValue("%.5g", c.model / c.reference - 1) : "") + "," +
             (c.referenceError > 0 ? formatValue("%.3g", (c.model - c.reference) / c.referenceError)
                                   : "") +
             "\n";
    writeFileAtomically(folder.path("links_check.csv"), csv);
    linkCheck = nlohmann::json::object();
    linkCheck["links"] = checks.size();
    linkCheck["samples_per_link"] = 4096;
    for (const LinkCheckSummary& s : summariseLinkChecks(checks)) {
      if (s.links == 0) continue;
      linkCheck[linkKindName(s.kind)] = {
          {"links", s.links},
          {"model_power", s.model},
          {"reference_power", s.reference},
          {"reference_standard_error", s.referenceError},
          {"mean_absolute_relative_difference", s.meanAbsoluteRelative}};
      if (log.message) {
        char line[256];
        std::snprintf(line, sizeof line,
                      "check-links: %-16s %5d links, power %.5g against %.5g ± %.2g (%+.2f %%), "
                      "mean |difference| %.1f %%",
                      linkKindName(s.kind), s.links, s.model, s.reference, s.referenceError,
                      s.reference > 0 ? 100 * (s.model / s.reference - 1) : 0.0,
                      100 * s.meanAbsoluteRelative);
        log.message(line);
      }
    }
  }

  const double total = secondsSince(start);
  result.seconds = total;
  nlohmann::json& report = result.report;
  report = nlohmann::json{
      {"radkit", RADKIT_VERSION},
      {"command", "run"},
      {"method", "hierarchical"},
      {"scene", sceneJson(scene)},
      {"mesh", meshJson(scene, r.leaves)},
      {"hierarchy", hierarchyJson(scene, r, job.hierarchical)},
      {"solvers", nlohmann::json::array({solveJson(r.solve)})},
      {"energy_balance", energyJson(r.energy)},
      {"escape_estimate",
       {{"rays_per_leaf", 32},
        {"rays_per_emitting_leaf", 1024},
        {"rays_per_emitting_leaf_max", 65536},
        {"rays_cast",
         [&] {
           long long n = 0;
           for (int k : r.escapeRays) n += k;
           return n;
         }()},
        {"escaped_standard_error_W",
         {r.escapedStandardError.x, r.escapedStandardError.y, r.escapedStandardError.z}}}},
      {"surfaces", surfacesJson(r.surfaces)}};
  report["load"] = loadJson(loaded);
  if (!job.preset.empty())
    report["preset"] = {{"name", job.preset}, {"description", describePreset(job.preset)}};
  if (!linkCheck.is_null()) report["link_check"] = linkCheck;
  if (r.daylight) report["daylight"] = daylightJson(*r.sky, *r.daylight);
  if (panorama) report["sky_panorama"] = *panorama;
  report["seconds"] = {{"load", loadSeconds},
                       {"input_faces", r.seconds.inputFaces},
                       {"hierarchy", r.seconds.hierarchy},
                       {"ray_scene", r.seconds.rayScene},
                       {"daylight", r.seconds.daylight},
                       {"links", r.seconds.refine},
                       {"solve", r.seconds.solve},
                       {"results", r.seconds.results},
                       {"outputs", secondsSince(solved)},
                       {"total", total}};
  report["peak_memory_bytes"] = peakMemoryBytes();
  markStageMemory(r.memory, "outputs");
  report["memory"] = memoryJson(r.memory, r.hierarchy->base().size());
  writeJson(folder.path("report.json"), report);
  folder.commit();
  return result;
}

}  // namespace radkit
