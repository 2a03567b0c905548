// ShadingScene: what the Monte Carlo image modes (path tracing, two-pass Phong and
// Cook-Torrance) share: a BSDF per material, emission and sidedness per patch, emitter
// sampling, and the two estimators every mode uses, next-event estimation with multiple
// importance sampling and the MIS weight of a BSDF-sampled ray that finds an emitter.
#pragma once

#include <functional>
#include <string>

#include <memory>
#include <optional>
#include <vector>

#include "bsdf/bsdf.h"
#include "daylight/sky.h"
#include "geometry/patch_mesh.h"
#include "geometry/ray_scene.h"
#include "geometry/visibility.h"
#include "render/emitters.h"
#include "render/radiosity_image.h"
#include "render/sampler.h"
#include "render/spherical_rectangle.h"
#include "util/sampling.h"

namespace radkit {

/// Which model glossy materials are shaded with. Lambert, mirror and glass are unaffected.
enum class GlossyModel {
  AsDeclared,  ///< each material's own "brdf"
  Phong,  ///< Cook-Torrance materials as Phong: n = 2/α² − 2, ks = F0 (Walter et al. 2007, eq. 35)
  CookTorrance,  ///< Phong materials as Cook-Torrance: α = √(2/(n + 2)), f0 = ks, metallic 0
};

/// \brief Whether a surface's material has a glossy lobe that GlossyModel can swap (phong or
/// cook-torrance); without one the Phong and Cook-Torrance two-pass images are the same.
bool hasGlossyMaterial(const Scene& scene, const BsdfSettings& settings);

/// How next-event estimation picks a point on the chosen emitter.
enum class LightSampling {
  Area,        ///< uniformly by area (density ∝ cos θ'/r² per steradian)
  SolidAngle,  ///< rectangles uniformly by solid angle (Ureña et al. 2013), others by area
};
/// "area" or "solid-angle"; throws std::invalid_argument otherwise.
LightSampling parseLightSampling(const std::string& name);
/// The name parseLightSampling reads.
std::string lightSamplingName(LightSampling sampling);

/// A surface point seen along a ray, in the frame in which its BSDF is evaluated.
struct SurfaceHit {
  int patch = -1;
  double distance = 0;
  Vec3 point;
  Vec3 normal;  ///< the patch's front normal, flipped toward wo for two-sided materials
  Frame frame{Vec3{0, 0, 1}};
  Vec3 wo;                     ///< toward the ray origin, local to `frame`
  bool front = false;          ///< wo on the side of the patch's front normal
  const Bsdf* bsdf = nullptr;  ///< null on the back of a one-sided surface (it absorbs)
};

/// Monte Carlo image with its per-pixel error: the sample variance of each pixel's mean.
struct MonteCarloImage {
  RadianceImage image;
  /// s²/n per pixel and channel, (W/m²/sr)²: exact in expectation for independent samples;
  /// stratified and Sobol samples usually do better than it, so for them it is a
  /// conservative bar (render with several seeds for an honest one).
  std::vector<Vec3> varianceOfMean;
  long long paths = 0;  ///< camera samples traced
  long long rays = 0;   ///< closest-hit and shadow rays cast
  double seconds = 0;   ///< wall time of the render
};

/// The camera-sample loop shared by the Monte Carlo image modes.
struct PixelSampling {
  int width = 256, height = 256;
  int samplesPerPixel = 16;
  std::uint64_t seed = 1;
  std::uint64_t stream = 0;  ///< keys pixel (x, y)'s numbers with (seed, y·width + x)
  SamplerType sampler = SamplerType::Sobol;
};

/// Estimates the radiance along one camera ray; adds the rays it casts to `rays`.
using CameraSampleRadiance = std::function<Vec3(const Vec3& origin, const Vec3& direction,
                                                Sampler& sampler, long long& rays)>;

class ShadingScene;

/// \brief Averages samplesPerPixel camera samples per pixel, jittered by the sampler's first
/// 2-D dimension (parallel over rows, deterministic), with the variance of each pixel mean and the
/// patch seen at the pixel centre.
MonteCarloImage renderCameraSamples(const ShadingScene& scene, const Camera& camera,
                                    const PixelSampling& sampling,
                                    const CameraSampleRadiance& radiance);

class ShadingScene {
 public:
  /// \brief The scene and mesh must outlive this object; `rays` answers for `mesh`.
  ShadingScene(const Scene& scene, const PatchMesh& mesh, const Visibility& rays,
               const BsdfSettings& bsdf, GlossyModel glossy = GlossyModel::AsDeclared,
               LightSampling light = LightSampling::Area);

