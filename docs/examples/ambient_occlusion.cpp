// docs/extending.md, example 5: an image mode. Ambient occlusion: each pixel shows the share
// of cosine-weighted rays from the surface it sees that leave without hitting anything within
// `distance` (0: any distance). With distance 0 that share is 1 − F, F being the form factor
// from the point to everything around it, so the mode is a picture of what a point sees.
// Built and run by tests/extending/.
#include <tbb/parallel_for.h>

#include <memory>
#include <string>

#include "geometry/ray_scene.h"
#include "geometry/subdivision.h"
#include "integrators/integrator.h"
#include "render/camera.h"
#include "util/frame.h"
#include "util/params.h"
#include "util/sampling.h"

namespace radkit {

namespace {

class AmbientOcclusionIntegrator final : public Integrator {
 public:
  AmbientOcclusionIntegrator(int rays, double distance) : m_rays(rays), m_distance(distance) {}

  RenderResult render(const Scene& scene, const RenderSettings& s) const override {
    const PatchMesh mesh = subdivide(scene, {});  // the surfaces whole: no light is solved
    const RayScene rays(mesh);
    const PinholeCamera camera(s.camera, s.film.width, s.film.height);
    const double reach = m_distance > 0 ? m_distance : std::numeric_limits<double>::infinity();
    RenderResult out;
    RadianceImage& img = out.image;
    img.width = s.film.width, img.height = s.film.height;
    const std::size_t pixels = std::size_t(img.width) * std::size_t(img.height);
    img.radiance.assign(pixels, Vec3{});
    img.patch.assign(pixels, -1);
    out.surfaces.assign(pixels, -1);
    out.emits.assign(pixels, false);
    tbb::parallel_for(0, img.height, [&](int y) {
      for (int x = 0; x < img.width; ++x) {
        const std::size_t k = std::size_t(y) * std::size_t(img.width) + std::size_t(x);
        const Vec3 d = camera.direction(x + 0.5, y + 0.5);
        const std::optional<RayHit> hit = rays.closestHit(camera.origin(), d, 0);
        if (!hit) continue;
        const Patch& p = mesh.patches[hit->patch];
        const Vec3 n = dot(p.normal, d) < 0 ? p.normal : -p.normal;  // the side seen
        const Vec3 point = camera.origin() + d * hit->distance;
        const Frame frame(n);
        // Every pixel its own stream: the same seed gives the same image on any thread count.
        Rng rng(s.film.seed, k, 0);
        int open = 0;
        for (int r = 0; r < m_rays; ++r) {
          const Vec3 w = frame.toWorld(sampleCosineHemisphere(rng.uniform(), rng.uniform()));
          open += !rays.closestHit(point, w, rays.epsilon(), reach);
        }
        const double share = double(open) / m_rays;
        img.radiance[k] = {share, share, share};
        img.patch[k] = hit->patch;
        out.surfaces[k] = p.surface;
      }
    });
    out.what = std::to_string(m_rays) + " occlusion rays per pixel" +
               (m_distance > 0 ? " within " + std::to_string(m_distance) : "");
    return out;
  }

 private:
  int m_rays;
  double m_distance;
};

}  // namespace

// The registry calls this with the mode's own parameters and refuses keys it did not read.
std::unique_ptr<Integrator> createAmbientOcclusion(Params& params) {
  const int rays = int(params.integer("rays", 64, 1, 1 << 20));
  const double distance = params.number("distance", 0, 0, 1e300);
  return std::make_unique<AmbientOcclusionIntegrator>(rays, distance);
}

}  // namespace radkit
