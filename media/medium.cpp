// Media for the path tracer (medium.h): the ray-box clip, a homogeneous box, and a cloud layer
// after Schneider 2015 and Hillaire 2016 (docs/volumes.md gives the formulas).
#include "media/medium.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace radkit::media {

namespace {
// Named inside the anonymous namespace: unity builds join media/*.cpp into one file.
namespace mediumimpl {

/// remap(v, l0, h0, n0, n1) of Schneider 2015: v's place in [l0, h0] carried to [n0, n1].
double remap(double v, double l0, double h0, double n0, double n1) {
  return n0 + (v - l0) * (n1 - n0) / (h0 - l0);
}

double smoothstep(double e0, double e1, double x) {
  const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3 - 2 * t);
}

/// A rounded band: rises over [a, b], falls over [c, d] of the height fraction.
double band(double h, double a, double b, double c, double d) {
  return smoothstep(a, b, h) * (1 - smoothstep(c, d, h));
}

/// Schneider 2015's three height gradients, blended by type (0 stratus, ½ stratocumulus,
/// 1 cumulus): stratus a thin low band, stratocumulus a medium one, cumulus nearly the whole
/// layer with rounded bottom and top.
double heightGradient(double h, double type) {
  const double stratus = band(h, 0.0, 0.07, 0.13, 0.22);
  const double stratocumulus = band(h, 0.0, 0.12, 0.35, 0.55);
  const double cumulus = band(h, 0.02, 0.15, 0.65, 0.98);
  if (type <= 0.5) return stratus + (stratocumulus - stratus) * (2 * type);
  return stratocumulus + (cumulus - stratocumulus) * (2 * type - 1);
}

/// The coverage-independent parts of the density at p (height fraction h, cloud type): the
/// base shape × height gradient, and the detail noise that erodes it.
void cloudShape(const CloudNoise& noise, const CloudLayerSettings& s, const Vec3& p, double h,
                double type, double& shapeGradient, double& detail) {
  // Base shape: Perlin-Worley dilated by the Worley fBm channels (Schneider 2015), × gradient.
  const Vec3 q = p / s.shapePeriod;
  const double wf = 0.625 * noise.shape.sample(q, 1) + 0.25 * noise.shape.sample(q, 2) +
                    0.125 * noise.shape.sample(q, 3);
  const double base = std::clamp(remap(noise.shape.sample(q, 0), wf - 1, 1, 0, 1), 0.0, 1.0);
  shapeGradient = base * heightGradient(h, type);
  // Detail: inverted Worley fBm (wispy) at the base, Worley fBm (billowy) above h = 0.1.
  const Vec3 r = p / s.detailPeriod;
  const double raw = 0.625 * noise.detail.sample(r, 0) + 0.25 * noise.detail.sample(r, 1) +
                     0.125 * noise.detail.sample(r, 2);
  detail = raw + (1 - 2 * raw) * (1 - std::clamp(10 * h, 0.0, 1.0));
}

/// Width in weather-noise units over which local coverage rises from 0 to 1.
constexpr double kCoverageRamp = 0.25;
/// Weather grid resolution per weatherPeriod.
constexpr int kWeatherSize = 256;
/// Columns (per side) and heights of the cover calibration.
constexpr int kCalibColumns = 64, kCalibHeights = 48;

}  // namespace mediumimpl
}  // namespace

bool clipRay(const Bounds3& b, const Vec3& o, const Vec3& d, double& t0, double& t1) {
  if (b.empty()) return false;
  double lo = 0, hi = INFINITY;
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0) {
      // Parallel to this slab: inside it for every t or never.
      if (o[a] < b.lo[a] || o[a] > b.hi[a]) return false;
      continue;
    }
    const double inv = 1 / d[a];
    double tn = (b.lo[a] - o[a]) * inv, tf = (b.hi[a] - o[a]) * inv;
    if (tn > tf) std::swap(tn, tf);
    lo = std::max(lo, tn);
    hi = std::min(hi, tf);
    if (lo > hi) return false;
  }
  t0 = lo, t1 = hi;
  return true;
}

