// JSON scene loading (the format in docs/formats.md). Every key is read in one place; keys that
// nothing reads are rejected with their location, as pbrt-v4's ReportUnused does.
#include "geometry/scene_loader.h"

#include <nlohmann/json.hpp>

#ifdef __GLIBC__
#include <malloc.h>
#endif

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <unordered_map>
#include <unordered_set>

#include "geometry/json_reader.h"
#include "geometry/mesh_reader.h"
#include "geometry/mesh_structure.h"
#include "geometry/validation.h"
#include "sky/sky_radiance.h"
#include "util/format.h"
#include "util/photometry.h"
#include "util/setting_names.h"

namespace radkit {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

/// Scene extents (largest side, metres) outside which loading warns that the unit may be wrong:
/// a 5 m room written in millimetres and read as metres spans 5 km.
constexpr double kLargestPlausibleMetres = 200;
constexpr double kSmallestPlausibleMetres = 1e-2;
constexpr double kLargestPlausibleOutdoorMetres = 1e5;

std::string unitList() {
  std::string list;
  for (const auto& unit : knownUnits()) list += (list.empty() ? "" : "|") + unit.first;
  return list;
}

bool isKnownUnit(const std::string& unit) {
  for (const auto& known : knownUnits())
    if (known.first == unit) return true;
  return false;
}

/// A plugin's own keys: every key of j but the common ones, as Params (a name, a number, or a
/// triple), for its registry to read and check.
Params pluginParams(ObjectReader& r, const json& j, std::initializer_list<const char*> common) {
  Params params;
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string& key = it.key();
    if (std::any_of(common.begin(), common.end(), [&](const char* c) { return key == c; }))
      continue;
    const json& v = it.value();
    if (v.is_string())
      params.setText(key, v.get<std::string>());
    else if (v.is_array())
      params.set(key, r.toVec3(v, key));
    else
      params.set(key, r.toNumber(v, key));
  }
  return params;
}

/// A material: "brdf" names the BSDF, "emission" and "two_sided" belong to every material, and
/// every other key is the BSDF's own, read and range-checked by it (bsdf/registry.cpp).
Material readMaterial(const std::string& name, const json& j, const std::string& file) {
  ObjectReader r(j, "material \"" + name + "\"", file);
  if (!j.is_object()) r.fail("must be an object");
  Material m;
  m.name = name;
  m.bsdf = r.string("brdf", "lambert");
  m.emission = r.vec3("emission", m.emission);
  m.twoSided = r.boolean("two_sided", false);
  m.params = pluginParams(r, j, {"brdf", "emission", "two_sided"});
  try {
    resolveMaterial(m);
  } catch (const ParamError& e) {
    const std::string what = e.what();
    r.fail(what.rfind("has unknown", 0) == 0 ? what : "(brdf \"" + m.bsdf + "\"): " + what);
  }
  return m;
}

/// Adds a polygon given by coordinates, sharing vertices with identical coordinates.
void addPolygon(Surface& s, const std::vector<Vec3>& points,
                std::map<std::array<double, 3>, int>& index) {
  Face face;
  for (const Vec3& p : points) {
    auto key = std::array<double, 3>{p.x, p.y, p.z};
    auto it = index.find(key);
    if (it == index.end()) {
      it = index.emplace(key, int(s.vertices.size())).first;
      s.vertices.push_back(p);
    }
    face.vertices.push_back(it->second);
  }
  s.faces.push_back(std::move(face));
}

std::vector<Vec3> readPolygon(ObjectReader& r, const json& j, const std::string& what) {
  if (!j.is_array() || j.size() < 3)
    r.fail("\"" + what + "\" must be an array of at least 3 points");
  std::vector<Vec3> points;
  for (std::size_t k = 0; k < j.size(); ++k)
    points.push_back(r.toVec3(j[k], what + "[" + std::to_string(k) + "]"));
  return points;
}

/// A 3×3 rotation as rows.
using Rotation = std::array<Vec3, 3>;

Vec3 rotate(const Rotation& m, const Vec3& v) { return {dot(m[0], v), dot(m[1], v), dot(m[2], v)}; }

