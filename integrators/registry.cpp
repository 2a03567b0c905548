// The image modes (integrator.h) and their one table. A mode is a function of the scene and
// the settings; the table gives each a name and a help line for `radkit render --shading`.
#include <optional>
#include <utility>

#include "integrators/integrator.h"
#include "photon/image.h"
#include "photon/map.h"
#include "photon/tracer.h"
#include "render/final_gather.h"
#include "render/shading.h"
#include "util/setting_names.h"

namespace radkit {

namespace {

void warn(const RenderSettings& s, RenderResult& out, const std::string& w) {
  out.warnings.push_back(w);
  if (s.warning) s.warning(w);
}

/// The surface each pixel centre sees, −1 where the ray escapes.
std::vector<int> pixelSurfaces(const RadianceImage& img, const PatchMesh& mesh) {
  std::vector<int> out(img.patch.size(), -1);
  for (std::size_t k = 0; k < out.size(); ++k)
    if (img.patch[k] >= 0) out[k] = mesh.patches[img.patch[k]].surface;
  return out;
}

RenderResult finish(RadianceImage img, const Scene& scene, const PatchMesh& mesh,
                    std::string what) {
  RenderResult out;
  out.emits = emitterPixels(img, scene, mesh);
  out.surfaces = pixelSurfaces(img, mesh);
  out.image = std::move(img);
  out.what = std::move(what);
  return out;
}

/// The mesh of the modes that do not solve radiosity; its warnings go to settings.warning.
PatchMesh ownMesh(const Scene& scene, const RenderSettings& s, bool defaultPatches) {
  SubdivisionSettings mesh = s.mesh;
  if (defaultPatches && mesh.maxArea <= 0 && mesh.targetPatches <= 0)
    mesh.targetPatches = kDefaultRenderPatches;
  return subdivideScene(scene, mesh, s.warning);
}

/// The radiosity solution the two-pass modes shade with.
PipelineResult solveRadiosity(const Scene& scene, const RenderSettings& s) {
  PipelineSettings settings;
  settings.mesh = s.mesh;
  if (settings.mesh.maxArea <= 0 && settings.mesh.targetPatches <= 0)
    settings.mesh.targetPatches = kDefaultRenderPatches;
  settings.formFactors = s.formFactors;
  settings.solvers = s.solvers;
  settings.stopping = s.stopping;
  return runPipeline(scene, settings, s.log);
}

class PhotonMapIntegrator final : public Integrator {
 public:
  RenderResult render(const Scene& scene, const RenderSettings& s) const override {
    // Final gathering over the global map plus the caustic map seen directly (Jensen 1996).
    const PatchMesh mesh = ownMesh(scene, s, true);
    const RayScene rays(mesh);
    const EmitterSampler emitters = photonEmitters(scene, mesh);
    PhotonSettings ps;
    ps.photons = s.photons;
    ps.seed = s.film.seed;
    ps.bsdf = s.bsdf;
    ps.gatherRays = s.gatherRays;
    PhotonMaps maps = buildPhotonMaps(mesh, tracePhotons(scene, mesh, rays, emitters, ps).photons);
    maps.global->precomputeIrradiance(ps.neighbours, ps.filter, ps.precomputeStride);
    const PhotonScene photons{scene, mesh, rays, emitters, *maps.global, *maps.caustic};
    const int width = s.film.width, height = s.film.height;
    RadianceImage img =
        renderPhotonImage(photons, s.camera, width, height, PhotonView::FinalGather, ps);
    // One jittered ray per pixel per pass; more passes are averaged, each pass its own
    // camera stream. A pass costs its gathers.
    const int passes = std::max(1, s.photonPasses);
    for (int pass = 1; pass < passes; ++pass) {
      PhotonSettings more = ps;
      more.seed = s.film.seed + std::uint64_t(pass);
      const RadianceImage next =
          renderPhotonImage(photons, s.camera, width, height, PhotonView::FinalGather, more);
      for (std::size_t k = 0; k < img.radiance.size(); ++k)
        img.radiance[k] = img.radiance[k] + next.radiance[k];
    }
    for (Vec3& v : img.radiance) v = v / double(passes);
    RenderResult out =
        finish(std::move(img), scene, mesh,
               std::to_string(s.photons) + " photons, " + std::to_string(maps.global->size()) +
                   " stored, " + std::to_string(ps.gatherRays) + " gather rays per pixel, " +
                   std::to_string(passes) + " pass(es)");
    return out;
  }
};

class PathTraceIntegrator final : public Integrator {
 public:
  RenderResult render(const Scene& scene, const RenderSettings& s) const override {
    const PatchMesh mesh = ownMesh(scene, s, false);
    // Embree's fast mode: about 15 % less time per ray, for a ray in 10⁷ that slips through a
    // shared edge (geometry/ray_scene.h). Under a sky such a ray would fetch daylight inside a
    // closed room, a firefly, so daylit scenes keep the robust mode.
    const RayScene rays(mesh, 0, scene.sky ? RayRobustness::Robust : RayRobustness::Fast);
    const ShadingScene shading(scene, mesh, rays, s.bsdf, GlossyModel::AsDeclared, s.light);
    PathTraceSettings p;
    p.width = s.film.width, p.height = s.film.height, p.samplesPerPixel = s.film.samplesPerPixel,
    p.seed = s.film.seed, p.sampler = s.film.sampler;
    p.rouletteDepth = s.rouletteDepth, p.maxDepth = s.maxDepth;
    MonteCarloImage img = renderPathTraced(shading, s.camera, p);
    return finish(std::move(img.image), scene, mesh,
                  std::to_string(img.paths) + " paths, " + std::to_string(img.rays) + " rays in " +
                      std::to_string(img.seconds) + " s");
  }
};

class RadiosityIntegrator final : public Integrator {
 public:
  RenderResult render(const Scene& scene, const RenderSettings& s) const override {
    const PipelineResult r = solveRadiosity(scene, s);
    ImageSettings is;
    is.width = s.film.width, is.height = s.film.height, is.smooth = s.smooth,
    is.smoothing = s.smoothing;
    if (r.sky) is.background = [&](const Vec3& d) { return r.sky->radiance(d); };
    const std::vector<bool> twoSided = scene.twoSidedSurfaces();
    RadianceImage img = renderRadiosity(r.mesh, *r.rays, s.camera, r.radiosity, twoSided, is);
    return finish(std::move(img), scene, r.mesh, std::to_string(r.mesh.size()) + " patches");
  }
};

class FinalGatherIntegrator final : public Integrator {
 public:
  RenderResult render(const Scene& scene, const RenderSettings& s) const override {
    const PipelineResult r = solveRadiosity(scene, s);
    const ShadingScene shading(scene, r.mesh, *r.rays, s.bsdf, GlossyModel::AsDeclared, s.light);
    FinalGatherSettings f;
    f.width = s.film.width, f.height = s.film.height, f.samplesPerPixel = s.film.samplesPerPixel,
    f.seed = s.film.seed, f.sampler = s.film.sampler;
    f.smoothing = s.smoothing;
    const RadiosityLighting lighting = radiosityLighting(r);
    std::optional<GatherGuide> guide;
    if (s.guided) guide.emplace(r.formFactors->matrix, lighting);
    MonteCarloImage img =
        renderFinalGather(shading, s.camera, lighting, f, guide ? &*guide : nullptr);
    return finish(std::move(img.image), scene, r.mesh,
                  std::to_string(r.mesh.size()) + " patches, " + std::to_string(img.paths) +
                      " gathers in " + std::to_string(img.seconds) + " s");
  }
};

/// Radiosity for the diffuse light, the glossy materials shaded as `m_glossy`.
class TwoPassIntegrator final : public Integrator {
 public:
  explicit TwoPassIntegrator(GlossyModel glossy) : m_glossy(glossy) {}
  RenderResult render(const Scene& scene, const RenderSettings& s) const override {
    const PipelineResult r = solveRadiosity(scene, s);
    const ShadingScene shading(scene, r.mesh, *r.rays, s.bsdf, m_glossy, s.light);
    TwoPassSettings t;
    t.width = s.film.width, t.height = s.film.height, t.samplesPerPixel = s.film.samplesPerPixel,
    t.seed = s.film.seed, t.sampler = s.film.sampler;
    MonteCarloImage img = renderTwoPass(shading, s.camera, radiosityLighting(r), t);
    RenderResult out =
        finish(std::move(img.image), scene, r.mesh,
               std::to_string(r.mesh.size()) + " patches, " + std::to_string(img.paths) +
                   " camera samples in " + std::to_string(img.seconds) + " s");
    out.warnings = r.warnings;
    // The two modes differ only in how glossy materials are shaded.
    if (!hasGlossyMaterial(scene, s.bsdf))
      warn(s, out,
           scene.file + ": no surface has a glossy (phong or cook-torrance) material, so " +
               setting("shading") + " phong and " + setting("shading") +
               " cook-torrance give the same image. Fix: give "
               "materials \"brdf\": \"phong\" or \"cook-torrance\" (data/cornell-box-glossy.json "
               "has both)");
    return out;
  }