HomogeneousBox::HomogeneousBox(const Bounds3& box, double extinction, double albedo,
                               std::unique_ptr<PhaseFunction> phase)
    : m_box(box), m_sigmaT(extinction), m_albedo(albedo), m_phase(std::move(phase)) {
  if (!(extinction >= 0) || !(albedo >= 0 && albedo <= 1) || !m_phase)
    throw std::invalid_argument("HomogeneousBox: extinction >= 0, albedo in [0, 1], a phase");
}

double HomogeneousBox::extinction(const Vec3& p) const {
  const bool inside = p.x >= m_box.lo.x && p.x <= m_box.hi.x && p.y >= m_box.lo.y &&
                      p.y <= m_box.hi.y && p.z >= m_box.lo.z && p.z <= m_box.hi.z;
  return inside ? m_sigmaT : 0.0;
}

CloudLayer::CloudLayer(const CloudLayerSettings& settings, std::unique_ptr<PhaseFunction> phase)
    : m_s(settings), m_phase(std::move(phase)) {
  using namespace mediumimpl;
  const CloudLayerSettings& s = m_s;
  if (!(s.top > s.bottom) || !(s.size > 0) || !(s.coverage >= 0 && s.coverage <= 1) ||
      !(s.cloudType >= 0 && s.cloudType <= 1) || !(s.extinction >= 0) ||
      !(s.albedo >= 0 && s.albedo <= 1) || !(s.shapePeriod > 0) || !(s.detailPeriod > 0) ||
      !(s.weatherPeriod > 0) || !(s.detailErosion >= 0 && s.detailErosion < 1) || s.shapeSize < 2 ||
      s.detailSize < 2 || !m_phase)
    throw std::invalid_argument("CloudLayer: invalid settings");
  m_noise = makeCloudNoise(s.shapeSize, s.detailSize, s.seed);

  // The weather map: two tileable Perlin fBm fields (4 cells per period, 4 octaves) on a
  // z-slice of the 3D noise, tabulated for bilinear lookup.
  m_weatherSize = kWeatherSize;
  m_weatherNoise.resize(std::size_t(kWeatherSize) * kWeatherSize);
  m_weatherType.resize(m_weatherNoise.size());
  const std::uint32_t wseed = s.seed * 0x2545F491u + 0x6a09e667u;
  for (int j = 0; j < kWeatherSize; ++j)
    for (int i = 0; i < kWeatherSize; ++i) {
      const Vec3 u{4.0 * i / kWeatherSize, 4.0 * j / kWeatherSize, 0.37};
      const std::size_t k = std::size_t(j) * kWeatherSize + i;
      m_weatherNoise[k] = float(perlinFbm3(u, 4, 4, 0.5, wseed));
      // Type varies about its mean by up to about ±0.25 (Perlin fBm rarely exceeds ±0.5).
      m_weatherType[k] =
          float(std::clamp(s.cloudType + 0.5 * perlinFbm3(u, 4, 3, 0.5, wseed + 77u), 0.0, 1.0));
    }

  // Calibrate the threshold so the fraction of columns holding any cloud is the coverage.
  // A column is cloudy where some height has remap(B·G, 1 − c, 1, 0, 1) > D·e, i.e. where its
  // local coverage c exceeds c* = min_h (1 − B·G)/(1 − D·e): c* does not depend on the
  // threshold, so the cover is a monotone step function of it, solved by bisection.
  if (s.coverage <= 0) {
    m_threshold = INFINITY;
    return;
  }
  if (s.coverage >= 1) {
    m_threshold = -INFINITY;
    return;
  }
  std::vector<double> cStar, noiseAt;
  const Bounds3 box = bounds();
  for (int j = 0; j < kCalibColumns; ++j)
    for (int i = 0; i < kCalibColumns; ++i) {
      const double x = box.lo.x + (i + 0.5) / kCalibColumns * s.size;
      const double y = box.lo.y + (j + 0.5) / kCalibColumns * s.size;
      const double type = weatherGrid(m_weatherType, x, y);
      double best = INFINITY;
      for (int k = 0; k < kCalibHeights; ++k) {
        const double h = (k + 0.5) / kCalibHeights;
        const Vec3 p{x, y, s.bottom + h * (s.top - s.bottom)};
        double shapeGradient, detail;
        cloudShape(m_noise, s, p, h, type, shapeGradient, detail);
        best = std::min(best, (1 - shapeGradient) / (1 - detail * s.detailErosion));
      }
      cStar.push_back(best);
      noiseAt.push_back(weatherGrid(m_weatherNoise, x, y));
    }
  const auto cover = [&](double threshold) {
    m_threshold = threshold;
    int n = 0;
    for (std::size_t k = 0; k < cStar.size(); ++k) n += coverageFromNoise(noiseAt[k]) > cStar[k];
    return double(n) / double(cStar.size());
  };
  double lo = -2 - kCoverageRamp, hi = 2;  // |Perlin fBm| < 2: cover 1 at lo, 0 at hi
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo + hi);
    (cover(mid) > s.coverage ? lo : hi) = mid;
  }
  m_threshold = 0.5 * (lo + hi);
}

