#include "job/report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "output/run_files.h"
#include "render/hdr_io.h"
#include "render/sky_panorama.h"
#include "solvers/convergence.h"
#include "util/line_chart.h"
#include "util/output_folder.h"
#include "util/process_memory.h"

namespace radkit {

using nlohmann::json;

json vec3Json(const Vec3& v) { return json::array({v.x, v.y, v.z}); }

json sceneJson(const Scene& scene) {
  json j{{"name", scene.name}, {"file", scene.file}, {"units", scene.units}};
  json names = json::array();
  for (const Surface& s : scene.surfaces) names.push_back(s.name);
  j["surfaces"] = names;
  j["materials"] = scene.materials.size();
  if (scene.camera)
    j["camera"] = {{"position", vec3Json(scene.camera->position)},
                   {"look_at", vec3Json(scene.camera->lookAt)},
                   {"up", vec3Json(scene.camera->up)},
                   {"fov_deg", scene.camera->fovDeg}};
  return j;
}

json meshJson(const Scene& scene, const PatchMesh& mesh) {
  int quads = 0;
  double lo = INFINITY, hi = 0, aspect = 0;
  for (const Patch& p : mesh.patches) {
    quads += p.isQuad();
    lo = std::min(lo, p.area);
    hi = std::max(hi, p.area);
    aspect = std::max(aspect, mesh.aspectRatio(p));
  }
  return {{"patches", mesh.size()},
          {"quads", quads},
          {"triangles", mesh.size() - quads},
          {"vertices", mesh.vertices.size()},
          {"total_area", mesh.totalArea()},
          {"area_units", scene.units + "^2"},
          {"min_patch_area", lo},
          {"max_patch_area", hi},
          {"worst_aspect_ratio", aspect}};
}

json numberOrNull(double v) { return std::isnan(v) ? json(nullptr) : json(v); }

json solveJson(const SolveResult& r) {
  json milestonesJson = json::array();
  for (const Milestone& m : milestones(r)) {
    json row{{"residual", m.level}, {"reached", m.reached}};
    if (m.reached)
      row.update({{"iterations", m.iterations}, {"seconds", m.seconds}, {"sweeps", m.sweeps}});
    milestonesJson.push_back(row);
  }
  return {{"solver", r.solver},
          {"description", r.description},
          {"converged", r.converged},
          {"reason", r.reason},
          {"exit_reason", r.exit},
          {"iterations", r.iterations},
          {"seconds", r.seconds},
          {"spectral_radius_estimate", numberOrNull(r.spectralRadius)},
          {"predicted_sweeps", numberOrNull(r.predictedSweeps)},
          {"residual", r.residual},
          {"checked_residual", r.checkedResidual},
          {"milestones", milestonesJson},
          {"ambient", json::array({r.ambient[0], r.ambient[1], r.ambient[2]})}};
}

json energyJson(const EnergyBalance& e) {
  return {{"emitted_W", vec3Json(e.emitted)},
          {"absorbed_W", vec3Json(e.absorbed)},
          {"escaped_W", vec3Json(e.escaped)},
          {"relative_imbalance", e.relativeImbalance}};
}

json surfacesJson(const std::vector<SurfaceResult>& surfaces) {
  json a = json::array();
  for (const SurfaceResult& s : surfaces) {
    a.push_back({{"surface", s.name},
                 {"area_m2", s.area},
                 {"radiosity_W_m2", vec3Json(s.radiosity)},
                 {"irradiance_W_m2", vec3Json(s.irradiance)},
                 {"luminance_cd_m2", s.luminance},
                 {"illuminance_lux", s.illuminance}});
    if (s.daylit)
      a.back().update({{"sky_view_factor", s.skyViewFactor},
                       {"daylight_W_m2", vec3Json(s.daylight)},
                       {"daylight_illuminance_lux", s.daylightIlluminance}});
  }
  return a;
}

json loadJson(const LoadReport& report) {
  nlohmann::json repairs = nlohmann::json::array();
  for (const MeshRepair& r : report.repairs)
    repairs.push_back({{"surface", r.surface},
                       {"welded_vertices", r.weldedVertices},
                       {"duplicate_faces_removed", r.duplicateFaces},
                       {"degenerate_faces_removed", r.degenerateFaces},
                       {"non_manifold_edges_cut", r.nonManifoldEdges},
                       {"non_manifold_vertices_split", r.nonManifoldVertices},
                       {"border_edges_stitched", r.stitchedEdges},
                       {"faces_reversed", r.reversedFaces},
                       {"summary", r.describe()}});
  return {{"warnings", report.warnings}, {"repairs", repairs}};
}

json daylightJson(const SkyModel& sky, const Daylight& d) {
  const SkyDescription& k = sky.description();
  json j{{"sky", sky.typeName()},
         {"horizontal_sky_W_m2", vec3Json(sky.horizontalSky())},
         {"horizontal_sun_W_m2", vec3Json(sky.horizontalSun())},
         {"horizontal_illuminance_lux",
          kLumensPerWatt * luminance(sky.horizontalSky() + sky.horizontalSun())},
         {"sky_rays_per_patch", k.samples},
         {"rays", d.rays},
         {"sky_noise", d.skyNoise},
         {"seconds", d.seconds}};
  if (k.sun)
    j["sun"] = {{"elevation_deg", k.sunElevationDeg},
                {"azimuth_deg", k.sunAzimuthDeg},
                {"direction", vec3Json(sky.sunDirection())},
                {"normal_irradiance_W_m2", vec3Json(sky.sunIrradiance())},
                {"rays_per_patch", k.sunSamples}};
  if (const auto model = sky.modelReport(); !model.empty()) j[sky.typeName()] = model;
  return j;
}

json writeSkyPanorama(OutputFolder& folder, const SkyModel& sky) {
  const RadianceImage image = skyPanorama(sky);
  writePfm(folder.path("sky.pfm"), image);
  return {{"file", "sky.pfm"},
          {"width", image.width},
          {"height", image.height},
          {"layout",
           "equirectangular: bearing 360u deg clockwise from north towards east, "
           "elevation 90 - 180v deg (u, v from the left and the top)"},
          {"up", vec3Json(sky.toScene({0, 0, 1}))},
          {"north", vec3Json(sky.toScene({0, 1, 0}))},
          {"east", vec3Json(sky.toScene({1, 0, 0}))}};
}

std::size_t peakMemoryBytes() { return lifetimePeakMemory(); }

namespace {

/// The JSON pointer of the first number that is not finite, or "" if all are: nlohmann writes
/// NaN and infinity as null, which readers take for "no value".
std::string firstNonFinite(const json& j, const std::string& at) {
  if (j.is_number_float()) return std::isfinite(j.get<double>()) ? "" : (at.empty() ? "/" : at);
  if (j.is_object()) {
    for (auto it = j.begin(); it != j.end(); ++it)
      if (std::string found = firstNonFinite(it.value(), at + "/" + it.key()); !found.empty())
        return found;
  } else if (j.is_array()) {
    for (std::size_t k = 0; k < j.size(); ++k)
      if (std::string found = firstNonFinite(j[k], at + "/" + std::to_string(k)); !found.empty())
        return found;
  }
  return "";
}

}  // namespace

void writeJson(const std::string& path, const json& j) {
  if (const std::string at = firstNonFinite(j, ""); !at.empty())
    throw std::runtime_error(path + ": the result " + at +
                             " is not a finite number, so the run writes nothing. Fix: bring "
                             "the scene's values (sizes, emission) nearer 1, or report this");
  writeFileAtomically(path, j.dump(2) + "\n");
}

void writeConvergence(const std::string& csvPath, const std::string& pngPath,
                      const std::vector<SolveResult>& solves, double metresPerUnit) {
  writeConvergenceCsv(csvPath, solves, metresPerUnit);
  // Work, not iterations, on x: a Southwell shot updates one row (1/n of a sweep), so its
  // thousands of shots would squash the sweeping solvers against x = 0.
  ChartPanel byIteration{"Residual against work",
                         "sweep-equivalents (a Southwell shot = 1/n sweep)",
                         "relative residual",
                         false,
                         true,
                         {}};
  ChartPanel bySeconds{"Residual against time", "seconds", "relative residual", true, true, {}};
  for (const SolveResult& s : solves) {
    ChartSeries it{s.solver, {}, {}}, sec{s.solver, {}, {}};
    for (const HistoryRow& h : s.history) {
      it.x.push_back(h.sweeps);
      it.y.push_back(h.residual);
      sec.x.push_back(h.seconds);
      sec.y.push_back(h.residual);
    }
    byIteration.series.push_back(it);
    bySeconds.series.push_back(sec);
  }
  writeLineChartPng(pngPath, {byIteration, bySeconds});
}

}  // namespace radkit
