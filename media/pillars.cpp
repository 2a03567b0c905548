// Light pillars: closed form and Monte Carlo of single specular reflection from ice plates
// (docs/pillars.md has the derivations; helper names carry a "pillar" prefix because unity
// builds concatenate media/*.cpp).
#include "media/pillars.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "util/sampling.h"

namespace radkit::media {

namespace {

constexpr double kPillarInf = std::numeric_limits<double>::infinity();
constexpr int kPillarTableSize = 4096;  ///< intervals of the tilt sampler's inverse-CDF table

/// Gauss-Legendre nodes and weights on [−1, 1] (Newton on P_n from Chebyshev starts).
void pillarGaussLegendre(int n, std::vector<double>& x, std::vector<double>& w) {
  x.assign(n, 0);
  w.assign(n, 0);
  for (int i = 0; i < (n + 1) / 2; ++i) {
    double z = std::cos(kPi * (i + 0.75) / (n + 0.5)), dp = 1;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1, p1 = z;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      if (n == 1) p0 = 1, p1 = z;
      dp = n * (z * p1 - p0) / (z * z - 1);
      const double dz = p1 / dp;
      z -= dz;
      if (std::fabs(dz) < 1e-16) break;
    }
    x[i] = -z;
    x[n - 1 - i] = z;
    w[i] = w[n - 1 - i] = 2 / ((1 - z * z) * dp * dp);
  }
}

/// The view ray seen from one lamp: closest approach C = eye + tc·d at distance b along the
/// unit u; the half vector at angle γ is sin γ·u − cos γ·d, so cos β = R|sin(γ − δ)| and
/// sin²β = S² + R²cos²(γ − δ), S = |(u × d)_z| = sin β_min (u, d, u × d orthonormal).
struct PillarRayFrame {
  double tc = 0, b = 0, R = 0, S = 0, delta = 0;
  Vec3 u;
  bool valid = false;

  PillarRayFrame(const Vec3& eye, const Vec3& d, const Vec3& lamp) {
    tc = dot(lamp - eye, d);
    const Vec3 off = lamp - (eye + d * tc);
    b = length(off);
    if (!(b > 1e-9 * (1 + length(lamp - eye)))) return;  // lamp on the ray: no reflection
    u = off / b;
    R = std::hypot(u.z, d.z);
    S = std::fabs(cross(u, d).z);
    delta = std::atan2(d.z, u.z);
    valid = true;
  }
  double gamma(double t) const { return kPi / 4 - 0.5 * std::atan((t - tc) / b); }
  double t(double g) const { return tc + b * std::tan(kPi / 2 - 2 * g); }
  double tilt(double g) const {
    const double s = std::sin(g - delta), c = std::cos(g - delta);
    return std::atan2(std::sqrt(S * S + R * R * c * c), R * std::fabs(s));
  }
};

bool pillarInsideBox(const Vec3& p, const PillarBox& box) {
  return p.x >= box.lo.x && p.x <= box.hi.x && p.y >= box.lo.y && p.y <= box.hi.y &&
         p.z >= box.lo.z && p.z <= box.hi.z;
}

/// Ray–sphere: nearest s > 0 where o + s·w (w unit) enters the sphere; +∞ when it misses or
/// starts inside.
double pillarRaySphere(const Vec3& o, const Vec3& w, const Vec3& centre, double radius) {
  const Vec3 oc = o - centre;
  const double bq = dot(oc, w), cq = dot(oc, oc) - radius * radius;
  if (cq <= 0) return kPillarInf;
  const double disc = bq * bq - cq;
  if (disc < 0 || bq > 0) return kPillarInf;
  // cq/(−bq + √disc) is the near root without cancellation.
  return cq / (-bq + std::sqrt(disc));
}

}  // namespace

double pillarTiltDensity(double beta, const PillarTilt& tilt) {
  if (beta < 0 || beta > tilt.cut) return 0;
  return std::sqrt(2 / kPi) / tilt.sigma * std::exp(-beta * beta / (2 * tilt.sigma * tilt.sigma));
}

