// Volume scene files (medium_json.h). Keys are read with geometry/json_reader.h's ObjectReader,
// as scene files are, so unknown keys and bad values get the same "FILE: WHERE ... Fix:" errors.
#include "media/medium_json.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <utility>

#include "geometry/json_reader.h"
#include "util/errors.h"
#include "util/format.h"

namespace radkit::media {

using nlohmann::json;

namespace {
// A named namespace inside the anonymous one: unity batches join this file's helpers with
// the other media files'.
namespace volumescene {

/// The default phase function of clouds: HG with the mean cosine of the Mie table for 10 µm
/// droplets (docs/clouds.md).
constexpr const char* kDefaultPhase = "henyey-greenstein";
constexpr const char* kDefaultPhaseParams = "g=0.86";

/// x checked against [lo, hi] (open where flagged), with the range in the message.
double inRange(ObjectReader& r, const std::string& key, double x, double lo, double hi, bool openLo,
               bool openHi, const std::string& why = "") {
  if ((openLo ? x > lo : x >= lo) && (openHi ? x < hi : x <= hi)) return x;
  r.fail("\"" + key + "\" " + formatNumber(x) + " is outside " + (openLo ? "(" : "[") +
         formatNumber(lo) + ", " + formatNumber(hi) + (openHi ? ")" : "]") + why +
         ". Fix: give a value in that range");
}

double positive(ObjectReader& r, const std::string& key, double x) {
  if (!(x > 0))
    r.fail("\"" + key + "\" must be greater than 0, not " + formatNumber(x) +
           ". Fix: give a positive number");
  return x;
}

/// An integer in [lo, hi].
long long whole(ObjectReader& r, const std::string& key, double x, double lo, double hi) {
  if (!(x >= lo && x <= hi && x == std::floor(x)))
    r.fail("\"" + key + "\" must be a whole number in [" + formatNumber(lo, 10) + ", " +
           formatNumber(hi, 10) + "], not " + formatNumber(x) + ". Fix: give one in that range");
  return (long long)x;
}

/// "phase": a registry name, or {"name": ..., parameter: number, ...}, turned into the
/// "k=v, k=v" text makePhaseFunction takes (numbers printed to round-trip exactly).
std::unique_ptr<PhaseFunction> readPhase(const json& parent, const std::string& file,
                                         std::string& name, std::string& params) {
  name = kDefaultPhase, params = kDefaultPhaseParams;
  if (parent.contains("phase")) {
    const json& j = parent.at("phase");
    if (j.is_string()) {
      name = j.get<std::string>(), params.clear();
    } else {
      ObjectReader r(j, "medium's \"phase\"", file);
      const json& n = r.get("name");
      if (!n.is_string())
        r.fail(
            "\"name\" must be a string. Fix: name a phase function, e.g. "
            "\"henyey-greenstein\"");
      name = n.get<std::string>(), params.clear();
      for (auto it = j.begin(); it != j.end(); ++it) {
        if (it.key() == "name") continue;
        char text[32];
        std::snprintf(text, sizeof text, "%.17g", r.toNumber(it.value(), it.key()));
        params += (params.empty() ? "" : ", ") + it.key() + "=" + text;
      }
    }
  }
  try {
    return makePhaseFunction(name, params);
  } catch (const std::invalid_argument& e) {
    std::string names;
    for (const std::string& n : phaseFunctionNames()) names += (names.empty() ? "" : ", ") + n;
    throw InputError(file + ": medium's \"phase\": " + e.what() + ". Fix: name one of " + names +
                     " and give only its parameters, within their ranges (docs/formats.md)");
  }
}

std::unique_ptr<Medium> readCloudLayer(const json& j, const std::string& file, std::string& name,
                                       std::string& params) {
  ObjectReader r(j, "medium (cloud-layer)", file);
  r.allowOnly({"type", "bottom", "top", "size", "coverage", "cloud_type", "extinction", "albedo",
               "shape_period", "detail_period", "detail_erosion", "weather_period", "shape_size",
               "detail_size", "seed", "phase"});
  CloudLayerSettings s;
  s.bottom = r.number("bottom", s.bottom);
  if (!(s.bottom >= 0))
    r.fail("\"bottom\" must not be negative. Fix: give metres above the ground, 0 or more");
  s.top = r.number("top", s.top);
  if (!(s.top > s.bottom))
    r.fail("\"top\" " + formatNumber(s.top) + " must be above \"bottom\" " +
           formatNumber(s.bottom) + ". Fix: give the layer a positive thickness");
  s.size = positive(r, "size", r.number("size", s.size));
  s.coverage = inRange(r, "coverage", r.number("coverage", s.coverage), 0, 1, false, false);
  s.cloudType = inRange(r, "cloud_type", r.number("cloud_type", s.cloudType), 0, 1, false, false,
                        " (0 stratus, 0.5 stratocumulus, 1 cumulus)");
  s.extinction = positive(r, "extinction", r.number("extinction", s.extinction));
  s.albedo = inRange(r, "albedo", r.number("albedo", s.albedo), 0, 1, false, false);
  s.shapePeriod = positive(r, "shape_period", r.number("shape_period", s.shapePeriod));
  s.detailPeriod = positive(r, "detail_period", r.number("detail_period", s.detailPeriod));
  s.detailErosion =
      inRange(r, "detail_erosion", r.number("detail_erosion", s.detailErosion), 0, 1, false, true);
  s.weatherPeriod = positive(r, "weather_period", r.number("weather_period", s.weatherPeriod));
  s.shapeSize = int(whole(r, "shape_size", r.number("shape_size", s.shapeSize), 8, 512));
  s.detailSize = int(whole(r, "detail_size", r.number("detail_size", s.detailSize), 8, 512));
  s.seed = std::uint32_t(whole(r, "seed", r.number("seed", s.seed), 0, 4294967295.0));
  std::unique_ptr<PhaseFunction> phase = readPhase(j, file, name, params);
  return std::make_unique<CloudLayer>(s, std::move(phase));
}

std::unique_ptr<Medium> readHomogeneousBox(const json& j, const std::string& file,
                                           std::string& name, std::string& params) {
  ObjectReader r(j, "medium (homogeneous-box)", file);
  r.allowOnly({"type", "min", "max", "extinction", "albedo", "phase"});
  const Vec3 lo = r.toVec3(r.get("min"), "min"), hi = r.toVec3(r.get("max"), "max");
  if (!(hi.x > lo.x && hi.y > lo.y && hi.z > lo.z))
    r.fail(
        "\"max\" must exceed \"min\" in every axis. Fix: give the box's lowest corner as "
        "\"min\" and its highest as \"max\"");
  const double extinction =
      positive(r, "extinction", r.toNumber(r.get("extinction"), "extinction"));
  const double albedo = inRange(r, "albedo", r.number("albedo", 1), 0, 1, false, false);
  Bounds3 box;
  box.extend(lo);
  box.extend(hi);
  std::unique_ptr<PhaseFunction> phase = readPhase(j, file, name, params);
  return std::make_unique<HomogeneousBox>(box, extinction, albedo, std::move(phase));
}

Camera readVolumeCamera(const json& j, const std::string& file) {
  ObjectReader r(j, "camera", file);
  r.allowOnly({"position", "look_at", "up", "fov_deg"});
  Camera c;
  c.position = r.vec3("position", {0, 0, 1.7});
  c.lookAt = r.toVec3(r.get("look_at"), "look_at");
  c.up = r.vec3("up", {0, 0, 1});
  c.fovDeg = r.number("fov_deg", 70);
  if (!(c.fovDeg > 0 && c.fovDeg < 180))
    r.fail("\"fov_deg\" " + formatNumber(c.fovDeg) +
           " must lie in (0, 180). Fix: give the full vertical field of view in degrees");
  const Vec3 forward = c.lookAt - c.position;
  if (length(forward) == 0)
    r.fail("\"look_at\" must differ from \"position\". Fix: give the point the camera looks at");
  if (length(cross(forward, c.up)) == 0)
    r.fail("\"up\" must not be parallel to the view direction. Fix: give [0, 0, 1]");
  return c;
}

}  // namespace volumescene
}  // namespace

std::unique_ptr<Medium> parseMedium(const json& j, const std::string& file, std::string* kind,
                                    std::string* phaseName, std::string* phaseParams) {
  using namespace volumescene;
  ObjectReader r(j, "medium", file);
  const std::string type = r.string("type", "");
  std::string name, params;
  std::unique_ptr<Medium> medium;
  if (type == "cloud-layer")
    medium = readCloudLayer(j, file, name, params);
  else if (type == "homogeneous-box")
    medium = readHomogeneousBox(j, file, name, params);
  else
    r.fail((type.empty() ? std::string("has no \"type\"")
                         : "has the unknown \"type\" \"" + type + "\"") +
           ". Fix: use \"cloud-layer\" or \"homogeneous-box\"");
  if (kind) *kind = type;
  if (phaseName) *phaseName = name;
  if (phaseParams) *phaseParams = params;
  return medium;
}

VolumeScene loadVolumeScene(const std::string& path) {
  using namespace volumescene;
  const json root = readJsonFile(path, "volume scene file");
  ObjectReader r(root, "the volume scene", path);
  r.allowOnly({"description", "medium", "sun", "camera", "ground_albedo"});
  VolumeScene scene;
  scene.file = path;
  const json& medium = r.get("medium");
  if (r.has("sun")) {
    ObjectReader sun(root.at("sun"), "\"sun\"", path);
    sun.allowOnly({"elevation", "azimuth"});
    if (sun.has("elevation"))
      scene.sunElevationDeg =
          inRange(sun, "elevation", sun.number("elevation", 0), -90, 90, false, false, " degrees");
    if (sun.has("azimuth"))
      scene.sunAzimuthDeg = inRange(sun, "azimuth", sun.number("azimuth", 0), -360, 360, false,
                                    false, " degrees clockwise from north");
  }
  if (r.has("camera")) scene.camera = readVolumeCamera(root.at("camera"), path);
  scene.groundAlbedo = inRange(r, "ground_albedo", r.number("ground_albedo", 0), 0, 1, false, true);
  if (scene.groundAlbedo > 0 && scene.camera && !(scene.camera->position.z > 0))
    r.fail(
        "\"camera\" stands at or below the ground (z = 0) that \"ground_albedo\" puts there. "
        "Fix: give the camera a position with z > 0");
  // The medium last: a cloud layer's noise takes seconds to build, after every cheap check.
  scene.medium = parseMedium(medium, path, &scene.kind, &scene.phaseName, &scene.phaseParams);
  if (scene.groundAlbedo > 0 && scene.medium->bounds().lo.z < 0)
    r.fail(
        "\"medium\" reaches below the ground (z = 0) that \"ground_albedo\" puts there. "
        "Fix: keep the medium at z >= 0, or set \"ground_albedo\" to 0");
  return scene;
}

}  // namespace radkit::media
