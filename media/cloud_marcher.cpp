#include "media/cloud_marcher.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "atmosphere/atmosphere.h"

namespace radkit::media {

double scaledPhase(const PhaseFunction& phase, double cosTheta, double scale) {
  if (scale == 1) return phase.eval(cosTheta);
  return phase.evalAnisotropyScaled(cosTheta, scale);
}

Vec3 marchCloud(const Medium& medium, const Lighting& light, const Vec3& o, const Vec3& d,
                const MarchSettings& s, double offset) {
  const Vec3 background = light.sky ? light.sky(d) : Vec3{0, 0, 0};
  double t0, t1;
  const Bounds3 box = medium.bounds();
  if (!clipRay(box, o, d, t0, t1) || t1 <= t0) return background;
  const int n = std::max(1, s.primarySteps);
  const double dt = (t1 - t0) / n;
  const double cosTheta = dot(light.sunDirection, d);  // light travels along −sun, then −d
  // Each octave's phase value, weight b^i and extinction factor a^i.
  std::vector<double> phase(std::max(1, s.octaves)), energy(phase.size()), extinction(phase.size());
  for (std::size_t i = 0; i < phase.size(); ++i) {
    phase[i] = scaledPhase(medium.phase(), cosTheta, std::pow(s.c, double(i)));
    energy[i] = std::pow(s.b, double(i));
    extinction[i] = std::pow(s.a, double(i));
  }
  const double albedo = medium.albedo();
  const bool sunUp = maxComponent(light.sunIrradiance) > 0;
  Vec3 radiance{0, 0, 0};
  double transmittance = 1;
  for (int i = 0; i < n; ++i) {
    const Vec3 x = o + d * (t0 + (i + offset) * dt);
    const double sigmaT = medium.extinction(x);
    if (!(sigmaT > 0)) continue;
    const double sigmaS = albedo * sigmaT;
    Vec3 source{0, 0, 0};
    if (sunUp) {
      // Optical depth to the box's boundary towards the sun, midpoints of lightSteps steps.
      double l0, l1, tau = 0;
      if (clipRay(box, x, light.sunDirection, l0, l1) && l1 > 0) {
        const int m = std::max(1, s.lightSteps);
        const double ds = l1 / m;
        for (int k = 0; k < m; ++k)
          tau += medium.extinction(x + light.sunDirection * ((k + 0.5) * ds)) * ds;
      }
      double octaves = 0;
      for (std::size_t j = 0; j < phase.size(); ++j)
        octaves += energy[j] * phase[j] * std::exp(-extinction[j] * tau);
      source += light.sunIrradiance * (sigmaS * octaves);
    }
    if (s.ambient) {
      // Isotropic light from above and below, attenuated through homogeneous medium of this
      // sample's extinction to the box's top and bottom; an isotropic phase function averages
      // the two hemispheres.
      const double up = std::max(0.0, box.hi.z - x.z), down = std::max(0.0, x.z - box.lo.z);
      source +=
          (s.ambientTop * std::exp(-sigmaT * up) + s.ambientBottom * std::exp(-sigmaT * down)) *
          (sigmaS / 2);
    }
    // ∫ over the step of T(s) σ_s-weighted source with T falling as e^{−σ_t s} (Hillaire 2016's
    // energy-conserving step), then the step's transmittance.
    const double stepT = std::exp(-sigmaT * dt);
    radiance += source * (transmittance * (1 - stepT) / sigmaT);
    transmittance *= stepT;
  }
  return radiance + background * transmittance;
}

std::vector<double> blueNoiseTile(std::uint64_t seed) {
  // Void-and-cluster (Ulichney 1993) on a 64 × 64 torus with a Gaussian filter (σ = 1.5):
  // start from a random 10 % of points, relax by swapping the tightest cluster into the
  // largest void, then rank: points removed from the tightest clusters get ranks below the
  // initial count, voids filled in order get the ranks above it.
  constexpr int n = 64, cells = n * n;
  constexpr double sigma = 1.5;
  constexpr int radius = 6;
  double kernel[2 * radius + 1][2 * radius + 1];
  for (int dy = -radius; dy <= radius; ++dy)
    for (int dx = -radius; dx <= radius; ++dx)
      kernel[dy + radius][dx + radius] = std::exp(-(dx * dx + dy * dy) / (2 * sigma * sigma));
  std::vector<char> on(cells, 0);
  std::vector<double> energy(cells, 0.0);
  auto splat = [&](int p, double sign) {
    const int px = p % n, py = p / n;
    for (int dy = -radius; dy <= radius; ++dy)
      for (int dx = -radius; dx <= radius; ++dx)
        energy[((py + dy + n) % n) * n + (px + dx + n) % n] +=
            sign * kernel[dy + radius][dx + radius];
  };
  auto extreme = [&](bool cluster) {
    int best = -1;
    for (int p = 0; p < cells; ++p)
      if (bool(on[p]) == cluster &&
          (best < 0 || (cluster ? energy[p] > energy[best] : energy[p] < energy[best])))
        best = p;
    return best;
  };
  Rng rng(seed, 0x626c7565, 0);  // "blue"
  const int initial = cells / 10;
  for (int placed = 0; placed < initial;) {
    const int p = int(rng.uniform() * cells);
    if (!on[p]) on[p] = 1, splat(p, 1), ++placed;
  }
  for (int iteration = 0; iteration < 4 * cells; ++iteration) {
    const int c = extreme(true);
    on[c] = 0, splat(c, -1);
    const int v = extreme(false);
    if (v == c) {
      on[c] = 1, splat(c, 1);
      break;
    }
    on[v] = 1, splat(v, 1);
  }
  std::vector<double> rank(cells, 0.0);
  std::vector<char> phase1 = on;
  std::vector<double> energy1 = energy;
  for (int r = initial - 1; r >= 0; --r) {  // remove clusters: ranks below the initial count
    const int c = extreme(true);
    on[c] = 0, splat(c, -1);
    rank[c] = r;
  }
  on = phase1, energy = energy1;
  for (int r = initial; r < cells; ++r) {  // fill voids: ranks above it
    const int v = extreme(false);
    on[v] = 1, splat(v, 1);
    rank[v] = r;
  }
  for (double& x : rank) x /= cells;
  return rank;
}

VolumeImage renderMarched(const Medium& medium, const Lighting& light, const Vec3& eye,
                          const CameraRay& camera, int width, int height, const MarchSettings& s,
                          std::uint64_t seed) {
  const auto start = std::chrono::steady_clock::now();
  const std::vector<double> tile = s.jitter ? blueNoiseTile(seed) : std::vector<double>{};
  VolumeImage img;
  img.width = width, img.height = height;
  img.radiance.assign(std::size_t(width) * height, Vec3{});
  img.standardError.assign(img.radiance.size(), Vec3{});
  tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y)
      for (int x = 0; x < width; ++x) {
        const double offset = s.jitter ? tile[(y % 64) * 64 + x % 64] : 0.5;
        img.radiance[std::size_t(y) * width + x] =
            marchCloud(medium, light, eye, camera(x + 0.5, y + 0.5), s, offset);
      }
  });
  img.paths = (long long)width * height;
  img.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return img;
}

}  // namespace radkit::media