double pillarTiltMass(const PillarTilt& tilt) {
  return std::erf(tilt.cut / (tilt.sigma * std::sqrt(2.0)));
}

double pillarNormalDensity(const Vec3& m, const PillarTilt& tilt) {
  // sin β from the horizontal part: 1 − cos² loses it below ~1e-8 rad.
  const double c = std::fabs(m.z), s = std::hypot(m.x, m.y);
  const double beta = std::atan2(s, c);
  if (s <= 0) return kPillarInf;  // p(0) > 0 over a vanishing sin β: integrable, not finite
  return pillarTiltDensity(beta, tilt) / (2 * kPi * s / length(m));
}

PillarTiltSampler::PillarTiltSampler(const PillarTilt& tilt)
    : m_tilt(tilt), m_scale(tilt.sigma * std::sqrt(2.0)), m_mass(pillarTiltMass(tilt)) {
  const double top = tilt.cut / m_scale;
  m_table.resize(kPillarTableSize + 1);
  for (int i = 0; i <= kPillarTableSize; ++i) {
    const double y = m_mass * i / double(kPillarTableSize);
    double lo = 0, hi = top;
    for (int it = 0; it < 60; ++it) {
      const double mid = 0.5 * (lo + hi);
      (std::erf(mid) < y ? lo : hi) = mid;
    }
    m_table[i] = 0.5 * (lo + hi);
  }
}

double PillarTiltSampler::sample(double u) const {
  const double f = std::clamp(u, 0.0, 1.0) * kPillarTableSize;
  const int i = std::min(kPillarTableSize - 1, int(f));
  const double y = u * m_mass, top = m_tilt.cut / m_scale;
  double x = m_table[i] + (f - i) * (m_table[i + 1] - m_table[i]);
  // One Newton step on erf(x) = y from the interpolated start leaves the CDF within 1e-10
  // (checked against erf in the tests): far below any sampling error.
  x -= (std::erf(x) - y) / (2 / std::sqrt(kPi) * std::exp(-x * x));
  return m_scale * std::clamp(x, 0.0, top);
}

double pillarRho0(double n) { return (n - 1) * (n - 1) / ((n + 1) * (n + 1)); }

double pillarSchlick(double cosTheta, double rho0) {
  const double m = 1 - std::clamp(cosTheta, 0.0, 1.0);
  const double m2 = m * m;
  return rho0 + (1 - rho0) * m2 * m2 * m;
}

double pillarSchlickAntiderivative(double theta, double rho0) {
  const double s = std::sin(theta), s3 = s * s * s;
  const double g = 63 * theta / 8 - 16 * s + 3.75 * std::sin(2 * theta) + 4 * s3 +
                   5.0 / 32 * std::sin(4 * theta) - 0.2 * s3 * s * s;
  return rho0 * theta + (1 - rho0) * g;
}

Vec3 pillarHalfVector(const Vec3& wi, const Vec3& wo) { return normalize(wi + wo); }

double pillarRequiredTilt(const Vec3& wi, const Vec3& wo) {
  const Vec3 h = wi + wo;
  return std::atan2(std::hypot(h.x, h.y), std::fabs(h.z));
}

Vec3 pillarReflect(const Vec3& w, const Vec3& m) { return m * (2 * dot(w, m)) - w; }

double pillarCrossSection(const Vec3& wi, const Vec3& wo, double area, const PillarTilt& tilt,
                          double rho0) {
  const Vec3 h = pillarHalfVector(wi, wo);
  return area * pillarNormalDensity(h, tilt) * pillarSchlick(dot(wi, h), rho0) / 4;
}

double pillarTiltAlongRay(const Vec3& eye, const Vec3& d, const Vec3& lamp, double t) {
  const Vec3 p = eye + d * t;
  return pillarRequiredTilt(normalize(lamp - p), -d);
}