  const PatchMesh& mesh() const { return m_mesh; }
  const Visibility& rays() const { return m_rays; }
  const EmitterSampler& emitters() const { return m_emitters; }

  /// \brief First surface along origin + t·dir (dir unit), t > tMin; its local frame.
  std::optional<SurfaceHit> intersect(const Vec3& origin, const Vec3& dir, double tMin = 0) const;
  /// \brief Radiance E/π leaving the front of an emitting patch; zero on the back.
  Vec3 emitted(const SurfaceHit& hit) const;
  /// \brief Origin for a ray leaving `hit` along world direction dir (lifted off the plane).
  Vec3 spawn(const SurfaceHit& hit, const Vec3& dir) const;

  /// \brief Next-event estimate of reflected direct light at a non-delta hit: one emitter
  /// (by power, a 1-D sample) and a point on it (a 2-D sample: uniform in solid angle for a
  /// rectangle seen under at least kMinSolidAngle with LightSampling::SolidAngle, else
  /// uniform by area), a shadow ray, weighted against BSDF sampling by the power heuristic.
  /// \param rays incremented by the shadow rays cast
  Vec3 directLight(const SurfaceHit& hit, Sampler& sampler, long long& rays) const;
  /// \brief Solid-angle density with which directLight() at `from` (the previous vertex's
  /// point) would pick the emitter point hit at `light` (0 on the back of the emitter).
  double lightPdf(const SurfaceHit& light, const Vec3& from) const;
  LightSampling lightSampling() const { return m_lightSampling; }

  /// Whether the scene declares a "sky" (daylight: a sky, and perhaps the sun's disc).
  bool hasSky() const { return m_sky.has_value(); }
  /// The scene's sky and its direction sampler (null without a "sky"), for photon emission.
  const SkyModel* sky() const { return m_sky ? &*m_sky : nullptr; }
  const SkySampler* skySampler() const { return m_skySampler.get(); }
  /// \brief Next-event estimate of the daylight reflected at a non-delta hit: one direction
  /// drawn by the sky's radiance (SkySampler) and one in the sun's disc, each with a ray that
  /// must leave the scene, each weighted against BSDF sampling by the power heuristic. Zero
  /// without a sky. Always takes one 1-D and two 2-D samples from `sampler`.
  Vec3 skyLight(const SurfaceHit& hit, Sampler& sampler, long long& rays) const;
  /// \brief Radiance of a ray that leaves the scene along unit `dir`: the sky and, inside its
  /// disc, the sun. After a non-specular bounce (`bsdfPdf` the density that drew dir) each is
  /// weighted against skyLight()'s sampling; after the camera or a delta lobe (`specular`) not.
  Vec3 escaped(const Vec3& dir, double bsdfPdf, bool specular) const;

  /// Below this solid angle (sr) rectangles are sampled by area: the angle sum that gives Ω
  /// loses relative precision as Ω shrinks (measured: 4e-10 at 4e-3 sr, 1e-5 at 2e-4 sr),
  /// and so small a light is nearly uniform in solid angle anyway.
  static constexpr double kMinSolidAngle = 1e-3;

 private:
  /// The emitter `patch` as a spherical rectangle seen from `from`, when directLight samples
  /// it by solid angle there.
  std::optional<SphericalRectangle> solidAngleSampling(int patch, const Vec3& from) const;

  const PatchMesh& m_mesh;
  const Visibility& m_rays;
  EmitterSampler m_emitters;
  LightSampling m_lightSampling;
  std::vector<std::unique_ptr<Bsdf>> m_bsdfs;  ///< per material
  std::vector<int> m_material;                 ///< per surface
  std::vector<bool> m_twoSided, m_transmits;   ///< per material
  std::vector<Vec3> m_emission;                ///< per material
  std::optional<SkyModel> m_sky;               ///< the scene's "sky", if it has one
  std::unique_ptr<SkySampler> m_skySampler;    ///< directions by the sky's radiance
  Vec3 m_sunRadiance;                          ///< E_n / Ω over the sun's disc (0: no sun)
  double m_sunSolidAngle = 0;                  ///< Ω = 2π(1 − cos r)
};

/// \brief The BSDF a material is shaded with under `glossy` (the table of substitutions).
std::unique_ptr<Bsdf> makeShadingBsdf(const Material& material, const BsdfSettings& settings,
                                      GlossyModel glossy);

}  // namespace radkit
