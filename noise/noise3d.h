// Tileable 3D noise for cloud density (after Schneider 2015, "The Real-Time Volumetric
// Cloudscapes of Horizon Zero Dawn"; lattice points hashed by noise2d.h's PCG hash): gradient
// (Perlin) noise, Worley (cellular) noise, Perlin-Worley, fBm of either, and the two textures
// clouds sample: a base shape (Perlin-Worley and three octaves of Worley fBm) and a detail texture
// (Worley fBm). Deterministic per seed. The textures are float: 128³ × 4 channels is 32 MiB in
// float.
#pragma once

#include <cstdint>
#include <vector>

#include "util/vec3.h"

namespace radkit {

/// \brief Gradient noise at p with period `period` in every axis (tileable), in about [−1, 1].
double perlin3(const Vec3& p, int period, std::uint32_t seed);
/// \brief Worley noise: distance to the nearest of one random point per unit cell, on a
/// lattice of period `period` (tileable), divided by √3 so it lies in [0, 1].
double worley3(const Vec3& p, int period, std::uint32_t seed);
/// \brief Σ_i amplitude^i · noise(p · 2^i) over `octaves`, periods doubled with the frequency,
/// normalised by Σ amplitude^i: for Perlin in about [−1, 1], for Worley in [0, 1].
double perlinFbm3(const Vec3& p, int period, int octaves, double amplitude, std::uint32_t seed);
double worleyFbm3(const Vec3& p, int period, int octaves, double amplitude, std::uint32_t seed);
/// \brief Perlin-Worley: Perlin fBm remapped by inverted Worley fBm (Schneider 2015), in [0, 1].
double perlinWorley3(const Vec3& p, int period, std::uint32_t seed);

/// A tileable scalar texture of n³ texels per channel, sampled trilinearly with wrap-around.
class NoiseTexture {
 public:
  NoiseTexture() = default;
  NoiseTexture(int n, int channels);
  int size() const { return m_n; }
  int channels() const { return m_channels; }
  float& at(int x, int y, int z, int c) {
    return m_values[((std::size_t(z) * m_n + y) * m_n + x) * m_channels + c];
  }
  /// Trilinear at p in texture units (one period is 1 in every axis), wrapping.
  double sample(const Vec3& p, int channel) const;

 private:
  int m_n = 0, m_channels = 0;
  std::vector<float> m_values;
};

/// The two textures of a cloud layer.
struct CloudNoise {
  NoiseTexture shape;   ///< channels: Perlin-Worley, Worley fBm at 3 frequencies (4, 8, 16 cells)
  NoiseTexture detail;  ///< channels: Worley fBm at 3 frequencies
};

/// \brief Builds both textures (parallel over slices; the same seed gives the same texels).
CloudNoise makeCloudNoise(int shapeSize, int detailSize, std::uint32_t seed);

}  // namespace radkit