PillarRayPoint pillarMinimumTilt(const Vec3& eye, const Vec3& d, const Vec3& lamp, double tMin,
                                 double tMax) {
  const PillarRayFrame f(eye, d, lamp);
  if (!f.valid) return {tMin, kPi / 2};
  const double gLo = f.gamma(tMax), gHi = f.gamma(tMin);  // γ falls as t grows
  PillarRayPoint best{tMin, f.tilt(gHi)};
  const double tiltEnd = f.tilt(gLo);
  if (tiltEnd < best.tilt) best = {tMax, tiltEnd};
  // Interior critical points γ* = δ + π/2 + kπ (|sin(γ − δ)| = 1, tilt = β_min).
  for (int k = -2; k <= 2; ++k) {
    const double g = f.delta + kPi / 2 + k * kPi;
    if (g > gLo && g < gHi) best = {f.t(g), std::asin(std::min(1.0, f.S))};
  }
  return best;
}

PillarRayPoint pillarFoundingMinimumTilt(const Vec3& eye, const Vec3& d, const Vec3& lamp) {
  const double D = std::hypot(lamp.x - eye.x, lamp.y - eye.y);
  const double alpha = std::asin(d.z);
  const double z = 0.5 * (eye.z + lamp.z + D * std::tan(alpha));
  const double t = (z - eye.z) / d.z;
  const Vec3 p = eye + d * t;
  const Vec3 h = normalize(lamp - p) - d;
  // The defect: the "a tilt β turns the ray by 2β" halving applied to the half vector, which
  // already halves; in the vertical plane the tilt is 0 and the error vanishes.
  return {t, 0.5 * std::atan2(std::hypot(h.x, h.y), std::fabs(h.z))};
}

std::vector<PillarRayPoint> pillarTiltSegments(const Vec3& eye, const Vec3& d, const Vec3& lamp,
                                               double tMin, double tMax, double cut) {
  std::vector<PillarRayPoint> out;
  const PillarRayFrame f(eye, d, lamp);
  const double sc = std::sin(cut);
  if (!f.valid || f.S >= sc) return out;
  // Boundary: sin²cut = S² + R² sin²φ, φ = γ − γ*.
  const double halfWidth = std::asin(std::min(1.0, std::sqrt(sc * sc - f.S * f.S) / f.R));
  const double gLo = f.gamma(tMax), gHi = f.gamma(tMin);
  for (int k = -2; k <= 2; ++k) {
    const double g = f.delta + kPi / 2 + k * kPi;
    const double a = std::max(gLo, g - halfWidth), b = std::min(gHi, g + halfWidth);
    if (a >= b) continue;
    const double t0 = b == gHi ? tMin : f.t(b), t1 = a == gLo ? tMax : f.t(a);
    out.push_back({t0, f.tilt(b)});
    out.push_back({t1, f.tilt(a)});
  }
  return out;
}

double pillarRayBox(const Vec3& o, const Vec3& w, const PillarBox& box, double sMin, double sMax) {
  double near = sMin, far = sMax;
  for (int k = 0; k < 3; ++k) {
    if (w[k] == 0) {
      if (o[k] < box.lo[k] || o[k] > box.hi[k]) return kPillarInf;
      continue;
    }
    double s0 = (box.lo[k] - o[k]) / w[k], s1 = (box.hi[k] - o[k]) / w[k];
    if (s0 > s1) std::swap(s0, s1);
    near = std::max(near, s0);
    far = std::min(far, s1);
    if (near > far) return kPillarInf;
  }
  return near;
}

