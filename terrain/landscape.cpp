#include "terrain/landscape.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>

#include "geometry/ray_scene.h"
#include "util/frame.h"
#include "util/sampling.h"

namespace radkit::terrain {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}  // namespace

TerrainSurface::TerrainSurface(const Heightfield& field, const TerrainSettings& settings)
    : m_field(field), m_mesh(triangulate(field, settings)) {
  m_normals.reserve(m_mesh.triangles.size());
  for (const auto& t : m_mesh.triangles) {
    const Vec3 &a = m_mesh.vertices[t[0]], &b = m_mesh.vertices[t[1]], &c = m_mesh.vertices[t[2]];
    const Vec3 n = normalize(cross(b - a, c - a));
    m_normals.push_back(n);
    m_maxGradient = std::max(m_maxGradient, std::hypot(n.x, n.y) / n.z);
  }
  m_top = *std::max_element(field.z.begin(), field.z.end());
}

bool TerrainSurface::inside(double x, double y) const {
  const double h = m_field.size / 2;
  return x >= -h && x <= h && y >= -h && y <= h;
}

double TerrainSurface::height(double x, double y, int* triangle) const {
  const int n = m_field.n;
  const double fx = (x / m_field.size + 0.5) * (n - 1), fy = (y / m_field.size + 0.5) * (n - 1);
  const int i = std::clamp(int(std::floor(fx)), 0, n - 2),
            j = std::clamp(int(std::floor(fy)), 0, n - 2);
  const double u = fx - i, v = fy - j;
  const double* z = &m_field.z[std::size_t(j) * n + i];
  const double z00 = z[0], z10 = z[1], z01 = z[n], z11 = z[n + 1];
  const bool lower = u >= v;  // triangle (00, 10, 11), else (00, 11, 01): triangulate's order
  if (triangle) *triangle = 2 * (j * (n - 1) + i) + (lower ? 0 : 1);
  return lower ? z00 + u * (z10 - z00) + v * (z11 - z10) : z00 + v * (z01 - z00) + u * (z11 - z01);
}

namespace {

/// The part [t0, t1] of the ray inside the field's columns and below its top.
bool clipToField(const TerrainSurface& s, const Vec3& o, const Vec3& d, double& t0, double& t1) {
  const double h = s.field().size / 2;
  t0 = 0, t1 = kInf;
  const double lo[3] = {-h, -h, -kInf}, hi[3] = {h, h, s.top()};
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0) {
      if (o[a] < lo[a] || o[a] > hi[a]) return false;
      continue;
    }
    double ta = (lo[a] - o[a]) / d[a], tb = (hi[a] - o[a]) / d[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta), t1 = std::min(t1, tb);
  }
  return t0 <= t1;
}

}  // namespace

std::optional<MarchHit> marchTerrain(const TerrainSurface& s, const Vec3& o, const Vec3& d,
                                     int maxSteps, int* stepsTaken) {
  double t, tEnd;
  int steps = 0;
  auto done = [&](std::optional<MarchHit> hit) {
    if (stepsTaken) *stepsTaken = steps;
    return hit;
  };
  if (!clipToField(s, o, d, t, tEnd)) return done(std::nullopt);
  // The gap z − h(x, y) shrinks per unit of t at most this fast.
  const double rate = s.maxGradient() * std::hypot(d.x, d.y) - d.z;
  if (rate <= 0 && o.z > s.height(o.x, o.y)) return done(std::nullopt);
  const double tolerance = 1e-3 * s.spacing(), minStep = 1e-4 * s.spacing();
  while (t <= tEnd && steps < maxSteps) {
    ++steps;
    const Vec3 p = o + d * t;
    int tri;
    const double gap = p.z - s.height(p.x, p.y, &tri);
    if (gap <= tolerance) {
      // The triangle's plane: gap(t + σ) = gap − σ (n·d)/n_z.
      const Vec3 n = s.normal(tri);
      const double closing = -dot(n, d) / n.z;
      if (gap <= 0) return done(MarchHit{t, tri});  // started below the surface
      if (closing > 0) {
        const double sigma = gap / closing;
        const Vec3 q = p + d * sigma;
        int tri2;
        if (s.inside(q.x, q.y)) {
          s.height(q.x, q.y, &tri2);
          if (tri2 == tri) return done(MarchHit{t + sigma, tri});
        }
      }
    }
    t += std::max(gap / rate, minStep);
  }
  return done(std::nullopt);
}

