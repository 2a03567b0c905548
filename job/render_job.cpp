#include "job/render_job.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "job/job.h"
#include "job/report.h"
#include "render/camera.h"
#include "render/exr_io.h"
#include "render/hdr_io.h"
#include "util/errors.h"
#include "util/format.h"
#include "util/output_folder.h"
#include "util/setting_names.h"

namespace radkit {

namespace {

/// Region errors against the reference renders: each surface, the lit surfaces away from
/// edges (emitters and aliased edges swamp "all"), the edges.
std::vector<RegionError> regionErrors(const Scene& scene, const RenderResult& mode,
                                      const std::vector<RadianceImage>& refs) {
  const RadianceImage& img = mode.image;
  std::vector<std::string> names;
  for (const Surface& s : scene.surfaces) names.push_back(s.name);
  names.push_back("edges");
  const std::vector<int> region =
      surfaceRegions(mode.surfaces, img.width, img.height, int(names.size()) - 1);
  std::vector<int> lit(region.size(), -1);
  for (std::size_t k = 0; k < region.size(); ++k)
    if (region[k] >= 0 && region[k] < int(scene.surfaces.size()) &&
        !scene.materials[scene.surfaces[region[k]].material].emits())
      lit[k] = 0;
  try {
    std::vector<RegionError> errors = compareToReference(img, refs, region, names);
    errors.insert(errors.begin() + 1, compareToReference(img, refs, lit, {"surfaces"})[1]);
    return errors;
  } catch (const std::invalid_argument& e) {
    throw InputError(std::string(e.what()) + ". Fix: render the image at the reference's " +
                     setting("size"));
  }
}

void writeReport(const RenderJobSettings& s, const LoadReport& loaded, const RenderJobResult& r) {
  nlohmann::json rows = nlohmann::json::array();
  for (const RegionError& e : r.errors) {
    if (e.pixels == 0) continue;
    rows.push_back({{"region", e.name},
                    {"pixels", e.pixels},
                    {"reference_mean", e.referenceMean},
                    {"raw_rmse", e.rawRmse},
                    {"reference_noise", e.referenceNoise},
                    {"rmse", e.rmse},
                    {"relative_rmse", e.relative()}});
  }
  const FilmSettings& film = s.render.film;
  const nlohmann::json j{{"shading", s.shading},
                         {"load", loadJson(loaded)},
                         {"warnings", r.mode.warnings},
                         {"smooth", s.render.smooth},
                         {"sampler", samplerName(film.sampler)},
                         {"light_sampling", lightSamplingName(s.render.light)},
                         {"spp", film.samplesPerPixel},
                         {"width", r.mode.image.width},
                         {"height", r.mode.image.height},
                         {"seconds", r.seconds},
                         {"references", s.references},
                         {"regions", rows}};
  writeJson(s.report, j);
}

}  // namespace

RenderJobResult runRenderJob(const RenderJobSettings& given, const PipelineLog& log) {
  RenderJobSettings s = given;
  const int width = s.render.film.width, height = s.render.film.height;
  // Refused before the render, which may take minutes, rather than when it is written.
  checkOutputFile(setting("out"), s.out);
  if (!s.report.empty()) {
    if (s.references.empty())
      throw InputError(setting("report") + " " + s.report + " needs " + setting("reference") +
                       ": the report holds the errors against it");
    checkOutputFile(setting("report"), s.report);
  }
  std::string ext = std::filesystem::path(s.out).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  if (ext != ".png" && ext != ".pfm" && ext != ".exr")
    throw InputError(setting("out") + " " + s.out + ": '" + ext +
                     "' is not an image format render writes (PNG bytes under "
                     "another name would mislead). Fix: end the name in .png (tone mapped), .exr "
                     "or .pfm (linear "
                     "radiance, W/m²/sr)");
  // References are read and their size checked first: a mismatch found after the render left
  // the image behind.
  std::vector<RadianceImage> refs;
  for (const std::string& f : s.references) {
    refs.push_back(readPfm(f));
    if (refs.back().width != width || refs.back().height != height)
      throw InputError(setting("reference") + " " + f + " is " + std::to_string(refs.back().width) +
                       "x" + std::to_string(refs.back().height) + ", the image " + setting("size") +
                       " " + std::to_string(width) + "x" + std::to_string(height) +
                       ". Fix: render at the reference's " + setting("size"));
  }
  LoadReport loaded;
  const Scene scene = loadJobScene(s.scene, s.load, s.camera, log, &loaded);
  RenderJobResult r;
  r.sceneName = scene.name, r.sceneFile = scene.file;
  const auto start = std::chrono::steady_clock::now();
  s.render.camera = chooseCamera(scene);  // loading put a given camera into the scene
  if (!s.render.log.progress) s.render.log = log;
  try {
    r.mode = renderImage(s.shading, scene, s.render);
  } catch (const TooManyPatches&) {
    SubdivisionSettings mesh = s.render.mesh;
    if (mesh.maxArea <= 0 && mesh.targetPatches <= 0) mesh.targetPatches = kDefaultRenderPatches;
    throwTooManyPatches(scene, mesh);
  }
  r.seconds = secondsSince(start);
  const RadianceImage& img = r.mode.image;
  r.format = ext.substr(1);
  r.exposure = s.exposure > 0 ? s.exposure : autoExposure(img, r.mode.emits);
  if (ext == ".pfm")
    writePfm(s.out, img);
  else if (ext == ".exr")
    writeExr(s.out, img);
  else
    writePng(s.out, toneMapCurve(img, r.exposure, s.tonemap));
  if (!refs.empty()) {
    r.errors = regionErrors(scene, r.mode, refs);
    if (!s.report.empty()) writeReport(s, loaded, r);
  }
  return r;
}

}  // namespace radkit