bool pillarShadowInterval(const Vec3& lamp, const Vec3& eye, const Vec3& d, double tMax,
                          const PillarBox& box, double& t0, double& t1) {
  struct Ab {
    double a, b;
  };
  // Segment points lamp + a(eye − lamp) + b·d with 0 ≤ a ≤ 1, 0 ≤ b ≤ tMax·a.
  std::vector<Ab> poly{{0, 0}, {1, 0}, {1, tMax}}, next;
  const Vec3 e = eye - lamp;
  for (int k = 0; k < 3; ++k)
    for (int side = 0; side < 2; ++side) {
      const double sign = side == 0 ? 1 : -1;
      const double c0 = sign * (lamp[k] - (side == 0 ? box.lo[k] : box.hi[k]));
      const double ca = sign * e[k], cb = sign * d[k];
      next.clear();
      for (std::size_t i = 0; i < poly.size(); ++i) {
        const Ab& p = poly[i];
        const Ab& q = poly[(i + 1) % poly.size()];
        const double fp = c0 + ca * p.a + cb * p.b, fq = c0 + ca * q.a + cb * q.b;
        if (fp >= 0) next.push_back(p);
        if ((fp >= 0) != (fq >= 0)) {
          const double s = fp / (fp - fq);
          next.push_back({p.a + s * (q.a - p.a), p.b + s * (q.b - p.b)});
        }
      }
      poly.swap(next);
      if (poly.empty()) return false;
    }
  t0 = kPillarInf, t1 = -kPillarInf;
  for (const Ab& p : poly) {
    if (p.a <= 1e-300) {  // the lamp itself is in the box: everything is dark
      t0 = 0, t1 = tMax;
      return true;
    }
    t0 = std::min(t0, p.b / p.a);
    t1 = std::max(t1, p.b / p.a);
  }
  t0 = std::clamp(t0, 0.0, tMax);
  t1 = std::clamp(t1, 0.0, tMax);
  return true;
}

void pillarValidate(const PillarScene& scene) {
  if (!(scene.plateDensity >= 0) || !(scene.extinction >= 0) || !(scene.slabTop > 0) ||
      !(scene.maxDistance > 0) || !(scene.rho0 >= 0 && scene.rho0 <= 1) ||
      !(scene.tilt.sigma > 0) || !(scene.tilt.cut > 0 && scene.tilt.cut < kPi / 2))
    throw std::invalid_argument("pillars: densities, slab, ρ0 or tilt out of range");
  for (const PillarLamp& l : scene.lamps) {
    if (!(l.radius > 0) || l.position.z - l.radius <= 0 || l.position.z > scene.slabTop)
      throw std::invalid_argument("pillars: a lamp must lie above the ground inside the slab");
    for (const PillarBox& b : scene.boxes)
      if (pillarInsideBox(l.position, b))
        throw std::invalid_argument("pillars: a lamp is inside an occluder box");
  }
}

double pillarViewRayEnd(const PillarScene& scene, const Vec3& eye, const Vec3& d) {
  double end = scene.maxDistance;
  if (d.z > 0) end = std::min(end, (scene.slabTop - eye.z) / d.z);
  if (d.z < 0) end = std::min(end, eye.z / -d.z);
  for (const PillarBox& b : scene.boxes) end = std::min(end, pillarRayBox(eye, d, b, 0, end));
  return std::max(0.0, end);
}

