#include "job/photons_job.h"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>

#include "experiments/photon_benchmark.h"
#include "geometry/mesh_structure.h"
#include "geometry/ray_scene.h"
#include "job/job.h"
#include "job/report.h"
#include "output/run_files.h"
#include "photon/image.h"
#include "render/camera.h"
#include "render/radiosity_image.h"
#include "util/errors.h"
#include "util/format.h"
#include "util/output_folder.h"
#include "util/setting_names.h"

namespace radkit {

namespace {

using nlohmann::json;
/// The radiosity solution to compare with: a run folder's surfaces.csv, or computed here on
/// the same mesh (then per patch too).
struct RadiosityReference {
  std::string source;
  std::vector<SurfaceRadiosity> surfaces;
  std::vector<Vec3> patches;  ///< empty when only per-surface values are known
  double seconds = 0;
};

RadiosityReference radiosityReference(const PhotonsJobSettings& cmd, const Scene& scene,
                                      const PatchMesh& mesh) {
  RadiosityReference ref;
  const auto start = Clock::now();
  if (!cmd.compare.empty()) {
    ref.source = cmd.compare;
    ref.surfaces = readSurfacesCsv((std::filesystem::path(cmd.compare) / "surfaces.csv").string());
    // Back sides of two-sided surfaces, after the scene's own (checked before the trace).
    if (ref.surfaces.size() > scene.surfaces.size()) ref.surfaces.resize(scene.surfaces.size());
  } else {
    PipelineSettings settings;
    settings.mesh = *cmd.mesh;
    PipelineResult r = runPipeline(scene, settings);
    ref.source = "computed (radkit run, same mesh)";
    for (const SurfaceResult& s : r.surfaces)
      ref.surfaces.push_back(
          {s.name, s.area / (scene.metresPerUnit() * scene.metresPerUnit()), s.radiosity});
    if (r.mesh.size() == mesh.size()) ref.patches = r.radiosity;
  }
  ref.seconds = secondsSince(start);
  return ref;
}

/// Per-patch values for difference.png: the patches' own, or their surfaces' when the
/// reference is per surface only.
void writeDifference(OutputFolder& folder, const Scene& scene, const PatchMesh& mesh,
                     const RayScene& rays, const PhotonRadiosity& photon,
                     const RadiosityReference& ref, const std::vector<SurfaceComparison>& rows,
                     const PhotonsJobSettings& cmd) {
  std::vector<Vec3> b = photon.radiosity, se = photon.radiosityError, rad = ref.patches;
  if (rad.empty()) {
    rad.resize(mesh.size());
    for (int i = 0; i < mesh.size(); ++i) {
      const SurfaceComparison& row = rows[mesh.patches[i].surface];
      b[i] = row.photon, se[i] = row.photonError, rad[i] = row.radiosity;
    }
  }
  ImageSettings s;
  s.width = cmd.imageWidth, s.height = cmd.imageHeight;
  s.samplesPerAxis = 1;
  const std::vector<bool> twoSided = scene.twoSidedSurfaces();
  const Camera camera = sceneCamera(scene, mesh);
  RadianceImage seen = renderRadiosity(mesh, rays, camera, b, twoSided, s);
  writePng(
      folder.path("difference.png"),
      differenceImage(seen, b, se, rad, ref.patches.empty() ? "z per surface" : "z per patch"));
}

json surfacesJson(const std::vector<SurfaceEstimate>& surfaces) {
  json a = json::array();
  for (const SurfaceEstimate& s : surfaces)
    a.push_back({{"name", s.name},
                 {"area", s.area},
                 {"radiosity", vec3Json(s.radiosity)},
                 {"standard_error", vec3Json(s.radiosityError)},
                 {"irradiance", vec3Json(s.irradiance)},
                 {"caustic_irradiance", vec3Json(s.causticIrradiance)},
                 {"photons", s.photons}});
  return a;
}

json statsJson(const PhotonTrace& t) {
  const PhotonTraceStats& s = t.stats;
  return {{"emitted", s.emitted},
          {"stored", s.stored},
          {"caustic", s.caustic},
          {"escaped", s.escaped},
          {"absorbed", s.absorbed},
          {"truncated", s.truncated},
          {"rays", s.rays},
          {"emitted_power", vec3Json(t.emittedPower)},
          {"total_power", vec3Json(t.sourcePower)},
          {"sky_and_sun_power", vec3Json(t.skyPower)}};
}

/// Everything one run computes, in the order it is computed.
struct PhotonRun {
  Scene scene;
  LoadReport loaded;  ///< the loader's warnings, for report.json
  PatchMesh mesh;
  std::unique_ptr<RayScene> rays;
  std::unique_ptr<EmitterSampler> emitters;
  PhotonTrace trace;
  PhotonRadiosity estimate;
  RadiosityReference reference;
  std::vector<SurfaceComparison> rows;
  std::unique_ptr<PhotonMap> global, caustic;
  PhotonView view = PhotonView::FinalGather;
  std::size_t stored = 0;
  double buildSeconds = 0;
  json seconds;
};

/// Refuses a --compare folder that is not a run of this scene: its surfaces.csv must list the
/// same surfaces with the same areas, and its report.json (a hand-made reference may have
/// none) name the same scene (a run of the glossy Cornell box has the plain box's surfaces).
void checkCompareFolder(const std::string& folder, const Scene& scene, const PatchMesh& mesh) {
  const std::filesystem::path dir(folder);
  const std::string fix = ". Fix: give the --out folder of a `radkit run` of " + scene.file;
  for (const char* file : {"report.json", "surfaces.csv"})
    requireRegularFile((dir / file).string(),
                       setting("compare") + " folder's " + std::string(file));
  std::ifstream in(dir / "report.json");
  json report = json::object();
  if (in) try {
      report = json::parse(in);
    } catch (const json::exception& e) {
      throw InputError(setting("compare") + " " + folder + ": report.json is not JSON (" +
                       e.what() + ")" + fix);
    }
  const json sceneJson =
      report.is_object() ? report.value("scene", json::object()) : json::object();
  const std::string name = sceneJson.is_object() ? sceneJson.value("name", scene.name) : scene.name;
  if (name != scene.name)
    throw InputError(setting("compare") + " " + folder + " is a run of scene \"" + name + "\" (" +
                     (sceneJson.is_object() ? sceneJson.value("file", "?") : "?") + "), not of \"" +
                     scene.name + "\"" + fix);
  const std::vector<SurfaceRadiosity> theirs = readSurfacesCsv((dir / "surfaces.csv").string());
  // A radiosity run adds "NAME (back)" after the surfaces for each two-sided one; the photon
  // tally has one estimate per surface (both sides): compare the surfaces themselves.
  std::size_t backs = 0;
  for (const Surface& s : scene.surfaces)
    if (scene.materials[s.material].twoSided && scene.surfaces.size() + backs < theirs.size() &&
        theirs[scene.surfaces.size() + backs].name == s.name + " (back)")
      ++backs;
  if (theirs.size() != scene.surfaces.size() + backs)
    throw InputError(setting("compare") + " " + folder + ": its surfaces.csv has " +
                     std::to_string(theirs.size()) + " surfaces, this scene " +
                     std::to_string(scene.surfaces.size()) + fix);
  for (std::size_t s = 0; s < scene.surfaces.size(); ++s) {
    double area = 0;
    for (int i = mesh.surfaceBegin[s]; i < mesh.surfaceBegin[s + 1]; ++i)
      area += mesh.patches[i].area;
    area *= scene.metresPerUnit() * scene.metresPerUnit();  // surfaces.csv's area is in m²
    // surfaces.csv keeps 17 digits; a hand-written reference may round to 3.
    if (theirs[s].name != scene.surfaces[s].name ||
        !(std::fabs(theirs[s].area - area) <= 1e-3 * area))
      throw InputError(setting("compare") + " " + folder + ": its surface " + std::to_string(s) +
                       " is \"" + theirs[s].name + "\" of area " +
                       formatValue("%.6g", theirs[s].area) + " m²" + ", this scene's \"" +
                       scene.surfaces[s].name + "\" of area " + formatValue("%.6g", area) +
                       " m² (the scene changed since that run)" + fix);
  }
}

/// Loads, meshes, checks emitters and the --compare folder (before any long work), traces
/// and estimates.
void traceAndEstimate(const PhotonsJobSettings& cmd, PhotonRun& r, const PipelineLog& log) {
  if (!cmd.compare.empty() &&
      !std::filesystem::exists(std::filesystem::path(cmd.compare) / "surfaces.csv"))
    throw InputError(setting("compare") + " " + cmd.compare +
                     ": no surfaces.csv there. Fix: give the " + setting("out") +
                     " folder of a "
                     "`radkit run` of the same scene");
  r.scene = loadJobScene(cmd.scene, cmd.load, cmd.camera, log, &r.loaded);
  auto t = Clock::now();
  r.mesh = subdivideScene(r.scene, *cmd.mesh, [&](const std::string& w) {
    if (log.message) log.message("warning: " + w);
  });
  r.rays = std::make_unique<RayScene>(r.mesh);
  r.seconds["mesh_and_ray_scene"] = secondsSince(t);
  r.emitters = std::make_unique<EmitterSampler>(photonEmitters(r.scene, r.mesh));
  if (!cmd.compare.empty()) {
    checkCompareFolder(cmd.compare, r.scene, r.mesh);
    r.reference = radiosityReference(cmd, r.scene, r.mesh);
  }
  r.trace = tracePhotons(r.scene, r.mesh, *r.rays, *r.emitters, cmd.settings);
  r.seconds["trace"] = r.trace.stats.seconds;
  t = Clock::now();
  r.estimate = estimateRadiosity(r.scene, r.mesh, r.trace.photons, cmd.settings.photons);
  r.seconds["estimate"] = secondsSince(t);
  if (!cmd.compare.empty()) r.rows = compareSurfaces(r.estimate.surfaces, r.reference.surfaces);
}

/// The global and caustic maps. They serve the images and the kd-tree figures; a study of the
/// per-surface estimate (--no-image --bench-rays 0) leaves them empty.
void buildMaps(const PhotonsJobSettings& cmd, PhotonRun& r) {
  const bool needed = cmd.image || cmd.benchRays > 0;
  auto t = Clock::now();
  r.stored = r.trace.photons.size();
  PhotonMaps maps =
      buildPhotonMaps(r.mesh, needed ? std::move(r.trace.photons) : std::vector<Photon>{});
  r.global = std::move(maps.global);
  r.caustic = std::move(maps.caustic);
  r.buildSeconds = needed ? secondsSince(t) : 0.0;
  r.seconds["kd_build"] = secondsSince(t);
  t = Clock::now();
  const PhotonSettings& ps = cmd.settings;
  r.view =
      cmd.view == "map" || ps.gatherRays == 0 ? PhotonView::GlobalMap : PhotonView::FinalGather;
  if (cmd.image && r.view == PhotonView::FinalGather)
    r.global->precomputeIrradiance(ps.neighbours, ps.filter, ps.precomputeStride);
  r.seconds["precompute"] = secondsSince(t);
}

/// photonmap.png and caustics.png (at photonmap.png's exposure, so the two compare).
void writeImages(OutputFolder& folder, const PhotonsJobSettings& cmd, PhotonRun& r) {
  const auto t = Clock::now();
  const PhotonScene in{r.scene, r.mesh, *r.rays, *r.emitters, *r.global, *r.caustic};
  const Camera camera = sceneCamera(r.scene, r.mesh);
  const int w = cmd.imageWidth, h = cmd.imageHeight;
  RadianceImage image = renderPhotonImage(in, camera, w, h, r.view, cmd.settings);
  const double exposure = photonImageExposure(in, image);
  writePng(folder.path("photonmap.png"), toneMap(image, exposure));
  if (!r.caustic->empty())
    writePng(folder.path("caustics.png"),
             toneMap(renderPhotonImage(in, camera, w, h, PhotonView::CausticMap, cmd.settings),
                     exposure));
  r.seconds["image"] = secondsSince(t);
}

json ratesJson(const PhotonsJobSettings& cmd, PhotonRun& r) {
  const auto t = Clock::now();
  const RateMeasurement embree =
      measureClosestHitRate(r.mesh, *r.rays, std::size_t(cmd.benchRays), cmd.settings.seed);
  // A k-nearest query costs about a hundred rays: time a hundredth as many.
  const RateMeasurement queries =
      measureKdTreeQueries(*r.global, r.mesh, std::size_t(cmd.benchRays / 100),
                           cmd.settings.neighbours, cmd.settings.filter);
  r.seconds["benchmark"] = secondsSince(t);
  const double photonRays = r.trace.stats.rays / r.trace.stats.seconds;
  return {
      {"photons_per_second", r.trace.stats.emitted / r.trace.stats.seconds},
      {"photon_rays_per_second", photonRays},
      {"embree_closest_hit_rays_per_second", embree.perSecond()},
      {"embree_rays_timed", embree.count},
      {"photon_rays_over_embree", embree.perSecond() > 0 ? photonRays / embree.perSecond() : 0.0},
      {"kd_build_photons_per_second", r.buildSeconds > 0 ? r.stored / r.buildSeconds : 0.0},
      {"kd_queries_timed", queries.count},
      {"kd_queries_per_second", queries.perSecond()}};
}

json reportJson(const PhotonsJobSettings& cmd, const PhotonRun& r, const json& rates) {
  const PhotonSettings& ps = cmd.settings;
  json report{{"radkit", RADKIT_VERSION},
              {"command", "photons"},
              {"scene", sceneJson(r.scene)},
              {"mesh", meshJson(r.scene, r.mesh)},
              {"settings",
               {{"photons", ps.photons},
                {"k", ps.neighbours},
                {"filter", filterName(ps.filter)},
                {"seed", ps.seed},
                {"view", viewName(r.view)},
                {"gather_rays", ps.gatherRays},
                {"direct_rays", ps.directRays},
                {"image_size",
                 !cmd.image ? json(nullptr) : json::array({cmd.imageWidth, cmd.imageHeight})}}},
              {"photons", statsJson(r.trace)},
              {"rates", rates},
              {"seconds", r.seconds},
              {"memory",
               {{"photon_map_bytes", r.global->memoryBytes()},
                {"caustic_map_bytes", r.caustic->memoryBytes()},
                {"peak_memory_bytes", peakMemoryBytes()}}},
              {"surfaces", surfacesJson(r.estimate.surfaces)},
              {"load", loadJson(r.loaded)}};
  if (!r.reference.surfaces.empty())
    report["comparison"] = {{"radiosity", r.reference.source},
                            {"per_patch", !r.reference.patches.empty()}};
  return report;
}

}  // namespace

PhotonsJobResult runPhotonsJob(const PhotonsJobSettings& given, const PipelineLog& log) {
  const auto start = Clock::now();
  if (given.view != "gather" && given.view != "map")
    throw std::invalid_argument("photons: view \"" + given.view + "\" is neither gather nor map");
  if (!given.compare.empty() && !given.radiosity)
    throw std::invalid_argument(
        "photons: a comparison folder was given and the radiosity comparison switched off");
  PhotonsJobSettings cmd = given;
  if (!cmd.mesh) cmd.mesh = SubdivisionSettings{0, kDefaultPhotonPatches};
  OutputFolder folder(cmd.out);  // refuses a folder it cannot replace before the work
  PhotonRun r;
  traceAndEstimate(cmd, r, log);
  buildMaps(cmd, r);
  if (cmd.image) writeImages(folder, cmd, r);
  if (cmd.compare.empty() && cmd.radiosity) {
    r.reference = radiosityReference(cmd, r.scene, r.mesh);
    r.rows = compareSurfaces(r.estimate.surfaces, r.reference.surfaces);
  }
  if (!r.reference.surfaces.empty()) {
    r.seconds["radiosity"] = r.reference.seconds;
    writeComparisonCsv(folder.path("comparison.csv"), r.rows, r.scene.metresPerUnit());
    writeDifference(folder, r.scene, r.mesh, *r.rays, r.estimate, r.reference, r.rows, cmd);
  }
  writePatchesCsv(folder.path("patches.csv"), r.scene, r.mesh, &r.estimate.radiosity);
  writeSurfacesCsv(folder.path("surfaces.csv"), r.scene,
                   surfaceResults(r.scene, r.mesh, r.estimate.radiosity, r.estimate.irradiance),
                   false);
  const json rates = ratesJson(cmd, r);
  r.seconds["total"] = secondsSince(start);
  PhotonsJobResult result;
  result.out = cmd.out;
  result.report = reportJson(cmd, r, rates);
  writeJson(folder.path("report.json"), result.report);
  folder.commit();
  result.surfaces = std::move(r.estimate.surfaces);
  result.comparison = std::move(r.rows);
  return result;
}

}  // namespace radkit
