#include "daylight/daylight.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "util/frame.h"
#include "util/sampling.h"

namespace radkit {

Daylight computeDaylight(const PatchMesh& mesh, const RayScene& rays, const SkyModel& sky,
                         std::uint64_t seed) {
  const auto start = std::chrono::steady_clock::now();
  const int n = mesh.size();
  const int skySamples = sky.description().samples;
  const int sunSamples = sky.hasSun() ? sky.description().sunSamples : 0;
  Daylight d;
  d.sky.assign(n, Vec3{});
  d.sun.assign(n, Vec3{});
  d.skyViewFactor.assign(n, 0.0);
  d.skyStandardError.assign(n, 0.0);
  d.skyViewFactorStandardError.assign(n, 0.0);
  const double eps = rays.epsilon();
  const double inf = std::numeric_limits<double>::infinity();
  const Frame sunFrame(sky.sunDirection());

  tbb::parallel_for(tbb::blocked_range<int>(0, n, 16), [&](const tbb::blocked_range<int>& range) {
    std::vector<double> u;
    std::vector<int> scratch;
    for (int i = range.begin(); i < range.end(); ++i) {
      const Patch& p = mesh.patches[i];
      const std::vector<Vec3> polygon = mesh.polygon(p);
      const double split = patchSplit(polygon.data(), p.vertexCount);
      const Frame frame(p.normal);
      // Sky: E = π · mean(L V) under cosine-weighted directions.
      Rng rng(seed, std::uint64_t(i), 0x736b79);  // "sky"
      latinHypercube(skySamples, 4, rng, u, scratch);
      Vec3 sum{0, 0, 0};
      double sum2 = 0, seen = 0;
      for (int k = 0; k < skySamples; ++k) {
        const double* s = &u[std::size_t(k) * 4];
        const Vec3 x = samplePatchUniform(polygon.data(), p.vertexCount, split, s[0], s[1]);
        const Vec3 dir = frame.toWorld(sampleCosineHemisphere(s[2], s[3]));
        if (rays.occludedRaw(x + p.normal * eps, dir, 0, inf)) continue;
        const Vec3 l = sky.radiance(dir) * M_PI;
        sum += l;
        sum2 += (l.x + l.y + l.z) * (l.x + l.y + l.z);
        seen += sky.aboveHorizon(dir);
      }
      const double k = skySamples;
      d.sky[i] = sum / k;
      const double mean = (sum.x + sum.y + sum.z) / k;
      d.skyStandardError[i] =
          std::sqrt(std::max(0.0, sum2 / k - mean * mean) / std::max(1.0, k - 1));
      d.skyViewFactor[i] = seen / k;
      const double f = seen / k;
      d.skyViewFactorStandardError[i] = std::sqrt(f * (1 - f) / std::max(1.0, k - 1));
      if (sunSamples == 0) continue;
      // Sun: E = E_n · mean(cos θ V) over its disc, uniform in solid angle.
      Rng sunRng(seed, std::uint64_t(i), 0x73756e);  // "sun"
      latinHypercube(sunSamples, 4, sunRng, u, scratch);
      double cosSum = 0;
      for (int j = 0; j < sunSamples; ++j) {
        const double* s = &u[std::size_t(j) * 4];
        const Vec3 dir = sunFrame.toWorld(sampleUniformCone(sky.sunCosRadius(), s[2], s[3]));
        const double c = dot(dir, p.normal);
        if (c <= 0) continue;
        const Vec3 x = samplePatchUniform(polygon.data(), p.vertexCount, split, s[0], s[1]);
        if (!rays.occludedRaw(x + p.normal * eps, dir, 0, inf)) cosSum += c;
      }
      d.sun[i] = sky.sunIrradiance() * (cosSum / sunSamples);
    }
  });
  d.rays = (long long)n * (skySamples + sunSamples);

  std::vector<std::pair<double, double>> relative;  // (SE/E, area) over lit patches
  for (int i = 0; i < n; ++i) {
    const double e = d.sky[i].x + d.sky[i].y + d.sky[i].z;
    if (!(e > 0)) continue;
    relative.push_back({d.skyStandardError[i] / e, mesh.patches[i].area});
  }
  d.skyNoise = areaWeightedMedian(std::move(relative));
  d.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return d;
}

double areaWeightedMedian(std::vector<std::pair<double, double>> values) {
  double total = 0, area = 0;
  for (const auto& v : values) total += v.second;
  std::sort(values.begin(), values.end());
  for (const auto& [value, a] : values)
    if ((area += a) >= total / 2) return value;
  return 0;
}

}  // namespace radkit