Rotation compose(const Rotation& a, const Rotation& b) {  // a·b: b first
  Rotation out;
  for (int i = 0; i < 3; ++i)
    out[i] = {dot(a[i], Vec3{b[0].x, b[1].x, b[2].x}), dot(a[i], Vec3{b[0].y, b[1].y, b[2].y}),
              dot(a[i], Vec3{b[0].z, b[1].z, b[2].z})};
  return out;
}

/// Rodrigues' rotation by `degrees` about the unit `axis` (right-handed).
Rotation axisAngle(const Vec3& axis, double degrees) {
  const double a = degrees * M_PI / 180, c = std::cos(a), s = std::sin(a), t = 1 - c;
  const Vec3 u = axis;
  return {Vec3{t * u.x * u.x + c, t * u.x * u.y - s * u.z, t * u.x * u.z + s * u.y},
          Vec3{t * u.x * u.y + s * u.z, t * u.y * u.y + c, t * u.y * u.z - s * u.x},
          Vec3{t * u.x * u.z - s * u.y, t * u.y * u.z + s * u.x, t * u.z * u.z + c}};
}

/// Applies a mesh surface's "transform": "up" (the model's up axis, turned onto radkit's +y),
/// then scale (number or per-axis), then "rotate" (axis-angle) or "euler_deg" (about x, then
/// y, then z), then translate.
void applyTransform(ObjectReader& surface, const json& j, const std::string& file, Surface& s) {
  ObjectReader r(j, surface.where() + " transform", file);
  r.allowOnly({"up", "scale", "rotate", "euler_deg", "translate"});
  Rotation up{Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}};
  if (r.has("up")) {
    const std::string given = r.string("up", "y");
    if (given == "z")  // +z onto +y: -90° about x, so (x, y, z) -> (x, z, -y)
      up = axisAngle({1, 0, 0}, -90);
    else if (given == "-z")
      up = axisAngle({1, 0, 0}, 90);
    else if (given == "x")
      up = axisAngle({0, 0, 1}, 90);
    else if (given != "y")
      r.fail("\"up\" \"" + given +
             "\" is not an axis radkit knows. Fix: \"z\" for a z-up model (most CAD and scan "
             "tools), \"y\" (radkit's own), \"-z\" or \"x\"");
  }
  Vec3 scale{1, 1, 1};
  if (r.has("scale")) {
    const json& given = j.at("scale");
    scale =
        given.is_array() ? r.toVec3(given, "scale") : Vec3{1, 1, 1} * r.toNumber(given, "scale");
  }
  if (scale.x == 0 || scale.y == 0 || scale.z == 0) r.fail("\"scale\" must be non-zero");
  if (r.has("rotate") && r.has("euler_deg"))
    r.fail("has both \"rotate\" and \"euler_deg\". Fix: give one rotation");
  Rotation turn{Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}};
  if (r.has("rotate")) {
    ObjectReader rot(j.at("rotate"), surface.where() + " transform rotate", file);
    rot.allowOnly({"axis", "degrees"});
    const Vec3 axis = rot.vec3("axis", {0, 0, 0});
    const double degrees = rot.number("degrees", 0);
    if (!(length(axis) > 0))
      rot.fail("\"axis\" must be a non-zero vector, e.g. [0, 1, 0] to turn about the vertical");
    if (!(std::fabs(degrees) <= 36000))
      rot.fail("\"degrees\" must be a finite angle within ±36000");
    turn = axisAngle(normalize(axis), degrees);
  } else if (r.has("euler_deg")) {
    const Vec3 e = r.toVec3(j.at("euler_deg"), "euler_deg");
    for (int c = 0; c < 3; ++c)
      if (!(std::fabs(e[c]) <= 36000)) r.fail("\"euler_deg\" angles must lie within ±36000");
    turn = compose(axisAngle({0, 0, 1}, e.z),
                   compose(axisAngle({0, 1, 0}, e.y), axisAngle({1, 0, 0}, e.x)));
  }
  const Vec3 translate = r.vec3("translate", {0, 0, 0});
  for (Vec3& v : s.vertices) v = rotate(turn, mul(rotate(up, v), scale)) + translate;
  // A mirroring scale turns counter-clockwise faces clockwise: reverse them to keep the front.
  // (Rotations keep handedness.)
  if (scale.x * scale.y * scale.z < 0)
    for (Face& f : s.faces) std::reverse(f.vertices.begin(), f.vertices.end());
}

