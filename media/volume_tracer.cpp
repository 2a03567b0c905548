// The volumetric path tracer (volume_tracer.h): delta tracking (Woodcock et al. 1965) for free
// flights, ratio tracking (Novák, Selle & Jarosz 2014) for transmittance, next-event estimation
// to the sun at every vertex and to the sky at every scattering event (weighted against phase
// sampling by Veach's power heuristic), an optional Lambertian ground at z = 0, and Russian
// roulette.
#include "media/volume_tracer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace radkit::media {

namespace {
// Named inside the anonymous namespace: unity builds join media/*.cpp into one file.
namespace tracerimpl {

/// The part of [0, tMax) along the ray inside the medium's box; false when empty.
bool trackSegment(const Medium& medium, const Vec3& o, const Vec3& d, double tMax, double& t0,
                  double& t1) {
  if (!clipRay(medium.bounds(), o, d, t0, t1)) return false;
  t1 = std::min(t1, tMax);
  return t0 < t1;
}

/// An exponential step of rate `rate` from u ∈ [0, 1) (1 − u > 0, so it is finite).
double exponentialStep(double rate, Rng& rng) { return -std::log1p(-rng.uniform()) / rate; }

/// Ratio tracking's estimate falling below this is played Russian roulette (survival T/kFloor,
/// then T = kFloor): unbiased, keeps T in [0, 1], and ends tracks through thick cloud early.
constexpr double kRatioRouletteFloor = 0.1;

/// Distance along d from o to the ground z = 0 (∞ without a ground or going up).
double groundDistance(const Lighting& light, const Vec3& o, const Vec3& d) {
  if (!(light.groundAlbedo > 0) || !(d.z < 0) || !(o.z > 0)) return INFINITY;
  return -o.z / d.z;
}

/// True when the ground hides the sky in direction w from x (above the ground).
bool groundHides(const Lighting& light, const Vec3& x, const Vec3& w) {
  return light.groundAlbedo > 0 && w.z <= 0 && x.z >= 0;
}

/// Transmittance from x towards the sun (0 when the ground hides it).
double sunTransmittance(const Medium& medium, const Lighting& light, const Vec3& x, Rng& rng) {
  const double tGround = groundDistance(light, x, light.sunDirection);
  if (std::isfinite(tGround) || (light.groundAlbedo > 0 && light.sunDirection.z <= 0)) return 0;
  return ratioTrack(medium, x, light.sunDirection, INFINITY, rng);
}

}  // namespace tracerimpl
}  // namespace

double deltaTrack(const Medium& medium, const Vec3& o, const Vec3& d, double tMax, Rng& rng) {
  double t0, t1;
  const double majorant = medium.majorant();
  if (!(majorant > 0) || !tracerimpl::trackSegment(medium, o, d, tMax, t0, t1)) return INFINITY;
  double t = t0;
  for (;;) {
    t += tracerimpl::exponentialStep(majorant, rng);
    if (t >= t1) return INFINITY;
    // A tentative collision is real with probability σ_t/σ̄, otherwise null.
    if (rng.uniform() * majorant < medium.extinction(o + d * t)) return t;
  }
}

double ratioTrack(const Medium& medium, const Vec3& o, const Vec3& d, double tMax, Rng& rng) {
  double t0, t1;
  const double majorant = medium.majorant();
  if (!(majorant > 0) || !tracerimpl::trackSegment(medium, o, d, tMax, t0, t1)) return 1;
  double T = 1, t = t0;
  for (;;) {
    t += tracerimpl::exponentialStep(majorant, rng);
    if (t >= t1) return T;
    // Each tentative collision weights by the null fraction 1 − σ_t/σ̄.
    T *= std::max(0.0, 1 - medium.extinction(o + d * t) / majorant);
    if (T < tracerimpl::kRatioRouletteFloor) {
      if (T <= 0 || rng.uniform() * tracerimpl::kRatioRouletteFloor >= T) return 0;
      T = tracerimpl::kRatioRouletteFloor;
    }
  }
}

