// The brute-force reference: a volumetric path tracer through the spherical atmosphere
// (atmosphere.h, reference.h). Each channel is traced by its own path (delta tracking needs
// one majorant per path). Unbiased throughout:
//  - free flights by delta tracking (Woodcock et al. 1965) with the majorant the extinction at
//    the ground, which bounds it everywhere above;
//  - at a real collision the weight takes the single-scattering albedo σ_s/σ_t (Mie's 0.9)
//    instead of absorbing the path;
//  - next-event estimation to the sun, a distant light of irradiance solarIrradiance, with
//    the transmittance by ratio tracking (Novák, Selle and Jarosz 2014), an unbiased
//    estimator; zero when the planet blocks the sun;
//  - scattering by the true mixture phase function: Rayleigh or Cornette-Shanks chosen by
//    their scattering coefficients at the collision, each sampled exactly (phase_sampling.h),
//    so the weight is unchanged;
//  - a Lambertian ground: next-event estimation to the sun, then a cosine-weighted bounce of
//    weight groundAlbedo;
//  - Russian roulette from the fourth bounce on.
// The sun is reached by next-event estimation only: a path that leaves the atmosphere adds
// nothing, so the sun's disc is excluded as in skyRadiance.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "atmosphere/atmosphere.h"
#include "atmosphere/reference.h"
#include "atmosphere/shell.h"
#include "phase/closed_form.h"
#include "util/frame.h"
#include "util/sampling.h"

namespace radkit::atmosphere {

namespace {

/// Paths per task and random stream: the partition, and so the result, is fixed whatever the
/// number of threads.
constexpr long long kBlock = 256;

/// One channel of the atmosphere, for the inner loops.
struct Channel {
  double groundRadius, topRadius, rayleighHeight, mieHeight;
  double rayleigh, mie, mieExtinction, g, albedo, sun;
  double majorant;

  Channel(const AtmosphereParameters& p, int c)
      : groundRadius(p.groundRadius),
        topRadius(p.topRadius),
        rayleighHeight(p.rayleighScaleHeight),
        mieHeight(p.mieScaleHeight),
        rayleigh(p.rayleighScattering[c] * p.relativeDensity),
        mie(p.mieScattering * p.relativeDensity),
        mieExtinction(p.mieExtinction * p.relativeDensity),
        g(p.mieG),
        albedo(p.groundAlbedo),
        sun(p.solarIrradiance[c]),
        majorant(rayleigh + mieExtinction) {}

  double extinction(const Vec3& x) const {
    const double h = length(x) - groundRadius;
    return rayleigh * std::exp(-h / rayleighHeight) + mieExtinction * std::exp(-h / mieHeight);
  }

  /// Ratio-tracking estimate of the transmittance from x along d to the top; 0 when the
  /// ground is in the way.
  double transmittance(const Vec3& x, const Vec3& d, Rng& rng) const {
    if (distanceToSphereFromOutside(x, d, groundRadius) >= 0) return 0;
    if (!(majorant > 0)) return 1;  // a vacuum
    const double end = distanceToSphereFromInside(x, d, topRadius);
    double t = 0, tr = 1;
    for (;;) {
      t -= std::log(1 - rng.uniform()) / majorant;
      if (t >= end) return tr;
      tr *= 1 - extinction(x + d * t) / majorant;
    }
  }