/// Material names to indices: a linear search per surface made loading quadratic.
using MaterialIndex = std::unordered_map<std::string, int>;

Surface readSurface(const json& j, std::size_t index, const Scene& scene,
                    const MaterialIndex& materialIndex, const std::string& file,
                    const LoadOptions& options, LoadReport& report, bool& selfIntersections) {
  std::string where = "surfaces[" + std::to_string(index) + "]";
  if (j.is_object() && j.contains("name") && j["name"].is_string())
    where += " (\"" + j["name"].get<std::string>() + "\")";
  ObjectReader r(j, where, file);
  r.allowOnly({"name", "material", "polygon", "polygons", "mesh", "transform", "reverse",
               "check_self_intersections"});
  Surface s;
  s.source = file + ": " + where;
  s.name = r.string("name", "surface" + std::to_string(index));
  std::string material = r.string("material", "");
  if (material.empty()) r.fail("needs a \"material\"");
  const auto found = materialIndex.find(material);
  s.material = found == materialIndex.end() ? -1 : found->second;
  if (s.material < 0) {
    std::string known;
    for (std::size_t m = 0; m < scene.materials.size() && m < 20; ++m)
      known += (m ? ", " : "") + scene.materials[m].name;
    if (scene.materials.size() > 20)
      known += " (and " + std::to_string(scene.materials.size() - 20) + " more)";
    r.fail("uses the unknown material \"" + material + "\". Fix: use one of: " + known);
  }
  int shapes = int(r.has("polygon")) + int(r.has("polygons")) + int(r.has("mesh"));
  if (shapes != 1) r.fail("needs exactly one of \"polygon\", \"polygons\" or \"mesh\"");
  std::map<std::array<double, 3>, int> vertexIndex;
  if (r.has("polygon")) {
    addPolygon(s, readPolygon(r, j.at("polygon"), "polygon"), vertexIndex);
  } else if (r.has("polygons")) {
    const json& list = j.at("polygons");
    if (!list.is_array() || list.empty())
      r.fail("\"polygons\" must be a non-empty array of polygons");
    for (std::size_t k = 0; k < list.size(); ++k)
      addPolygon(s, readPolygon(r, list[k], "polygons[" + std::to_string(k) + "]"), vertexIndex);
  } else {
    if (!j.at("mesh").is_string()) r.fail("\"mesh\" must be a file name");
    fs::path meshPath = fs::path(file).parent_path() / j.at("mesh").get<std::string>();
    RawMesh raw;
    try {
      MeshReadProgress progress;
      if (options.progress)
        progress = [&](double f) {
          options.progress("reading " + meshPath.filename().string(), f);
        };
      raw = readMeshFile(meshPath.string(), options.repair, progress);
    } catch (const InputError& e) {
      r.fail("reads its mesh: " + std::string(e.what()));
    }
    if (raw.droppedFaces > 0)
      report.warnings.push_back(
          file + ": " + where + " (mesh " + meshPath.string() + "): repair: the reader dropped " +
          std::to_string(raw.droppedFaces) + " face(s) that repeat a vertex.");
    s.vertices = std::move(raw.vertices);
    s.faces = std::move(raw.faces);
    s.source += " (mesh " + meshPath.string() + ")";
  }
  // For a mesh known to be clean: its self-intersection check (seconds a million faces) is
  // skipped.
  if (r.has("check_self_intersections")) {
    if (!j.at("check_self_intersections").is_boolean())
      r.fail("\"check_self_intersections\" must be true or false");
    selfIntersections = j.at("check_self_intersections").get<bool>();
  }
  if (r.has("transform")) {
    if (!r.has("mesh")) r.fail("has a \"transform\": only mesh surfaces take one");
    applyTransform(r, j.at("transform"), file, s);
  }
  // "reverse": the other side is the front (a mesh wound inward, such as a scan whose normals
  // point into the model).
  if (r.has("reverse")) {
    if (!j.at("reverse").is_boolean()) r.fail("\"reverse\" must be true or false");
    if (j.at("reverse").get<bool>())
      for (Face& f : s.faces) std::reverse(f.vertices.begin(), f.vertices.end());
  }
  return s;
}

