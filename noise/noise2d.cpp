#include "noise/noise2d.h"

#include <algorithm>
#include <cmath>

namespace radkit {

std::uint32_t hashPCG(std::uint32_t v) {
  const std::uint32_t state = v * 747796405u + 2891336453u;
  const std::uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

namespace {

/// The gradient at lattice point (i, j): an angle from the hash, so every direction occurs.
double corner(std::int64_t i, std::int64_t j, std::uint32_t seed, double dx, double dy) {
  const std::uint32_t h = hashPCG(std::uint32_t(i) ^ hashPCG(std::uint32_t(j) ^ hashPCG(seed)));
  const double angle = h * (2 * M_PI / 4294967296.0);
  return std::cos(angle) * dx + std::sin(angle) * dy;
}

}  // namespace

double gradientNoise(double x, double y, std::uint32_t seed) {
  const double fx = std::floor(x), fy = std::floor(y);
  const std::int64_t i = std::int64_t(fx), j = std::int64_t(fy);
  const double dx = x - fx, dy = y - fy;
  const double u = quinticFade(dx), v = quinticFade(dy);
  const double n00 = corner(i, j, seed, dx, dy), n10 = corner(i + 1, j, seed, dx - 1, dy);
  const double n01 = corner(i, j + 1, seed, dx, dy - 1);
  const double n11 = corner(i + 1, j + 1, seed, dx - 1, dy - 1);
  return (n00 * (1 - u) + n10 * u) * (1 - v) + (n01 * (1 - u) + n11 * u) * v;
}

double fbm(double x, double y, const FractalSettings& s) {
  double sum = 0, frequency = 1;
  for (int i = 0; i < s.octaves; ++i) {
    sum += gradientNoise(x * frequency, y * frequency, s.seed + std::uint32_t(i)) *
           std::pow(s.lacunarity, -i * s.H);
    frequency *= s.lacunarity;
  }
  return sum;
}

double ridgedMultifractal(double x, double y, const FractalSettings& s) {
  double signal = s.offset - std::fabs(gradientNoise(x, y, s.seed));
  signal *= signal;
  double result = signal, frequency = 1;
  for (int i = 1; i < s.octaves; ++i) {
    frequency *= s.lacunarity;
    const double weight = std::clamp(signal * s.gain, 0.0, 1.0);
    signal = s.offset - std::fabs(gradientNoise(x * frequency, y * frequency, s.seed + i));
    signal *= signal * weight;
    result += signal * std::pow(s.lacunarity, -i * s.H);
  }
  return result;
}

}  // namespace radkit