  /// One path's radiance estimate from p along d, direct sun excluded.
  double trace(Vec3 p, Vec3 d, const Vec3& sunDir, Rng& rng) const {
    double weight = 1, radiance = 0;
    for (int bounce = 0; bounce < 100000; ++bounce) {
      double t0 = 0, t1 = 0;
      bool ground = false;
      if (!atmosphereSegment(p, d, groundRadius, topRadius, t0, t1, ground)) break;
      double t = t0;
      bool collided = false;
      double sR = 0, sM = 0, sT = 0;
      while (majorant > 0) {  // a vacuum has no collisions
        t -= std::log(1 - rng.uniform()) / majorant;
        if (t >= t1) break;
        const double h = length(p + d * t) - groundRadius;
        const double dM = std::exp(-h / mieHeight);
        sR = rayleigh * std::exp(-h / rayleighHeight);
        sM = mie * dM;
        sT = sR + mieExtinction * dM;
        if (rng.uniform() * majorant < sT) {
          collided = true;
          break;
        }
      }
      if (collided) {
        const Vec3 x = p + d * t;
        weight *= (sR + sM) / sT;
        const double mu = dot(d, sunDir);
        const double phase = (sR * rayleighPhase(mu) + sM * cornetteShanksPhase(mu, g)) / (sR + sM);
        radiance += weight * phase * sun * transmittance(x, sunDir, rng);
        const double muNew = rng.uniform() * (sR + sM) < sR ? sampleRayleighCosine(rng.uniform())
                                                            : sampleCornetteShanksCosine(rng, g);
        d = directionAround(d, muNew, rng.uniform());
        p = x;
      } else if (ground && albedo > 0) {
        const Vec3 x = p + d * t1;
        const Vec3 n = normalize(x);
        const double cosSun = dot(n, sunDir);
        if (cosSun > 0)
          radiance += weight * albedo / kPi * cosSun * sun * transmittance(x, sunDir, rng);
        weight *= albedo;
        const double u0 = rng.uniform(), u1 = rng.uniform();
        d = Frame(n).toWorld(sampleCosineHemisphere(u0, u1));
        p = x;
      } else {
        break;  // left the atmosphere, or absorbed by a black ground
      }
      if (bounce >= 3) {
        const double survive = std::clamp(weight, 0.05, 0.95);
        if (rng.uniform() >= survive) break;
        weight /= survive;
      }
    }
    return radiance;
  }
};

/// Mean and standard error of `paths` estimates sample(rng) (a Vec3 each), in blocks of
/// kBlock paths with stream (seed, block, 0), summed in block order.
template <class Sample>
ReferenceEstimate estimate(long long paths, std::uint64_t seed, const Sample& sample) {
  ReferenceEstimate r;
  r.paths = std::max(0LL, paths);
  if (r.paths == 0) return r;
  const long long blocks = (r.paths + kBlock - 1) / kBlock;
  const std::size_t count = std::size_t(blocks);
  std::vector<Vec3> sum(count), sumSq(count);
  tbb::parallel_for(tbb::blocked_range<long long>(0, blocks, 1),
                    [&](const tbb::blocked_range<long long>& range) {
                      for (long long b = range.begin(); b < range.end(); ++b) {
                        Rng rng(seed, std::uint64_t(b), 0);
                        Vec3 s{0, 0, 0}, s2{0, 0, 0};
                        const long long end = std::min(r.paths, (b + 1) * kBlock);
                        for (long long i = b * kBlock; i < end; ++i) {
                          const Vec3 v = sample(rng);
                          s += v;
                          s2 += mul(v, v);
                        }
                        sum[std::size_t(b)] = s;
                        sumSq[std::size_t(b)] = s2;
                      }
                    });
  Vec3 s{0, 0, 0}, s2{0, 0, 0};
  for (long long b = 0; b < blocks; ++b) {
    s += sum[std::size_t(b)];
    s2 += sumSq[std::size_t(b)];
  }
  const double n = double(r.paths);
  r.mean = s / n;
  for (int c = 0; c < 3; ++c) {
    const double variance =
        n > 1 ? std::max(0.0, (s2[c] - n * r.mean[c] * r.mean[c]) / (n - 1)) : 0;
    r.standardError[c] = std::sqrt(variance / n);
  }
  return r;
}

}  // namespace

ReferenceEstimate referenceSkyRadiance(const Atmosphere& atmosphere, const Vec3& p, const Vec3& dir,
                                       const Vec3& sunDir, long long paths, std::uint64_t seed) {
  const AtmosphereParameters& ap = atmosphere.parameters();
  const Channel channels[3] = {{ap, 0}, {ap, 1}, {ap, 2}};
  return estimate(paths, seed, [&](Rng& rng) {
    Vec3 v;
    for (int c = 0; c < 3; ++c) v[c] = channels[c].trace(p, dir, sunDir, rng);
    return v;
  });
}

ReferenceEstimate referenceHorizontalIrradiance(const Atmosphere& atmosphere, const Vec3& p,
                                                const Vec3& sunDir, long long paths,
                                                std::uint64_t seed) {
  const AtmosphereParameters& ap = atmosphere.parameters();
  const Channel channels[3] = {{ap, 0}, {ap, 1}, {ap, 2}};
  const Frame up(normalize(p));
  return estimate(paths, seed, [&](Rng& rng) {
    // E = ∫ L cos θ dω; a cosine-weighted direction (pdf cos θ/π) estimates it as π·L.
    Vec3 v;
    for (int c = 0; c < 3; ++c) {
      const double u0 = rng.uniform(), u1 = rng.uniform();
      v[c] = kPi * channels[c].trace(p, up.toWorld(sampleCosineHemisphere(u0, u1)), sunDir, rng);
    }
    return v;
  });
}

}  // namespace radkit::atmosphere