/// surfaces[i] {"include": "model.obj"}: every surface of an OBJ, with its MTL materials
/// (read by loadObjScene) unless the scene defines a material of the same name, which then
/// overrides it. The scene's units, camera and "transform" apply to the included geometry.
void includeObj(const json& j, std::size_t index, Scene& scene, MaterialIndex& materialIndex,
                const std::string& file) {
  const std::string where = "surfaces[" + std::to_string(index) + "]";
  ObjectReader r(j, where, file);
  r.allowOnly({"include", "transform"});
  if (!j.at("include").is_string()) r.fail("\"include\" must be the file name of an .obj");
  const fs::path objPath = fs::path(file).parent_path() / j.at("include").get<std::string>();
  std::string ext = objPath.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  if (ext != ".obj")
    r.fail("includes " + objPath.string() +
           ", not an .obj. Fix: include an OBJ scene (with its MTL), or give a \"mesh\" surface");
  std::error_code ec;
  if (!fs::exists(objPath, ec))
    r.fail("includes " + objPath.string() +
           ", which does not exist. Fix: give the OBJ's path relative to " + file);
  Scene obj;
  try {
    requireRegularFile(objPath.string(), "included OBJ");
    std::unordered_set<std::string> defined;
    for (const auto& entry : materialIndex) defined.insert(entry.first);
    obj = loadObjScene(objPath.string(), nullptr, &defined);
  } catch (const InputError& e) {
    r.fail("includes an OBJ: " + std::string(e.what()));
  }
  std::vector<int> material(obj.materials.size());
  for (std::size_t m = 0; m < obj.materials.size(); ++m) {
    const auto [at, added] =
        materialIndex.emplace(obj.materials[m].name, int(scene.materials.size()));
    material[m] = at->second;
    if (added) scene.materials.push_back(obj.materials[m]);
  }
  for (Surface& s : obj.surfaces) {
    s.material = material[s.material];
    s.source = file + ": " + where + " (" + s.source + ")";
    if (r.has("transform")) applyTransform(r, j.at("transform"), file, s);
    scene.surfaces.push_back(std::move(s));
  }
}

/// A radiance given as one number (grey) or three.
Vec3 readRadiance(ObjectReader& r, const json& j, const std::string& key) {
  if (j.is_number()) {
    const double v = r.toNumber(j, key);
    return {v, v, v};
  }
  return r.toVec3(j, key);
}

void requireNonNegative(ObjectReader& r, const Vec3& v, const std::string& key) {
  try {
    checkEmission(key, v);
  } catch (const ParamError& e) {
    r.fail(e.what());
  }
}

/// The sun: where it stands and, unless the sky model computes it, how strong it is.
void readSun(const json& j, const std::string& file, bool modelMakesSun, SkyDescription& sky) {
  ObjectReader r(j, "sky's \"sun\"", file);
  if (modelMakesSun)
    r.allowOnly({"elevation", "azimuth", "angular_radius"});
  else
    r.allowOnly({"elevation", "azimuth", "angular_radius", "irradiance", "illuminance"});
  sky.sun = true;
  sky.sunElevationDeg = r.toNumber(r.get("elevation"), "elevation");
  if (std::abs(sky.sunElevationDeg) > 90) r.fail("\"elevation\" must lie in [-90, 90] degrees");
  sky.sunAzimuthDeg = r.number("azimuth", sky.sunAzimuthDeg);
  sky.sunAngularRadiusDeg = r.number("angular_radius", sky.sunAngularRadiusDeg);
  if (!(sky.sunAngularRadiusDeg > 0 && sky.sunAngularRadiusDeg <= 10))
    r.fail("\"angular_radius\" must lie in (0, 10] degrees (the real sun's is 0.2665)");
  if (modelMakesSun) return;
  if (r.has("irradiance") == r.has("illuminance"))
    r.fail(
        "needs exactly one of \"irradiance\" (W/m² per channel, normal to the sun) and "
        "\"illuminance\" (lux, white)");
  if (r.has("irradiance")) {
    sky.sunIrradiance = readRadiance(r, j.at("irradiance"), "irradiance");
    requireNonNegative(r, sky.sunIrradiance, "irradiance");
  } else {
    const double lux = r.toNumber(j.at("illuminance"), "illuminance");
    if (lux < 0) r.fail("\"illuminance\" must not be negative");
    const double w = lux / kLumensPerWatt;
    sky.sunIrradiance = {w, w, w};
    requireNonNegative(r, sky.sunIrradiance, "illuminance");
  }
}