double softShadow(const TerrainSurface& s, const Vec3& x, const Vec3& sun, double radius,
                  int maxSteps) {
  if (sun.z <= -radius) return 0;
  const double rate = s.maxGradient() * std::hypot(sun.x, sun.y) - sun.z;
  if (rate <= 0) return 1;  // the sun rises faster than any slope: nothing can block it
  double alpha = kInf, t = 0.01 * s.spacing();
  for (int k = 0; k < maxSteps; ++k) {
    const Vec3 p = x + sun * t;
    if (!s.inside(p.x, p.y) || p.z > s.top()) break;
    const double gap = p.z - s.height(p.x, p.y);
    alpha = std::min(alpha, gap / t);
    if (alpha < -radius) return 0;
    // Safe steps while clear; within a quarter cell below the surface or close to it.
    t += std::max(gap / rate, 0.25 * s.spacing());
  }
  return alpha == kInf ? 1 : std::clamp(0.5 + alpha / (2 * radius), 0.0, 1.0);
}

PatchMesh terrainPatchMesh(const TerrainMesh& mesh) {
  PatchMesh out;
  out.vertices = mesh.vertices;
  out.surfaceBegin.push_back(0);
  for (int m = 0; m < 3; ++m) {
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      if (int(mesh.material[t]) != m) continue;
      Patch p;
      p.vertexCount = 3;
      for (int k = 0; k < 3; ++k) p.vertex[k] = mesh.triangles[t][k];
      const Vec3 &a = mesh.vertices[p.vertex[0]], &b = mesh.vertices[p.vertex[1]],
                 &c = mesh.vertices[p.vertex[2]];
      const Vec3 n = cross(b - a, c - a);
      p.area = length(n) / 2;
      p.normal = n / length(n);
      p.centroid = (a + b + c) / 3;
      p.surface = int(out.surfaceBegin.size()) - 1;
      out.patches.push_back(p);
    }
    if (out.patches.size() > std::size_t(out.surfaceBegin.back()))
      out.surfaceBegin.push_back(int(out.patches.size()));
  }
  return out;
}

