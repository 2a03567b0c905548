#include "job/terrain_job.h"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "atmosphere/atmosphere.h"
#include "job/report.h"
#include "render/camera.h"
#include "render/hdr_io.h"
#include "sky/sky_radiance.h"
#include "util/canvas.h"
#include "util/format.h"
#include "util/output_folder.h"

namespace radkit {

namespace {

using nlohmann::json;
using terrain::TerrainMaterial;

/// The heightfield as a viridis PNG, north up.
void writeHeightMap(const std::string& path, const terrain::Heightfield& f, double height) {
  Canvas c(f.n, f.n);
  for (int j = 0; j < f.n; ++j)
    for (int i = 0; i < f.n; ++i)
      c.set(i, f.n - 1 - j, viridis(height > 0 ? f.z[std::size_t(j) * f.n + i] / height : 0));
  writePng(path, c);
}

Camera terrainCamera(const terrain::TerrainSettings& s) {
  const double half = s.size / 2;
  Camera c;
  c.position = {0.0, -1.2 * half, 1.6 * s.height};
  c.lookAt = {0.0, 0.2 * half, 0.3 * s.height};
  c.up = {0, 0, 1};
  c.fovDeg = 55;
  return c;
}

/// Both landscape images, their difference, and what each cost.
json renderLandscapes(const TerrainJobSettings& cmd, const terrain::TerrainSettings& settings,
                      OutputFolder& folder, const terrain::Heightfield& field) {
  terrain::LandscapeSettings ls = cmd.landscape;
  ls.sunElevationDeg = cmd.sunElevation, ls.sunAzimuthDeg = cmd.sunAzimuth;
  ls.seed = settings.fractal.seed;
  const terrain::TerrainSurface surface(field, settings);
  const atmosphere::Atmosphere air;
  const PinholeCamera camera(terrainCamera(settings), ls.width, ls.height);
  const auto direction = [&](double x, double y) { return camera.direction(x, y); };
  const terrain::LandscapeImage march =
      terrain::renderLandscape(surface, air, camera.origin(), direction, ls, false);
  const terrain::LandscapeImage embree =
      terrain::renderLandscape(surface, air, camera.origin(), direction, ls, true);
  // Exposure: the reference's mean luminance to 0.18 (a mid grey), unless given.
  double mean = 0;
  for (const Vec3& v : embree.radiance) mean += luminance(v);
  mean /= double(embree.radiance.size());
  const double exposure = cmd.exposure > 0 ? cmd.exposure : (mean > 0 ? 0.18 / mean : 1);
  json out = json::object();
  double sumSq = 0, refSq = 0, hitMismatch = 0, depthError = 0, both = 0;
  for (std::size_t i = 0; i < embree.radiance.size(); ++i) {
    const Vec3 e = march.radiance[i] - embree.radiance[i];
    sumSq += dot(e, e) / 3, refSq += dot(embree.radiance[i], embree.radiance[i]) / 3;
    const bool a = march.depth[i] >= 0, b = embree.depth[i] >= 0;
    hitMismatch += a != b;
    if (a && b)
      both += 1, depthError += std::fabs(march.depth[i] - embree.depth[i]) / embree.depth[i];
  }
  const std::size_t pixels = embree.radiance.size();
  for (const auto& [name, image] :
       {std::pair<std::string, const terrain::LandscapeImage*>{"march", &march},
        {"embree", &embree}}) {
    writeLinearAndPng(folder.path("landscape-" + name),
                      pixelImage(ls.width, ls.height, image->radiance, exposure));
    out[name] = {{"seconds", image->seconds},
                 {"visibility_thread_seconds", image->visibilitySeconds},
                 {"rays", image->rays},
                 {"rays_per_second", image->rays / std::max(image->seconds, 1e-9)}};
    if (name == "march") out[name]["steps"] = image->steps;
  }
  writePng(
      folder.path("landscape-difference.png"),
      toneMapCurve(relativeDifferenceImage(ls.width, ls.height, march.radiance, embree.radiance), 1,
                   ToneCurve::Srgb));
  out["relative_rmse"] = refSq > 0 ? std::sqrt(sumSq / refSq) : 0.0;
  out["hit_mismatch_pixels"] = hitMismatch;
  out["mean_relative_depth_difference"] = both > 0 ? depthError / both : 0.0;
  out["pixels"] = pixels;
  out["settings"] = {{"width", ls.width},
                     {"height", ls.height},
                     {"max_steps", ls.maxSteps},
                     {"sun_samples", ls.sunSamples},
                     {"aerial_samples", ls.aerialSamples},
                     {"aerial_perspective", ls.aerialPerspective},
                     {"exposure", exposure}};
  return out;
}

/// A parameter as the scene file writes it: a name, a number (whole numbers without ".0"), or
/// a triple.
json paramJson(const Params::Value& v) {
  if (v.isText) return v.text;
  if (v.numbers.size() != 1) return v.numbers;
  const double x = v.numbers[0];
  if (x == std::floor(x) && std::abs(x) < 1e15) return static_cast<long long>(x);
  return x;
}

/// The scene's sky: the model named by --sky with its parameters, or its registry example (a
/// daylight of 10 000 lux) when none are given; the terrain's sun for a model that needs one.
json skyJson(const TerrainJobSettings& cmd) {
  const PluginChoice choice = splitPluginChoice(cmd.sky);
  const SkyRegistry::Entry& entry = skyRegistry().at(choice.name);
  const Params params =
      Params::parse(choice.parameters.empty() ? entry.example : choice.parameters);
  const std::unique_ptr<SkyRadiance> model = skyRegistry().make(choice.name, params);
  json sky{{"type", choice.name},
           {"up", {0, 0, 1}},
           {"north", {0, 1, 0}},
           {"samples", cmd.skySamples},
           {"sun_samples", cmd.sunSamples}};
  for (const auto& [key, value] : params.values()) sky[key] = paramJson(value);
  if (model->needsSun())
    sky["sun"] = {{"elevation", cmd.sunElevation}, {"azimuth", cmd.sunAzimuth}};
  return sky;
}

}  // namespace

TerrainJobResult runTerrainJob(const TerrainJobSettings& cmd) {
  const auto start = std::chrono::steady_clock::now();
  if (cmd.type != "ridged" && cmd.type != "fbm")
    throw std::invalid_argument("terrain: type \"" + cmd.type + "\" is neither ridged nor fbm");
  if (cmd.format != "obj" && cmd.format != "ply")
    throw std::invalid_argument("terrain: format \"" + cmd.format + "\" is neither obj nor ply");
  json sky;
  try {
    sky = skyJson(cmd);
  } catch (const ParamError& e) {
    throw std::invalid_argument(std::string("terrain: sky: ") + e.what());
  }
  TerrainJobResult result;
  result.out = cmd.out;
  terrain::TerrainSettings s = cmd.settings;
  s.type = cmd.type == "fbm" ? terrain::NoiseType::Fbm : terrain::NoiseType::Ridged;
  OutputFolder folder(cmd.out);
  const terrain::Heightfield field = terrain::makeHeightfield(s);
  const terrain::TerrainMesh mesh = terrain::triangulate(field, s);
  const double generateSeconds = secondsSince(start);

  json materials = json::object(), surfaces = json::array(), counts = json::object();
  for (int m = 0; m < 3; ++m) {
    const std::string name = terrain::kTerrainMaterialNames[m];
    const std::string file = "terrain-" + name + "." + cmd.format;
    const std::size_t n = terrain::writeTerrainPart(folder.path(file), mesh, TerrainMaterial(m));
    counts[name] = n;
    if (n == 0) {
      std::filesystem::remove(folder.path(file));
      continue;
    }
    materials[name] = {{"reflectance", vec3Json(terrain::kTerrainReflectance[m])}};
    surfaces.push_back({{"name", name}, {"material", name}, {"mesh", file}});
  }
  // In the order a person reads a scene file (nlohmann::json would sort the keys).
  const auto ordered = [](const json& j) { return nlohmann::ordered_json::parse(j.dump()); };
  nlohmann::ordered_json scene;
  // Named after its folder, so `radkit run` writes to out/<folder>.
  const std::string folderName = std::filesystem::path(cmd.out).filename().string();
  scene["name"] = folderName.empty() ? "terrain" : folderName;
  scene["description"] = "radkit terrain: " + cmd.type + " heightfield, seed " +
                         std::to_string(s.fractal.seed) + ", " + std::to_string(s.resolution) +
                         "² vertices over " + formatNumber(s.size) + " m";
  scene["units"] = "m";
  scene["materials"] = ordered(materials);
  scene["surfaces"] = ordered(surfaces);
  scene["camera"] = ordered({{"position", vec3Json(terrainCamera(s).position)},
                             {"look_at", vec3Json(terrainCamera(s).lookAt)},
                             {"up", {0, 0, 1}},
                             {"fov_deg", terrainCamera(s).fovDeg}});
  scene["sky"] = ordered(sky);
  writeFileAtomically(folder.path("terrain.json"), scene.dump(1) + "\n");
  writeHeightMap(folder.path("heightmap.png"), field, s.height);
  const FractalSettings& f = s.fractal;
  json& report = result.report;
  report = json{{"radkit", RADKIT_VERSION},
                {"command", "terrain"},
                {"settings",
                 {{"type", cmd.type},
                  {"octaves", f.octaves},
                  {"lacunarity", f.lacunarity},
                  {"H", f.H},
                  {"gain", f.gain},
                  {"offset", f.offset},
                  {"seed", f.seed},
                  {"resolution", s.resolution},
                  {"size_m", s.size},
                  {"height_m", s.height},
                  {"feature_size_m", s.featureSize},
                  {"snow_line", s.snowLine},
                  {"rock_slope_deg", s.rockSlopeDeg},
                  {"format", cmd.format}}},
                {"triangles", mesh.triangles.size()},
                {"triangles_by_material", counts},
                {"seconds", {{"generate", generateSeconds}}}};
  if (cmd.image) report["landscape"] = renderLandscapes(cmd, s, folder, field);
  writeJson(folder.path("report.json"), report);
  folder.commit();
  return result;
}

}  // namespace radkit
