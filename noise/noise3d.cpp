// Tileable 3D noise for clouds (noise.h): Perlin gradient noise and Worley cellular noise on a
// lattice wrapped by its period, their fBm, Perlin-Worley, and the two cloud textures.
#include "noise/noise3d.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "noise/noise2d.h"

namespace radkit {

namespace {
// A named namespace inside the anonymous one: unity builds concatenate noise/*.cpp, and these
// helpers must not collide with another file's.
namespace noiseimpl {

/// Non-negative remainder: lattice indices wrapped into [0, period).
int wrapIndex(long long i, int period) {
  const long long r = i % period;
  return int(r < 0 ? r + period : r);
}

/// Hash of a wrapped lattice point and the hashed seed hs = hashPCG(seed) (Jarzynski & Olano's
/// PCG hash, chained z, y, x as worley3 does).
std::uint32_t latticeHash(int x, int y, int z, std::uint32_t hs) {
  return hashPCG(std::uint32_t(x) ^ hashPCG(std::uint32_t(y) ^ hashPCG(std::uint32_t(z) ^ hs)));
}

/// Perlin 2002's twelve cube-edge gradients, chosen by the hash: g·(dx, dy, dz).
double edgeGradient(std::uint32_t h, double dx, double dy, double dz) {
  switch (h % 12u) {
    case 0:
      return dx + dy;
    case 1:
      return -dx + dy;
    case 2:
      return dx - dy;
    case 3:
      return -dx - dy;
    case 4:
      return dx + dz;
    case 5:
      return -dx + dz;
    case 6:
      return dx - dz;
    case 7:
      return -dx - dz;
    case 8:
      return dy + dz;
    case 9:
      return -dy + dz;
    case 10:
      return dy - dz;
    default:
      return -dy - dz;
  }
}

/// Octave i of an fBm uses seed + i·kOctaveSeedStep (the golden ratio in 32 bits).
constexpr std::uint32_t kOctaveSeedStep = 0x9E3779B9u;

double lerp(double a, double b, double t) { return a + (b - a) * t; }

/// remap(v, l0, h0, n0, n1) of Schneider 2015: v's position in [l0, h0] carried to [n0, n1].
double remapRange(double v, double l0, double h0, double n0, double n1) {
  return n0 + (v - l0) * (n1 - n0) / (h0 - l0);
}

}  // namespace noiseimpl
}  // namespace

double perlin3(const Vec3& p, int period, std::uint32_t seed) {
  using namespace noiseimpl;
  const double fx = std::floor(p.x), fy = std::floor(p.y), fz = std::floor(p.z);
  const double dx = p.x - fx, dy = p.y - fy, dz = p.z - fz;
  const int x0 = wrapIndex((long long)fx, period), y0 = wrapIndex((long long)fy, period),
            z0 = wrapIndex((long long)fz, period);
  const int x1 = x0 + 1 == period ? 0 : x0 + 1, y1 = y0 + 1 == period ? 0 : y0 + 1,
            z1 = z0 + 1 == period ? 0 : z0 + 1;
  const double u = quinticFade(dx), v = quinticFade(dy), w = quinticFade(dz);
  const std::uint32_t hs = hashPCG(seed);
  const auto g = [&](int x, int y, int z, double ox, double oy, double oz) {
    return edgeGradient(latticeHash(x, y, z, hs), ox, oy, oz);
  };
  const double x00 = lerp(g(x0, y0, z0, dx, dy, dz), g(x1, y0, z0, dx - 1, dy, dz), u);
  const double x10 = lerp(g(x0, y1, z0, dx, dy - 1, dz), g(x1, y1, z0, dx - 1, dy - 1, dz), u);
  const double x01 = lerp(g(x0, y0, z1, dx, dy, dz - 1), g(x1, y0, z1, dx - 1, dy, dz - 1), u);
  const double x11 =
      lerp(g(x0, y1, z1, dx, dy - 1, dz - 1), g(x1, y1, z1, dx - 1, dy - 1, dz - 1), u);
  return lerp(lerp(x00, x10, v), lerp(x01, x11, v), w);
}

double worley3(const Vec3& p, int period, std::uint32_t seed) {
  using namespace noiseimpl;
  const double fx = std::floor(p.x), fy = std::floor(p.y), fz = std::floor(p.z);
  const double dx = p.x - fx, dy = p.y - fy, dz = p.z - fz;
  // Squared distance from p to the neighbour cell at offset o along one axis (0 for o = 0).
  const auto gap2 = [](int o, double f) {
    const double g = o < 0 ? f : (o > 0 ? 1 - f : 0.0);
    return g * g;
  };
  const std::uint32_t hs = hashPCG(seed);
  // Wrapped lattice indices of the cells at offsets −1, 0, +1 (one division per axis).
  const auto wrapped = [period](double f, int(&w)[3]) {
    w[1] = wrapIndex((long long)f, period);
    w[0] = w[1] == 0 ? period - 1 : w[1] - 1;
    w[2] = w[1] + 1 == period ? 0 : w[1] + 1;
  };
  int wx[3], wy[3], wz[3];
  wrapped(fx, wx);
  wrapped(fy, wy);
  wrapped(fz, wz);
  double best = 1e300;
  // The own cell first, so its point bounds the search and far cells are skipped unhashed.
  static constexpr int kOrder[3] = {0, -1, 1};
  for (int k : kOrder) {
    const double gz = gap2(k, dz);
    if (gz >= best) continue;
    const std::uint32_t hz = hashPCG(std::uint32_t(wz[k + 1]) ^ hs);
    for (int j : kOrder) {
      const double gy = gz + gap2(j, dy);
      if (gy >= best) continue;
      const std::uint32_t hy = hashPCG(std::uint32_t(wy[j + 1]) ^ hz);
      for (int i : kOrder) {
        if (gy + gap2(i, dx) >= best) continue;
        // The cell's feature point comes from its wrapped index, so the pattern repeats;
        // the same chain as latticeHash.
        std::uint32_t h = hashPCG(std::uint32_t(wx[i + 1]) ^ hy);
        const double ox = h * 0x1.0p-32;
        h = hashPCG(h);
        const double oy = h * 0x1.0p-32;
        h = hashPCG(h);
        const double oz = h * 0x1.0p-32;
        const double ex = i + ox - dx, ey = j + oy - dy, ez = k + oz - dz;
        best = std::min(best, ex * ex + ey * ey + ez * ez);
      }
    }
  }
  // The own cell's point is at most √3 away, so F1/√3 ≤ 1.
  return std::min(1.0, std::sqrt(best) / std::sqrt(3.0));
}

namespace {
namespace noiseimpl {

template <class Noise>
double fbm3(const Noise& noise, const Vec3& p, int period, int octaves, double amplitude,
            std::uint32_t seed) {
  double sum = 0, norm = 0, a = 1, f = 1;
  for (int i = 0; i < octaves; ++i) {
    // Frequency and period double together, so each octave (and the sum) keeps the tiling.
    sum += a * noise(p * f, period << i, seed + std::uint32_t(i) * kOctaveSeedStep);
    norm += a;
    a *= amplitude;
    f *= 2;
  }
  return norm > 0 ? sum / norm : 0.0;
}

}  // namespace noiseimpl
}  // namespace

double perlinFbm3(const Vec3& p, int period, int octaves, double amplitude, std::uint32_t seed) {
  return noiseimpl::fbm3(perlin3, p, period, octaves, amplitude, seed);
}

double worleyFbm3(const Vec3& p, int period, int octaves, double amplitude, std::uint32_t seed) {
  return noiseimpl::fbm3(worley3, p, period, octaves, amplitude, seed);
}

namespace {
namespace noiseimpl {

/// Seed of the Worley fBm inside perlinWorley3 (and of the shape texture's first Worley channel).
std::uint32_t perlinWorleySeed(std::uint32_t seed) { return seed ^ 0x5bd1e995u; }

/// Perlin fBm P taken to [0, 1], dilated by Worley fBm W: remap(P, W − 1, 1, 0, 1) =
/// (P + 1 − W)/(2 − W). Near Worley's feature points (W ≈ 0) it is (P + 1)/2, billowy; far from
/// them (W → 1) plain P (Schneider 2015's Perlin-Worley).
double combinePerlinWorley(double perlinFbm, double worleyFbm) {
  const double P = std::clamp(0.5 + 0.5 * perlinFbm, 0.0, 1.0);
  return std::clamp(remapRange(P, worleyFbm - 1, 1, 0, 1), 0.0, 1.0);
}

/// Worley fBm (3 octaves, gain ½) at `cells`·2^c cells for c = 0, 1, 2 sharing octaves: the
/// five Worley evaluations at cells·2^m, m = 0..4, seeds seed + m·golden, so that channel c is
/// exactly worleyFbm3(u·cells·2^c, cells·2^c, 3, ½, seed + c·golden).
void worleyChannels(const Vec3& u, int cells, std::uint32_t seed, double out[3]) {
  double w[5];
  for (int m = 0; m < 5; ++m)
    w[m] = worley3(u * double(cells << m), cells << m, seed + std::uint32_t(m) * kOctaveSeedStep);
  for (int c = 0; c < 3; ++c) out[c] = (w[c] + 0.5 * w[c + 1] + 0.25 * w[c + 2]) / 1.75;
}

}  // namespace noiseimpl
}  // namespace

double perlinWorley3(const Vec3& p, int period, std::uint32_t seed) {
  // Perlin fBm and Worley fBm of 3 octaves, gain ½ each.
  return noiseimpl::combinePerlinWorley(
      perlinFbm3(p, period, 3, 0.5, seed),
      worleyFbm3(p, period, 3, 0.5, noiseimpl::perlinWorleySeed(seed)));
}

NoiseTexture::NoiseTexture(int n, int channels)
    : m_n(n), m_channels(channels), m_values(std::size_t(n) * n * n * channels, 0.0f) {}

double NoiseTexture::sample(const Vec3& p, int channel) const {
  // Texel (i, j, k) is centred at ((i, j, k) + ½)/n; one period is 1.
  const double n = m_n;
  const double x = p.x * n - 0.5, y = p.y * n - 0.5, z = p.z * n - 0.5;
  const double fx = std::floor(x), fy = std::floor(y), fz = std::floor(z);
  const double tx = x - fx, ty = y - fy, tz = z - fz;
  // Inside the first period (the common case) no division is needed to wrap.
  const auto wrap = [this](double f) {
    return f >= 0 && f < m_n ? int(f) : noiseimpl::wrapIndex((long long)f, m_n);
  };
  const int x0 = wrap(fx), y0 = wrap(fy), z0 = wrap(fz);
  const int x1 = x0 + 1 == m_n ? 0 : x0 + 1, y1 = y0 + 1 == m_n ? 0 : y0 + 1,
            z1 = z0 + 1 == m_n ? 0 : z0 + 1;
  const auto v = [&](int i, int j, int k) {
    return double(m_values[((std::size_t(k) * m_n + j) * m_n + i) * m_channels + channel]);
  };
  using noiseimpl::lerp;
  const double a =
      lerp(lerp(v(x0, y0, z0), v(x1, y0, z0), tx), lerp(v(x0, y1, z0), v(x1, y1, z0), tx), ty);
  const double b =
      lerp(lerp(v(x0, y0, z1), v(x1, y0, z1), tx), lerp(v(x0, y1, z1), v(x1, y1, z1), tx), ty);
  return lerp(a, b, tz);
}

CloudNoise makeCloudNoise(int shapeSize, int detailSize, std::uint32_t seed) {
  CloudNoise out;
  out.shape = NoiseTexture(shapeSize, 4);
  out.detail = NoiseTexture(detailSize, 3);
  // Each texel is a pure function of its index and the seed: any slice order gives the same.
  const auto fill = [](NoiseTexture& tex, std::uint32_t texSeed, bool shape) {
    const int n = tex.size();
    tbb::parallel_for(tbb::blocked_range<int>(0, n), [&](const tbb::blocked_range<int>& zs) {
      for (int z = zs.begin(); z < zs.end(); ++z)
        for (int y = 0; y < n; ++y)
          for (int x = 0; x < n; ++x) {
            const Vec3 u{(x + 0.5) / n, (y + 0.5) / n, (z + 0.5) / n};  // one period = 1
            double w[3];
            if (shape) {
              // Worley fBm at 4, 8 and 16 cells, and Perlin-Worley at 4 cells, whose Worley
              // fBm is the first channel's: channel 0 is perlinWorley3(4u, 4, texSeed).
              noiseimpl::worleyChannels(u, 4, noiseimpl::perlinWorleySeed(texSeed), w);
              tex.at(x, y, z, 0) = float(
                  noiseimpl::combinePerlinWorley(perlinFbm3(u * 4.0, 4, 3, 0.5, texSeed), w[0]));
              for (int c = 0; c < 3; ++c) tex.at(x, y, z, c + 1) = float(w[c]);
            } else {
              // Worley fBm at 2, 4 and 8 cells: the detail texture is itself tiled finely.
              noiseimpl::worleyChannels(u, 2, texSeed, w);
              for (int c = 0; c < 3; ++c) tex.at(x, y, z, c) = float(w[c]);
            }
          }
    });
  };
  fill(out.shape, hashPCG(seed), true);
  fill(out.detail, hashPCG(seed ^ 0xa511e9b3u), false);
  return out;
}

}  // namespace radkit