Bounds3 CloudLayer::bounds() const {
  Bounds3 b;
  b.extend(Vec3{-m_s.size / 2, -m_s.size / 2, m_s.bottom});
  b.extend(Vec3{m_s.size / 2, m_s.size / 2, m_s.top});
  return b;
}

double CloudLayer::weatherGrid(const std::vector<float>& grid, double x, double y) const {
  const int n = m_weatherSize;
  const double gx = x / m_s.weatherPeriod * n, gy = y / m_s.weatherPeriod * n;
  const double fx = std::floor(gx), fy = std::floor(gy);
  const double tx = gx - fx, ty = gy - fy;
  const auto wrap = [n](double v) {
    const long long r = (long long)v % n;
    return int(r < 0 ? r + n : r);
  };
  const int x0 = wrap(fx), y0 = wrap(fy), x1 = (x0 + 1) % n, y1 = (y0 + 1) % n;
  const auto g = [&](int i, int j) { return double(grid[std::size_t(j) * n + i]); };
  return (g(x0, y0) * (1 - tx) + g(x1, y0) * tx) * (1 - ty) +
         (g(x0, y1) * (1 - tx) + g(x1, y1) * tx) * ty;
}

double CloudLayer::coverageFromNoise(double n) const {
  if (m_threshold == -INFINITY) return 1;  // coverage 1: everywhere
  if (m_threshold == INFINITY) return 0;   // coverage 0: nowhere
  return mediumimpl::smoothstep(m_threshold, m_threshold + mediumimpl::kCoverageRamp, n);
}

void CloudLayer::weather(double x, double y, double& coverage, double& type) const {
  coverage = coverageFromNoise(weatherGrid(m_weatherNoise, x, y));
  type = weatherGrid(m_weatherType, x, y);
}

double CloudLayer::density(const Vec3& p) const {
  using namespace mediumimpl;
  const CloudLayerSettings& s = m_s;
  const double h = (p.z - s.bottom) / (s.top - s.bottom);
  if (!(h >= 0 && h <= 1) || !(std::fabs(p.x) <= s.size / 2 && std::fabs(p.y) <= s.size / 2))
    return 0;
  double coverage, type;
  weather(p.x, p.y, coverage, type);
  if (!(coverage > 0)) return 0;
  if (!(heightGradient(h, type) > 0)) return 0;
  double shapeGradient, detail;
  cloudShape(m_noise, s, p, h, type, shapeGradient, detail);
  // Coverage: only the part of the shape above 1 − coverage remains, stretched back to [0, 1];
  // then the detail erodes it where it is thin (Schneider 2015).
  const double covered = remap(shapeGradient, 1 - coverage, 1, 0, 1);
  if (!(covered > 0)) return 0;
  // The majorant is settings.extinction: the density must not exceed 1.
  return std::clamp(remap(covered, detail * s.detailErosion, 1, 0, 1), 0.0, 1.0);
}

double CloudLayer::extinction(const Vec3& p) const { return m_s.extinction * density(p); }

}  // namespace radkit::media