Vec3 pillarRadianceClosed(const PillarScene& scene, const Vec3& eye, const Vec3& d,
                          const PillarQuadrature& quadrature) {
  std::vector<double> gx, gw;
  pillarGaussLegendre(quadrature.points, gx, gw);
  const double tEnd = pillarViewRayEnd(scene, eye, d);
  if (tEnd <= 0) return {};
  const double sc = std::sin(scene.tilt.cut), sigma = scene.tilt.sigma;
  const double pNorm = std::sqrt(2 / kPi) / sigma;
  Vec3 total;
  std::vector<std::pair<double, double>> shadows;
  for (const PillarLamp& lamp : scene.lamps) {
    const PillarRayFrame f(eye, d, lamp.position);
    if (!f.valid || f.S >= sc) continue;
    // In the lamp's vertical plane S = 0 and L diverges like log(1/S): keep it finite.
    const double S = std::max(f.S, 1e-12), R = f.R;
    const double halfWidth = std::asin(std::min(1.0, std::sqrt(sc * sc - f.S * f.S) / R));
    const double gLo = f.gamma(tEnd), gHi = f.gamma(0);
    shadows.clear();
    for (const PillarBox& box : scene.boxes) {
      double t0, t1;
      if (pillarShadowInterval(lamp.position, eye, d, tEnd, box, t0, t1))
        shadows.push_back({f.gamma(t1), f.gamma(t0)});
    }
    std::sort(shadows.begin(), shadows.end());
    double integral = 0;
    for (int k = -2; k <= 2; ++k) {
      const double gs = f.delta + kPi / 2 + k * kPi;
      double a = std::max(gLo, gs - halfWidth);
      const double b = std::min(gHi, gs + halfWidth);
      // Lit pieces [a, b] minus the sorted shadow intervals.
      std::vector<std::pair<double, double>> lit;
      for (const auto& s : shadows) {
        if (s.second <= a) continue;
        if (s.first >= b) break;
        if (s.first > a) lit.push_back({a, s.first});
        a = std::max(a, s.second);
      }
      if (a < b) lit.push_back({a, b});
      for (const auto& piece : lit) {
        const double va = std::asinh(R * std::sin(piece.first - gs) / S);
        const double vb = std::asinh(R * std::sin(piece.second - gs) / S);
        if (!(vb > va)) continue;
        const int panels = std::max(1, int(std::ceil((vb - va) / quadrature.panelWidth)));
        const double h = (vb - va) / panels;
        for (int p = 0; p < panels; ++p)
          for (std::size_t i = 0; i < gx.size(); ++i) {
            const double v = va + h * (p + 0.5 + 0.5 * gx[i]);
            const double sphi = std::clamp(S * std::sinh(v) / R, -1.0, 1.0);
            const double phi = std::asin(sphi), cphi = std::sqrt(1 - sphi * sphi);
            const double beta = std::asin(std::min(1.0, S * std::cosh(v)));
            // D dγ = p(β)/(2π R cos φ) dv; the ends are exactly at the cut by construction.
            const double density =
                pNorm * std::exp(-beta * beta / (2 * sigma * sigma)) / (2 * kPi * R * cphi);
            const double g = gs + phi, psi = kPi / 2 - 2 * g;
            const double t = f.tc + f.b * std::tan(psi), rl = f.b / std::cos(psi);
            const double value = density * pillarSchlick(std::cos(g), scene.rho0) *
                                 std::exp(-scene.extinction * (t + rl));
            integral += 0.5 * h * gw[i] * value;
          }
      }
    }
    // L = ∫ n_pA D R/4 · I/r² · T dt and dt/r² = 2 dγ/b.
    total += lamp.intensity * (scene.plateDensity * integral / (2 * f.b));
  }
  return total;
}

Vec3 pillarRadianceBruteForce(const PillarScene& scene, const Vec3& eye, const Vec3& d,
                              int intervals) {
  const double tEnd = pillarViewRayEnd(scene, eye, d);
  Vec3 total;
  if (tEnd <= 0) return total;
  const int n = intervals + intervals % 2;
  const double h = tEnd / n;
  for (const PillarLamp& lamp : scene.lamps) {
    double sum = 0;
    for (int i = 0; i <= n; ++i) {
      const double t = i * h;
      const Vec3 p = eye + d * t, toLamp = lamp.position - p;
      const double r = length(toLamp);
      const Vec3 wi = toLamp / r;
      bool lit = true;
      for (const PillarBox& b : scene.boxes)
        if (pillarRayBox(p, wi, b, 0, r) < kPillarInf) lit = false;
      if (!lit) continue;
      const double value = scene.plateDensity *
                           pillarCrossSection(wi, -d, 1, scene.tilt, scene.rho0) / (r * r) *
                           std::exp(-scene.extinction * (t + r));
      if (!std::isfinite(value)) continue;
      sum += (i == 0 || i == n ? 1 : (i % 2 ? 4 : 2)) * value;
    }
    total += lamp.intensity * (sum * h / 3);
  }
  return total;
}

