#include "hierarchy/element_daylight.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "util/frame.h"
#include "util/sampling.h"

namespace radkit {

namespace {

/// The receiver's reflectance counts as at least this much, as in the link oracle: the bound is
/// in reflected watts, and a black surface's irradiance (a photometer plane) must still follow.
constexpr double kMinReflectance = 0.5;

}  // namespace

ElementDaylight::ElementDaylight(const RayScene& rays, const SkyModel& sky, std::uint64_t seed)
    : m_rays(rays), m_model(sky), m_seed(seed) {}

void ElementDaylight::grow(const Hierarchy& h) {
  const std::size_t n = h.size();
  m_sampled.resize(n, 0);
  m_sky.resize(n);
  m_sun.resize(n);
  m_emission.resize(n);
  m_svf.resize(n, 0.0f);
  m_skyError.resize(n, 0.0f);
  m_svfError.resize(n, 0.0f);
  m_variation.resize(n, 0.0f);
}

void ElementDaylight::sampleNewLeaves(const Hierarchy& h) {
  grow(h);
  std::vector<int> todo;
  for (int n = 0; n < h.size(); ++n)
    if (h[n].element && h[n].isLeaf() && !m_sampled[n]) todo.push_back(n);
  sample(h, todo);
}

void ElementDaylight::sample(const Hierarchy& h, const std::vector<int>& nodes) {
  const auto start = std::chrono::steady_clock::now();
  grow(h);
  // Each quarter of the element gets a quarter of the sky's and the sun's samples (rounded
  // up), in a Latin hypercube of its own: the element's estimate is stratified by quarter,
  // and the quarters' means and spreads tell whether the daylight varies across it.
  const int skyN = (m_model.description().samples + 3) / 4;
  const int sunN = m_model.hasSun() ? (m_model.description().sunSamples + 3) / 4 : 0;
  const double eps = m_rays.epsilon();
  const double inf = std::numeric_limits<double>::infinity();
  const Frame sunFrame(m_model.sunDirection());
  const Vec3 sunE = m_model.sunIrradiance();
  const double sunMax = maxComponent(sunE);
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, nodes.size(), 4),
      [&](const tbb::blocked_range<std::size_t>& range) {
        std::vector<double> u;
        std::vector<int> scratch;
        for (std::size_t i = range.begin(); i < range.end(); ++i) {
          const int n = nodes[i];
          const HPolygon& p = h.polygon(n);
          HPolygon kids[4];
          double areas[4], total = 0;
          quarterPolygons(p, kids, areas);
          for (double a : areas) total += a;
          const Frame frame(p.normal);
          Rng skyRng(m_seed, h.key(n), 0x656c736b79ULL);  // "elsky"
          Rng sunRng(m_seed, h.key(n), 0x656c73756eULL);  // "elsun"
          Vec3 sky{0, 0, 0}, sun{0, 0, 0};
          double svf = 0, skyVar = 0, svfVar = 0;
          double w[4], D[4], V[4];  // per quarter: weight, mean sky light, variance of the mean
          double sunVisible = 0, sunCosine = 0;  // over the whole element
          for (int q = 0; q < 4; ++q) {
            const HPolygon& k = kids[q];
            w[q] = total > 0 ? areas[q] / total : 0.25;
            const double split = patchSplit(k.v, k.count);
            // Sky: E = π · mean(L V) under cosine-weighted directions.
            latinHypercube(skyN, 4, skyRng, u, scratch);
            Vec3 sum{0, 0, 0};
            double y = 0, y2 = 0, c = 0, c2 = 0, seen = 0;
            for (int s = 0; s < skyN; ++s) {
              const double* r = &u[std::size_t(s) * 4];
              const Vec3 x = samplePatchUniform(k.v, k.count, split, r[0], r[1]);
              const Vec3 dir = frame.toWorld(sampleCosineHemisphere(r[2], r[3]));
              if (m_rays.occludedRaw(x + p.normal * eps, dir, 0, inf)) continue;
              const Vec3 l = m_model.radiance(dir) * M_PI;
              sum += l;
              const double m = maxComponent(l), cs = l.x + l.y + l.z;
              y += m, y2 += m * m, c += cs, c2 += cs * cs;
              seen += m_model.aboveHorizon(dir);
            }
            const double ns = skyN;
            sky += sum * (w[q] / ns);
            const double ym = y / ns, cm = c / ns, f = seen / ns;
            D[q] = ym;
            V[q] = ns > 1 ? std::max(0.0, y2 / ns - ym * ym) / (ns - 1) : ym * ym;
            skyVar += w[q] * w[q] * std::max(0.0, c2 / ns - cm * cm) / std::max(1.0, ns - 1);
            svf += w[q] * f;
            svfVar += w[q] * w[q] * f * (1 - f) / std::max(1.0, ns - 1);
            if (sunN == 0) continue;
            // Sun: E = E_n · mean(cos θ V) over its disc, uniform in solid angle.
            latinHypercube(sunN, 4, sunRng, u, scratch);
            double cosSum = 0;
            for (int s = 0; s < sunN; ++s) {
              const double* r = &u[std::size_t(s) * 4];
              const Vec3 dir =
                  sunFrame.toWorld(sampleUniformCone(m_model.sunCosRadius(), r[2], r[3]));
              const double cs = dot(dir, p.normal);
              if (cs <= 0) continue;
              const Vec3 x = samplePatchUniform(k.v, k.count, split, r[0], r[1]);
              sunCosine += w[q] * cs / sunN;
              if (!m_rays.occludedRaw(x + p.normal * eps, dir, 0, inf))
                cosSum += cs, sunVisible += w[q] / sunN;
            }
            sun += sunE * (w[q] * cosSum / sunN);
          }
          // Sky: how far each quarter's mean lies from the element's, beyond what the samples'
          // noise explains: var(D_q − D̄) = (1 − w_q)² V_q + Σ_{j≠q} w_j² V_j. Each sky sample
          // is one direction's radiance, far noisier than the light at its point.
          double mean = 0, variation = 0;
          for (int q = 0; q < 4; ++q) mean += w[q] * D[q];
          for (int q = 0; q < 4; ++q) {
            double var = (1 - w[q]) * (1 - w[q]) * V[q];
            for (int j = 0; j < 4; ++j)
              if (j != q) var += w[j] * w[j] * V[j];
            variation += areas[q] * std::max(0.0, std::fabs(D[q] - mean) -
                                                      kDaylightNoiseSigmas * std::sqrt(var));
          }
          // Sun: each sample is the light at its point (the disc is 0.53° across: a point is lit
          // or not), so a mixed set means a shadow edge crosses the element, wherever it lies:
          // ∫|E_sun − Ē_sun| dA = A E_n cos · mean|V − V̄| = A E_n cos · 2V̄(1 − V̄).
          variation += total * sunMax * sunCosine * 2 * sunVisible * (1 - sunVisible);
          const SurfaceRadiometry& rad = h.radiometry(n);
          m_sky[n] = sky;
          m_sun[n] = sun;
          m_emission[n] = rad.emission + mul(rad.reflectance, sky + sun);
          m_svf[n] = float(svf);
          m_skyError[n] = float(std::sqrt(skyVar));
          m_svfError[n] = float(std::sqrt(svfVar));
          m_variation[n] = float(variation);
          m_sampled[n] = 1;
        }
      });
  m_rayCount += (long long)nodes.size() * 4 * (skyN + sunN);
  m_sampledCount += (long long)nodes.size();
  m_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