 private:
  GlossyModel m_glossy;
};

template <class T>
std::unique_ptr<Integrator> create(Params&) {
  return std::make_unique<T>();
}
std::unique_ptr<Integrator> createPhong(Params&) {
  return std::make_unique<TwoPassIntegrator>(GlossyModel::Phong);
}
std::unique_ptr<Integrator> createCookTorrance(Params&) {
  return std::make_unique<TwoPassIntegrator>(GlossyModel::CookTorrance);
}

}  // namespace

const Registry<Integrator>& integratorRegistry() {
  static const Registry<Integrator> registry(
      "integrator",
      {
          {"radiosity", create<RadiosityIntegrator>,
           "the radiosity solution seen by the camera (flat, or smoothed)", ""},
          {"phong", createPhong,
           "two-pass: radiosity for diffuse light, glossy materials shaded as Phong", ""},
          {"cook-torrance", createCookTorrance,
           "two-pass: glossy materials shaded as Cook-Torrance", ""},
          {"path-trace", create<PathTraceIntegrator>,
           "unidirectional path tracing with MIS (the reference)", ""},
          {"photon-map", create<PhotonMapIntegrator>,
           "photon mapping with final gathering (photon count and gather rays)", ""},
          {"final-gather", create<FinalGatherIntegrator>,
           "one gather bounce over the radiosity solution", ""},
      });
  return registry;
}

RenderResult renderImage(const std::string& shading, const Scene& scene,
                         const RenderSettings& settings) {
  const PluginChoice mode = splitPluginChoice(shading);  // "name:key=value;key=value"
  return integratorRegistry()
      .make(mode.name, Params::parse(mode.parameters))
      ->render(scene, settings);
}

}  // namespace radkit