PillarEstimate pillarRadianceMonteCarlo(const PillarScene& scene, const PillarTiltSampler& sampler,
                                        const Vec3& eye, const Vec3& d, long long samples,
                                        std::uint64_t seed, std::uint64_t pixel) {
  PillarEstimate e;
  const double tEnd = pillarViewRayEnd(scene, eye, d);
  if (tEnd <= 0 || samples <= 0) return e;
  const double scale = tEnd * scene.plateDensity * pillarTiltMass(scene.tilt);
  const Vec3 wo = -d;
  double sumY = 0, sumY2 = 0;
  Vec3 sum;
  for (long long k = 0; k < samples; ++k) {
    Rng rng(seed, pixel, std::uint64_t(k));
    const double t = rng.uniform() * tEnd;
    const double beta = sampler.sample(rng.uniform());
    const double phi = 2 * kPi * rng.uniform();
    const Vec3 m{std::sin(beta) * std::cos(phi), std::sin(beta) * std::sin(phi), std::cos(beta)};
    const Vec3 p = eye + d * t, wi = pillarReflect(wo, m);
    double sBest = kPillarInf;
    int hit = -1;
    for (std::size_t j = 0; j < scene.lamps.size(); ++j) {
      const double s = pillarRaySphere(p, wi, scene.lamps[j].position, scene.lamps[j].radius);
      if (s < sBest) sBest = s, hit = int(j);
    }
    if (hit < 0) continue;
    bool lit = true;
    for (const PillarBox& b : scene.boxes)
      if (pillarRayBox(p, wi, b, 0, sBest) < kPillarInf) lit = false;
    if (!lit) continue;
    const PillarLamp& lamp = scene.lamps[std::size_t(hit)];
    const double c = std::fabs(dot(wo, m));
    const double w = scale * c * pillarSchlick(c, scene.rho0) *
                     std::exp(-scene.extinction * (t + sBest)) / (kPi * lamp.radius * lamp.radius);
    const Vec3 x = lamp.intensity * w;
    const double y = luminance(x);
    sum += x;
    sumY += y;
    sumY2 += y * y;
    ++e.hits;
  }
  const double n = double(samples);
  e.mean = sum / n;
  const double meanY = sumY / n;
  if (samples > 1) e.luminanceSe = std::sqrt(std::max(0.0, (sumY2 / n - meanY * meanY) / (n - 1)));
  return e;
}

Vec3 PillarCamera::direction(int x, int y) const {
  const double az = azimuthDeg * kPi / 180, el = elevationDeg * kPi / 180;
  const Vec3 forward{std::sin(az) * std::cos(el), std::cos(az) * std::cos(el), std::sin(el)};
  const Vec3 right{std::cos(az), -std::sin(az), 0};
  const Vec3 up = cross(right, forward);
  const double tanHalf = std::tan(0.5 * fovDeg * kPi / 180);
  const double px = (2 * (x + 0.5) / width - 1) * tanHalf;
  const double py = (1 - 2 * (y + 0.5) / height) * tanHalf * height / width;
  return normalize(forward + right * px + up * py);
}

PillarImage pillarRenderClosed(const PillarScene& scene, const PillarCamera& camera,
                               const PillarQuadrature& quadrature) {
  pillarValidate(scene);
  const auto start = std::chrono::steady_clock::now();
  PillarImage img;
  img.width = camera.width, img.height = camera.height;
  img.radiance.assign(std::size_t(img.width) * img.height, Vec3{});
  tbb::parallel_for(tbb::blocked_range<int>(0, img.height), [&](const tbb::blocked_range<int>& r) {
    for (int y = r.begin(); y < r.end(); ++y)
      for (int x = 0; x < img.width; ++x)
        img.radiance[std::size_t(y) * img.width + x] =
            pillarRadianceClosed(scene, camera.eye, camera.direction(x, y), quadrature);
  });
  img.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return img;
}

