// The model against the reference (comparison.h).
#include "experiments/sky_comparison.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <chrono>
#include <cmath>
#include <cstdio>

#include "atmosphere/reference.h"
#include "util/frame.h"

namespace radkit::atmosphere {

Vec3 modelHorizontalIrradiance(const Atmosphere& atmosphere, const Vec3& p, const Vec3& sunDir,
                               const SkySettings& settings, int rings) {
  // E = ∫ L cos θ dω = ∫₀^{2π} ∫₀¹ L ds/2 dφ with s = cos²θ: the midpoint rule in s and φ.
  const int columns = 2 * rings;
  const Frame up(normalize(p));
  std::vector<Vec3> ring(static_cast<std::size_t>(rings));
  tbb::parallel_for(0, rings, [&](int i) {
    const double mu = std::sqrt((i + 0.5) / rings);
    Vec3 sum{0, 0, 0};
    for (int j = 0; j < columns; ++j)
      sum += atmosphere.skyRadiance(
          p, up.toWorld(localDirection(mu, 2 * kPi * (j + 0.5) / columns)), sunDir, settings);
    ring[std::size_t(i)] = sum;
  });
  Vec3 total{0, 0, 0};
  for (const Vec3& v : ring) total += v;
  return total * (kPi / (double(rings) * columns));
}

std::vector<ComparisonRow> compareWithReference(const Atmosphere& atmosphere,
                                                const ComparisonSettings& s) {
  const Vec3 eye = atmosphere.pointAtAltitude(s.altitude);
  SkySettings single = s.sky, both = s.sky;
  single.multipleScattering = false;
  both.multipleScattering = true;
  SkySettings fine = s.fine;
  fine.multipleScattering = false;
  std::vector<ComparisonRow> rows;
  for (double elevation : s.sunElevationsDeg) {
    const Vec3 sun = sunDirection(elevation, s.sunAzimuthDeg);
    const std::pair<const char*, Vec3> views[3] = {
        {"zenith", {0, 0, 1}},
        {"horizon toward sun", sunDirection(s.horizonElevationDeg, s.sunAzimuthDeg)},
        {"horizon away from sun", sunDirection(s.horizonElevationDeg, s.sunAzimuthDeg + 180)}};
    for (const auto& [name, dir] : views) {
      ComparisonRow r;
      r.sunElevationDeg = elevation;
      r.quantity = name;
      r.direction = dir;
      r.singleScattering = atmosphere.skyRadiance(eye, dir, sun, single);
      r.singleScatteringFine = atmosphere.skyRadiance(eye, dir, sun, fine);
      r.withMultipleScattering = atmosphere.skyRadiance(eye, dir, sun, both);
      const auto start = std::chrono::steady_clock::now();
      r.reference = referenceSkyRadiance(atmosphere, eye, dir, sun, s.paths, s.seed + rows.size());
      r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      rows.push_back(r);
    }
    ComparisonRow r;
    r.sunElevationDeg = elevation;
    r.quantity = "irradiance";
    r.direction = {0, 0, 1};
    r.singleScattering = modelHorizontalIrradiance(atmosphere, eye, sun, single);
    r.singleScatteringFine = modelHorizontalIrradiance(atmosphere, eye, sun, fine);
    r.withMultipleScattering = modelHorizontalIrradiance(atmosphere, eye, sun, both);
    const auto start = std::chrono::steady_clock::now();
    r.reference =
        referenceHorizontalIrradiance(atmosphere, eye, sun, s.paths, s.seed + rows.size());
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    rows.push_back(r);
  }
  return rows;
}

namespace {

std::string formatTriple(const char* f, double a, double b, double c) {
  char buffer[128];
  std::snprintf(buffer, sizeof buffer, f, a, b, c);
  return buffer;
}

/// "r / g / b" of f(a_c, b_c) printed with `format`, "n/a" for a channel whose quotient has no
/// value: a dark reference (sun far below the horizon) or a zero standard error (one path).
template <class F>
std::string quotientTriple(const char* format, const Vec3& a, const Vec3& b, F f) {
  std::string out;
  for (int c = 0; c < 3; ++c) {
    const double v = f(a[c], b[c]);
    char buffer[64];
    if (b[c] > 0 && std::isfinite(v))
      std::snprintf(buffer, sizeof buffer, format, v);
    else
      std::snprintf(buffer, sizeof buffer, "n/a");
    out += (c ? " / " : "") + std::string(buffer);
  }
  return out;
}

/// "r / g / b" of 100·(model/reference − 1).
std::string percentTriple(const Vec3& model, const Vec3& reference) {
  return quotientTriple("%+.1f", model, reference,
                        [](double m, double r) { return 100 * (m / r - 1); });
}

}  // namespace

std::string comparisonMarkdown(const std::vector<ComparisonRow>& rows) {
  std::string out =
      "| sun elev. | quantity | reference R / G / B | ref. SE % | SS % | SS fine % | SS+MS % | "
      "SS+MS \\|z\\| |\n|---|---|---|---|---|---|---|---|\n";
  for (const ComparisonRow& r : rows) {
    const Vec3& m = r.reference.mean;
    const Vec3& e = r.reference.standardError;
    const Vec3 gap{std::fabs(r.withMultipleScattering.x - m.x),
                   std::fabs(r.withMultipleScattering.y - m.y),
                   std::fabs(r.withMultipleScattering.z - m.z)};
    out += formatTriple("| %g° ", r.sunElevationDeg, 0, 0) + "| " + r.quantity + " | " +
           formatTriple("%.4g / %.4g / %.4g", m.x, m.y, m.z) + " | " +
           quotientTriple("%.2f", e, m, [](double se, double mean) { return 100 * se / mean; }) +
           " | " + percentTriple(r.singleScattering, m) + " | " +
           percentTriple(r.singleScatteringFine, m) + " | " +
           percentTriple(r.withMultipleScattering, m) + " | " +
           quotientTriple("%.0f", gap, e, [](double d, double se) { return d / se; }) + " |\n";
  }
  return out;
}

}  // namespace radkit::atmosphere