SkyDescription readSky(const json& j, const std::string& file) {
  ObjectReader r(j, "\"sky\"", file);
  SkyDescription sky;
  if (!r.has("type"))
    r.fail("needs \"type\": one of " + skyRegistry().namesText() + " (docs/daylight.md)");
  sky.model = r.string("type", "");
  sky.parameters = pluginParams(
      r, j, {"type", "sun", "up", "north", "ground_reflectance", "samples", "sun_samples"});
  // Checks the model's own keys now; its set-up (the physical sky's table) waits for daylight/.
  std::unique_ptr<SkyRadiance> model;
  try {
    model = skyRegistry().make(sky.model, sky.parameters);
  } catch (const ParamError& e) {
    r.fail(e.what());
  }
  if (model->needsSun() && !r.has("sun"))
    r.fail("(" + sky.model + ") needs a \"sun\": {\"elevation\": degrees}");
  if (r.has("sun")) readSun(j.at("sun"), file, model->computesSun(), sky);
  sky.up = r.vec3("up", sky.up);
  sky.north = r.vec3("north", sky.north);
  if (length(sky.up) == 0) r.fail("\"up\" must not be the zero vector");
  sky.up = normalize(sky.up);
  sky.north = sky.north - sky.up * dot(sky.north, sky.up);
  if (!(length(sky.north) > 1e-6))
    r.fail("\"north\" must not be parallel to \"up\". Fix: give a horizontal direction");
  sky.north = normalize(sky.north);
  sky.groundReflectance = r.number("ground_reflectance", sky.groundReflectance);
  if (!(sky.groundReflectance >= 0 && sky.groundReflectance < 1))
    r.fail("\"ground_reflectance\" must lie in [0, 1)");
  const double samples = r.number("samples", sky.samples);
  const double sunSamples = r.number("sun_samples", sky.sunSamples);
  if (!(samples >= 1 && samples <= 1 << 20 && samples == std::floor(samples)))
    r.fail("\"samples\" must be a whole number in [1, 1048576]");
  if (!(sunSamples >= 1 && sunSamples <= 1 << 16 && sunSamples == std::floor(sunSamples)))
    r.fail("\"sun_samples\" must be a whole number in [1, 65536]");
  sky.samples = int(samples);
  sky.sunSamples = int(sunSamples);
  return sky;
}

Camera readCamera(const json& j, const std::string& file) {
  ObjectReader r(j, "camera", file);
  r.allowOnly({"position", "look_at", "up", "fov_deg"});
  Camera c;
  c.position = r.vec3("position", c.position);
  c.lookAt = r.vec3("look_at", c.lookAt);
  c.up = r.vec3("up", c.up);
  c.fovDeg = r.number("fov_deg", c.fovDeg);
  if (!(c.fovDeg > 0 && c.fovDeg < 180)) r.fail("\"fov_deg\" must lie in (0, 180)");
  if (length(c.lookAt - c.position) == 0) r.fail("\"look_at\" must differ from \"position\"");
  return c;
}