Vec3 traceVolumePath(const Medium& medium, const Lighting& light, const Vec3& o, const Vec3& d,
                     Rng& rng, int rouletteDepth) {
  using namespace tracerimpl;
  const bool sunOn = maxComponent(light.sunIrradiance) > 0;
  const SkySampler* skyNee = light.sky ? light.skySampler.get() : nullptr;
  const double albedo = medium.albedo();
  const PhaseFunction& phase = medium.phase();
  Vec3 radiance{0, 0, 0}, x = o, w = d;
  double beta = 1;  // grey media and a grey ground: the throughput is a scalar
  // The phase density that drew w, when the sky's next-event estimation also reaches it (a
  // scattering event with a sampler); negative otherwise (the camera ray, a ground bounce).
  double phasePdf = -1;
  for (int events = 0;; ++events) {
    const double tGround = groundDistance(light, x, w);
    const double t = deltaTrack(medium, x, w, tGround, rng);
    if (std::isfinite(t)) {
      // A real collision: absorption by the albedo, then the sun's light scattered towards
      // −w (it travels along −sunDirection, leaves along −w: cos θ = sunDirection·w).
      x = x + w * t;
      beta *= albedo;
      if (sunOn) {
        const double T = sunTransmittance(medium, light, x, rng);
        if (T > 0)
          radiance += light.sunIrradiance * (beta * phase.eval(dot(light.sunDirection, w)) * T);
      }
      if (skyNee) {
        // The sky from a direction drawn by its radiance, weighted against the chance that
        // phase sampling below draws the same direction and sees the sky on escape.
        const double u0 = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
        double lightPdf;
        const Vec3 wl = skyNee->sample(u0, u1, u2, lightPdf);
        const double f = phase.eval(dot(wl, w));
        if (lightPdf > 0 && f > 0 && !groundHides(light, x, wl)) {
          const Vec3 L = light.sky(wl);
          if (maxComponent(L) > 0) {
            const double T = ratioTrack(medium, x, wl, INFINITY, rng);
            if (T > 0) radiance += L * (beta * f * T * powerHeuristic(lightPdf, f) / lightPdf);
          }
        }
      }
      // Sampling cos θ by the phase function makes its weight eval/pdf = 1.
      double pdf;
      const double mu = phase.sample(rng.uniform(), pdf);
      w = normalize(Frame(w).toWorld(localDirection(mu, 2 * kPi * rng.uniform())));
      phasePdf = skyNee ? phase.eval(mu) : -1;
    } else if (std::isfinite(tGround)) {
      // The Lambertian ground: the sun through the medium, then a cosine-weighted bounce
      // whose weight (ρ/π · cos / (cos/π)) is ρ.
      x = x + w * tGround;
      x.z = 0;
      beta *= light.groundAlbedo;
      if (sunOn && light.sunDirection.z > 0) {
        const double T = ratioTrack(medium, x, light.sunDirection, INFINITY, rng);
        radiance += light.sunIrradiance * (beta / kPi * light.sunDirection.z * T);
      }
      const double u0 = rng.uniform(), u1 = rng.uniform();
      w = sampleCosineHemisphere(u0, u1);
      phasePdf = -1;
    } else {
      // Escaped: the sky's radiance (a camera ray that never scattered sees the sky behind),
      // with the phase-sampling side of the MIS weight after a scattering event.
      if (light.sky) {
        const double weight = phasePdf >= 0 ? powerHeuristic(phasePdf, skyNee->pdf(w)) : 1.0;
        if (weight > 0) radiance += light.sky(w) * (beta * weight);
      }
      return radiance;
    }
    if (events + 1 >= rouletteDepth) {
      const double q = std::min(1.0, beta);
      if (q < 1) {
        if (rng.uniform() >= q) return radiance;
        beta /= q;
      }
    }
  }
}

VolumeImage renderVolume(const Medium& medium, const Lighting& light, const Vec3& eye,
                         const CameraRay& camera, int width, int height, int samples,
                         std::uint64_t seed) {
  const auto start = std::chrono::steady_clock::now();
  VolumeImage img;
  img.width = width, img.height = height;
  img.radiance.assign(std::size_t(width) * height, Vec3{});
  img.standardError.assign(img.radiance.size(), Vec3{});
  const int n = std::max(1, samples);
  tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y)
      for (int x = 0; x < width; ++x) {
        const std::size_t pixel = std::size_t(y) * width + x;
        // The pixel's own stream: the image does not depend on which thread renders it.
        Rng rng(seed, pixel, 0);
        Vec3 sum{0, 0, 0}, sum2{0, 0, 0};
        for (int s = 0; s < n; ++s) {
          const double jx = rng.uniform(), jy = rng.uniform();
          const Vec3 v = traceVolumePath(medium, light, eye, camera(x + jx, y + jy), rng);
          sum += v;
          sum2 += mul(v, v);
        }
        const Vec3 mean = sum / n;
        img.radiance[pixel] = mean;
        if (n > 1) {
          // Standard error of the mean from the unbiased sample variance.
          const Vec3 var = (sum2 - mul(sum, mean)) / (n - 1);
          img.standardError[pixel] = {std::sqrt(std::max(0.0, var.x) / n),
                                      std::sqrt(std::max(0.0, var.y) / n),
                                      std::sqrt(std::max(0.0, var.z) / n)};
        }
      }
  });
  img.paths = (long long)width * height * n;
  img.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return img;
}

}  // namespace radkit::media