PillarImage pillarRenderMonteCarlo(const PillarScene& scene, const PillarCamera& camera,
                                   long long samples, std::uint64_t seed) {
  pillarValidate(scene);
  const auto start = std::chrono::steady_clock::now();
  const PillarTiltSampler sampler(scene.tilt);
  PillarImage img;
  img.width = camera.width, img.height = camera.height;
  const std::size_t n = std::size_t(img.width) * img.height;
  img.radiance.assign(n, Vec3{});
  img.standardError.assign(n, 0);
  img.hits.assign(n, 0);
  tbb::parallel_for(tbb::blocked_range<int>(0, img.height), [&](const tbb::blocked_range<int>& r) {
    for (int y = r.begin(); y < r.end(); ++y)
      for (int x = 0; x < img.width; ++x) {
        const std::size_t i = std::size_t(y) * img.width + x;
        const PillarEstimate e = pillarRadianceMonteCarlo(scene, sampler, camera.eye,
                                                          camera.direction(x, y), samples, seed, i);
        img.radiance[i] = e.mean;
        img.standardError[i] = e.luminanceSe;
        img.hits[i] = e.hits;
      }
  });
  img.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return img;
}

PillarComparison pillarCompare(const PillarImage& closed, const PillarImage& mc,
                               double signalFraction, long long minHits) {
  PillarComparison c;
  double maxY = 0;
  for (const Vec3& v : closed.radiance) maxY = std::max(maxY, luminance(v));
  double sumSq = 0, sumRef = 0, sumZ2 = 0;
  int within = 0;
  for (std::size_t i = 0; i < closed.radiance.size(); ++i) {
    const double yc = luminance(closed.radiance[i]), ym = luminance(mc.radiance[i]);
    const long long hits = mc.hits.empty() ? 0 : mc.hits[i];
    if (!(yc > signalFraction * maxY) && hits < minHits) continue;
    ++c.signalPixels;
    sumSq += (ym - yc) * (ym - yc);
    sumRef += yc;
    const double se = mc.standardError.empty() ? 0 : mc.standardError[i];
    if (std::fabs(ym - yc) < 3 * se) ++within;
    if (se > 0) {
      const double z = (ym - yc) / se;
      sumZ2 += z * z;
      c.maxAbsZ = std::max(c.maxAbsZ, std::fabs(z));
      ++c.zPixels;
    }
  }
  if (c.signalPixels > 0) {
    c.relativeRmse = sumRef > 0 ? std::sqrt(sumSq / c.signalPixels) / (sumRef / c.signalPixels) : 0;
    c.within3Se = double(within) / c.signalPixels;
  }
  if (c.zPixels > 0) c.meanZ2 = sumZ2 / c.zPixels;
  return c;
}

PillarScene pillarNightScene() {
  PillarScene s;
  const Vec3 sodium{1.0, 0.52, 0.12}, led{0.92, 0.95, 1.0};
  struct Spot {
    double azimuthDeg, distance, height;
    Vec3 colour;
    double intensity;
  };
  const Spot spots[] = {{-12.3, 220, 6, sodium, 4000},
                        {-4.1, 450, 8, led, 6000},
                        {3.2, 800, 10, sodium, 12000},
                        {8.7, 1100, 7, led, 15000},
                        {14.6, 1500, 5, sodium, 20000}};
  for (const Spot& p : spots) {
    const double a = p.azimuthDeg * kPi / 180;
    s.lamps.push_back({{p.distance * std::sin(a), p.distance * std::cos(a), p.height},
                       p.colour * p.intensity,
                       0.3});
  }
  // A warehouse 350 m out hides the foot of the 800 m lamp's pillar and shadows its plates.
  s.boxes.push_back({{20, 350, 0}, {70, 380, 22}});
  return s;
}

}  // namespace radkit::media