long long ElementDaylight::refine(Hierarchy& h, double threshold, double minArea) {
  sampleNewLeaves(h);
  std::vector<int> candidates;
  for (int n = 0; n < h.size(); ++n)
    if (h[n].element && h[n].isLeaf()) candidates.push_back(n);
  long long splits = 0;
  while (!candidates.empty()) {
    std::vector<int> split;
    for (int n : candidates) {
      const double rho = std::max(kMinReflectance, maxComponent(h.radiometry(n).reflectance));
      if (h[n].isLeaf() && rho * m_variation[n] > threshold && h.canSplit(n, minArea))
        split.push_back(n);
    }
    if (split.empty()) break;
    const int first = h.size();
    for (int n : split) h.split(n);  // serially, in node order: numbering is deterministic
    splits += static_cast<long long>(split.size());
    candidates.clear();
    for (int n = first; n < h.size(); ++n) candidates.push_back(n);
    sample(h, candidates);
  }
  m_splits += splits;
  return splits;
}

Daylight ElementDaylight::leafDaylight(const Hierarchy& h, const std::vector<int>& leaves) const {
  Daylight d;
  const std::size_t n = leaves.size();
  d.sky.resize(n), d.sun.resize(n), d.skyViewFactor.resize(n), d.skyStandardError.resize(n),
      d.skyViewFactorStandardError.resize(n);
  std::vector<std::pair<double, double>> relative;  // (SE/E, area) over lit leaves
  for (std::size_t i = 0; i < n; ++i) {
    const int k = leaves[i];
    d.sky[i] = m_sky[k], d.sun[i] = m_sun[k];
    d.skyViewFactor[i] = m_svf[k];
    d.skyStandardError[i] = m_skyError[k];
    d.skyViewFactorStandardError[i] = m_svfError[k];
    const double e = m_sky[k].x + m_sky[k].y + m_sky[k].z;
    if (!(e > 0)) continue;
    relative.push_back({m_skyError[k] / e, h[k].area});
  }
  d.skyNoise = areaWeightedMedian(std::move(relative));
  d.rays = m_rayCount;
  d.seconds = m_seconds;
  return d;
}

}  // namespace radkit