Scene loadJsonScene(const std::string& path, const LoadOptions& options, LoadReport& report,
                    std::vector<bool>& selfIntersections) {
  const json root = readJsonFile(path, "scene file");
  Scene scene;
  scene.file = path;
  ObjectReader r(root, "the scene", path);
  r.allowOnly({"name", "description", "units", "materials", "surfaces", "camera", "sky"});
  scene.name = r.string("name", fs::path(path).stem().string());
  scene.units = r.string("units", options.units.empty() ? "m" : options.units);
  if (!isKnownUnit(scene.units))
    r.fail("has unknown \"units\" \"" + scene.units + "\". Fix: use one of " + unitList());
  if (!options.units.empty() && scene.units != options.units)
    r.fail("says \"units\": \"" + scene.units + "\" but " + setting("units") + " " + options.units +
           " was given. Fix: drop " + setting("units") + ", or change the scene's \"units\"");
  if (r.has("materials")) {
    const json& mats = root.at("materials");
    if (!mats.is_object()) r.fail("\"materials\" must be an object of named materials");
    for (auto it = mats.begin(); it != mats.end(); ++it)
      scene.materials.push_back(readMaterial(it.key(), it.value(), path));
  }
  MaterialIndex materialIndex;
  for (std::size_t m = 0; m < scene.materials.size(); ++m)
    materialIndex.emplace(scene.materials[m].name, int(m));
  const json& surfaces = r.get("surfaces");
  if (!surfaces.is_array()) r.fail("\"surfaces\" must be an array");
  for (std::size_t i = 0; i < surfaces.size(); ++i) {
    if (surfaces[i].is_object() && surfaces[i].contains("include")) {
      includeObj(surfaces[i], i, scene, materialIndex, path);
    } else {
      bool check = true;
      scene.surfaces.push_back(
          readSurface(surfaces[i], i, scene, materialIndex, path, options, report, check));
      selfIntersections.resize(scene.surfaces.size(), true);
      selfIntersections.back() = check;
    }
  }
  if (r.has("camera")) scene.camera = readCamera(root.at("camera"), path);
  if (r.has("sky")) scene.sky = readSky(root.at("sky"), path);
  return scene;
}

/// Whether a surface's geometry comes from a file format without units (STL, OBJ), where CAD
/// exports in millimetres are common.
bool fromUnitlessMesh(const Scene& scene, const Surface& s) {
  const auto endsWith = [](const std::string& text, const char* tail) {
    const std::string t = tail;
    return text.size() >= t.size() && text.compare(text.size() - t.size(), t.size(), t) == 0;
  };
  std::string source = s.source;
  std::transform(source.begin(), source.end(), source.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  std::string ext = fs::path(scene.file).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext == ".obj" || (source.find("(mesh ") != std::string::npos &&
                           (endsWith(source, ".stl)") || endsWith(source, ".obj)")));
}

/// A unitless mesh (STL, OBJ) over 10 m, alone or among room-sized surfaces, was probably
/// written in millimetres: a 31 mm bolt read as metres is a 31 m bolt. Returns whether it
/// warned.
bool warnOnUnitlessGiants(const Scene& scene, LoadReport& report) {
  if (scene.sky) return false;  // a street or a landscape may hold large meshes
  bool warned = false;
  constexpr double kLargestObjectMetres = 10, kRoomMetres = 20;
  const double unit = scene.metresPerUnit();
  std::vector<double> extent(scene.surfaces.size());
  for (std::size_t k = 0; k < scene.surfaces.size(); ++k) {
    Bounds3 b;
    for (const Vec3& v : scene.surfaces[k].vertices) b.extend(v);
    const Vec3 size = (b.hi - b.lo) * unit;
    extent[k] = std::max({size.x, size.y, size.z});
  }
  for (std::size_t k = 0; k < scene.surfaces.size(); ++k) {
    const Surface& s = scene.surfaces[k];
    if (extent[k] <= kLargestObjectMetres || !fromUnitlessMesh(scene, s)) continue;
    Bounds3 rest;
    bool others = false;
    for (std::size_t j = 0; j < scene.surfaces.size(); ++j)
      if (j != k && !fromUnitlessMesh(scene, scene.surfaces[j]))
        for (const Vec3& v : scene.surfaces[j].vertices) rest.extend(v), others = true;
    const Vec3 restSize = (rest.hi - rest.lo) * unit;
    const double room = others ? std::max({restSize.x, restSize.y, restSize.z}) : 0;
    if (others && !(room <= kRoomMetres && extent[k] > room)) continue;
    char text[200];
    std::snprintf(text, sizeof text, " spans %.4g m", extent[k]);
    std::string where =
        others ? std::string(text) + " in a room " + formatNumber(room, 3) + " m across"
               : std::string(text) + ", alone in the scene";
    report.warnings.push_back(
        s.source + where + ", read in " + scene.units +
        ". STL and OBJ files carry no unit, and CAD exports are often in millimetres. Fix: if it "
        "is in mm, give " +
        (others
             ? std::string("its surface \"transform\": {\"scale\": 0.001} (or " + setting("units") +
                           " "
                           "mm when the whole scene is in mm)")
             : std::string(setting("units") + " mm")) +
        ".");
    warned = true;
  }
  return warned;
}

/// A scene whose extent is far from a room's or an object's was probably written in another
/// unit than the one it is read in: areas and powers would be off by powers of 1000.
void warnOnImplausibleSize(const Scene& scene, LoadReport& report) {
  const Bounds3 b = scene.bounds();
  const Vec3 size = (b.hi - b.lo) * scene.metresPerUnit();
  const double largest = std::max({size.x, size.y, size.z});
  // Under a sky a scene is a street or a landscape, not a room.
  const double plausible = scene.sky ? kLargestPlausibleOutdoorMetres : kLargestPlausibleMetres;
  if (largest <= plausible && largest >= kSmallestPlausibleMetres) return;
  char text[160];
  std::snprintf(text, sizeof text, "%.4g m x %.4g m x %.4g m", size.x, size.y, size.z);
  report.warnings.push_back(
      scene.file + ": the scene spans " + text + " read in " + scene.units + ", " +
      (largest > plausible ? "large" : "small") +
      (scene.sky ? " for a landscape." : " for a room or an object.") +
      " Fix: if its coordinates are in another unit, give " + setting("units") + " " + unitList() +
      (fs::path(scene.file).extension() == ".json" ? " (or \"units\" in the scene file)" : "") +
      ".");
}

}  // namespace