LandscapeImage renderLandscape(const TerrainSurface& s, const atmosphere::Atmosphere& air,
                               const Vec3& eye, const RayDirection& camera,
                               const LandscapeSettings& settings, bool reference) {
  const auto start = std::chrono::steady_clock::now();
  const atmosphere::AtmosphereParameters& ap = air.parameters();
  const Vec3 sun = atmosphere::sunDirection(settings.sunElevationDeg, settings.sunAzimuthDeg);
  auto planet = [&](const Vec3& x) { return air.pointAtAltitude(x.z) + Vec3{x.x, x.y, 0}; };
  // The sky's irradiance on a horizontal plane (midpoint rule), for the isotropic sky term.
  Vec3 skyHorizontal{0, 0, 0};
  {
    const int ne = 16, na = 32;
    const Vec3 p = planet(eye);
    for (int i = 0; i < ne; ++i)
      for (int j = 0; j < na; ++j) {
        const double e = (i + 0.5) / ne * M_PI / 2, a = (j + 0.5) / na * 2 * M_PI;
        const Vec3 w{std::cos(e) * std::sin(a), std::cos(e) * std::cos(a), std::sin(e)};
        skyHorizontal += air.skyRadiance(p, w, sun, settings.sky) * (std::sin(e) * std::cos(e));
      }
    skyHorizontal = skyHorizontal * ((M_PI / 2) / ne * (2 * M_PI) / na);
  }
  // Embree's triangles, and each patch's triangle (patches are grouped by material).
  std::unique_ptr<RayScene> rays;
  std::vector<int> patchTriangle;
  if (reference) {
    const PatchMesh mesh = terrainPatchMesh(s.mesh());
    rays = std::make_unique<RayScene>(mesh);
    for (int m = 0; m < 3; ++m)
      for (std::size_t t = 0; t < s.mesh().triangles.size(); ++t)
        if (int(s.mesh().material[t]) == m) patchTriangle.push_back(int(t));
  }
  const double radius = ap.sunAngularRadius;
  const Frame sunFrame(sun);
  LandscapeImage img;
  const int w = settings.width, h = settings.height;
  img.radiance.assign(std::size_t(w) * h, Vec3{});
  img.depth.assign(std::size_t(w) * h, -1.0);
  std::atomic<long long> rayCount{0}, stepCount{0}, visibilityNanoseconds{0};
  using Clock = std::chrono::steady_clock;
  tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
    long long localRays = 0, localSteps = 0;
    Clock::duration visibility{0};
    for (int y = rows.begin(); y < rows.end(); ++y)
      for (int x = 0; x < w; ++x) {
        const std::size_t pixel = std::size_t(y) * w + x;
        const Vec3 d = camera(x + 0.5, y + 0.5);
        ++localRays;
        auto t0 = Clock::now();
        std::optional<MarchHit> hit;
        if (reference) {
          if (auto r = rays->closestHit(eye, d, 0.0))
            hit = MarchHit{r->distance, patchTriangle[r->patch]};
        } else {
          int steps = 0;
          hit = marchTerrain(s, eye, d, settings.maxSteps, &steps);
          localSteps += steps;
        }
        visibility += Clock::now() - t0;
        if (!hit) {
          img.radiance[pixel] = air.skyRadiance(planet(eye), d, sun, settings.sky);
          continue;
        }
        img.depth[pixel] = hit->t;
        const Vec3 n = s.normal(hit->triangle);
        const Vec3 p = eye + d * hit->t;
        const Vec3 lifted = p + n * (1e-3 * s.spacing());
        double visible = 0;
        const double cosSun = dot(n, sun);
        t0 = Clock::now();
        if (cosSun > 0) {
          if (reference) {
            Rng rng(settings.seed, pixel, 0x73756e);
            std::vector<double> u;
            std::vector<int> scratch;
            latinHypercube(settings.sunSamples, 2, rng, u, scratch);
            const double cosMax = std::cos(radius);
            for (std::size_t k = 0; k < std::size_t(settings.sunSamples); ++k) {
              const Vec3 dir = sunFrame.toWorld(sampleUniformCone(cosMax, u[2 * k], u[2 * k + 1]));
              visible += !rays->occludedRaw(lifted, dir, 0, kInf);
            }
            visible /= settings.sunSamples;
            localRays += settings.sunSamples;
          } else {
            visible = softShadow(s, lifted, sun, radius, settings.maxSteps);
            ++localRays;
          }
        }
        visibility += Clock::now() - t0;
        const Vec3 albedo = kTerrainReflectance[int(s.mesh().material[hit->triangle])];
        const Vec3 e = air.sunIrradiance(planet(p), sun) * (std::max(0.0, cosSun) * visible) +
                       skyHorizontal * ((1 + n.z) / 2);
        Vec3 l = mul(albedo, e) / M_PI;
        if (settings.aerialPerspective) {
          // Single scattering along the view ray to the hit, the sun's light attenuated to
          // each sample by the atmosphere (not by the terrain: no volumetric shadows).
          const int k = settings.aerialSamples;
          const double ds = hit->t / k, mu = dot(d, sun);
          const double pr = rayleighPhase(mu);
          const double pm = cornetteShanksPhase(mu, ap.mieG);
          Vec3 depth{0, 0, 0}, inscatter{0, 0, 0};
          for (int i = 0; i < k; ++i) {
            const Vec3 q = eye + d * ((i + 0.5) * ds);
            const double alt = std::max(0.0, q.z);
            const Vec3 ext = air.extinctionAt(alt);
            const Vec3 half = depth + ext * (ds / 2);
            const Vec3 tv{std::exp(-half.x), std::exp(-half.y), std::exp(-half.z)};
            const Vec3 scatter = air.rayleighScatteringAt(alt) * pr +
                                 Vec3{1, 1, 1} * (air.mieScatteringAt(alt) * pm);
            inscatter += mul(mul(tv, scatter), air.sunIrradiance(planet(q), sun)) * ds;
            depth += ext * ds;
          }
          l = mul(l, Vec3{std::exp(-depth.x), std::exp(-depth.y), std::exp(-depth.z)}) + inscatter;
        }
        img.radiance[pixel] = l;
      }
    rayCount += localRays;
    stepCount += localSteps;
    visibilityNanoseconds +=
        std::chrono::duration_cast<std::chrono::nanoseconds>(visibility).count();
  });
  img.rays = rayCount;
  img.steps = stepCount;
  img.visibilitySeconds = visibilityNanoseconds * 1e-9;
  img.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return img;
}

}  // namespace radkit::terrain