const std::vector<std::pair<std::string, double>>& knownUnits() {
  static const std::vector<std::pair<std::string, double>> units{
      {"m", 1.0}, {"cm", 1e-2}, {"mm", 1e-3}, {"km", 1e3}, {"in", 0.0254}, {"ft", 0.3048}};
  return units;
}

Scene loadScene(const std::string& path, LoadReport* report, const LoadOptions& options) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  requireRegularFile(path, "scene file");
  if (!options.units.empty() && !isKnownUnit(options.units))
    throw InputError(setting("units") + " " + options.units +
                     " is not a unit radkit knows. Fix: use one of " + unitList() + ".");
  LoadReport local;
  LoadReport& out = report ? *report : local;
  Scene scene;
  ValidationSettings settings;
  settings.selfIntersections = options.selfIntersections;
  settings.progress = options.progress;
  if (ext == ".json")
    scene = loadJsonScene(path, options, out, settings.surfaceSelfIntersections);
  else if (ext == ".obj") {
    scene = loadObjScene(path, &out.warnings);
    if (std::none_of(scene.materials.begin(), scene.materials.end(),
                     [](const Material& m) { return m.emits(); }))
      throw InputError(
          path +
          ": no material emits light, so every result would be black. Fix: give the "
          "light's material an emission \"Ke r g b\" (W/m²) in the MTL file (Ka is ambient "
          "colour, which radkit does not read as emission); or, for a model without a lamp "
          "(a CAD part, a scan), include it from a JSON scene that adds one (\"include\", "
          "docs/formats.md), or stand it in a lit room with "
          "data/tools/make_model_room.py MODEL --out SCENE.json.");
  } else if (ext == ".stl" || ext == ".ply" || ext == ".off")
    // A bare mesh has neither materials nor a light: say how to give it both.
    throw InputError(path + ": this " +
                     std::string(ext == ".ply"   ? "PLY"
                                 : ext == ".off" ? "OFF"
                                                 : "STL") +
                     " file is a mesh without materials or lights, not a scene. Fix: name it "
                     "as a surface's \"mesh\" in a JSON scene, with a material and a lamp "
                     "(docs/formats.md), or stand it in a lit room with "
                     "data/tools/make_model_room.py MODEL --out SCENE.json.");
  else
    throw InputError(path + ": unknown scene format '" + ext +
                     "'. Fix: give a .json scene or an .obj with its .mtl.");
  if (ext == ".obj" && !options.units.empty()) scene.units = options.units;
  validateScene(scene, out, options.repair, settings);
  // A mesh named as too large says what the scene-wide size warning would, with its file.
  if (!warnOnUnitlessGiants(scene, out)) warnOnImplausibleSize(scene, out);
#ifdef __GLIBC__
  // Reading and checking a large mesh frees hundreds of megabytes of small blocks that malloc
  // keeps; hand them back, so the scene's own size is what the process holds from here on.
  malloc_trim(0);
#endif
  return scene;
}

}  // namespace radkit
