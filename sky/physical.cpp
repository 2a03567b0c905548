// The physical sky: Rayleigh and Mie scattering of atmosphere/ seen from the scene, tabulated
// once for the scene's sun; the sun's irradiance comes from the same atmosphere.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "atmosphere/atmosphere.h"
#include "atmosphere/rayleigh.h"
#include "sky/sky_radiance.h"

namespace radkit {

namespace {

/// The table: 2° of azimuth hides nothing of the Mie peak's width at g = 0.76
/// (tests/daylight compares the table's irradiance with direct evaluation).
constexpr int kTableRows = 96, kTableColumns = 192;

class PhysicalSky final : public SkyRadiance {
 public:
  PhysicalSky(double density, double altitude, const atmosphere::RayleighAir& air)
      : m_density(density), m_altitude(altitude), m_air(air) {}

  bool needsSun() const override { return true; }
  bool computesSun() const override { return true; }
  void prepare(bool sun, double sunElevationDeg, double sunAzimuthDeg) override;
  Vec3 radiance(const Vec3& local) const override;
  Vec3 horizontalIrradiance() const override { return m_horizontal; }
  Vec3 sunIrradiance() const override { return m_sunIrradiance; }
  std::map<std::string, double> report() const override {
    return {{"density", m_density}, {"altitude_m", m_altitude}, {"table_seconds", m_seconds}};
  }

 private:
  double m_density, m_altitude;
  atmosphere::RayleighAir m_air;
  // Radiance at rows of elevation e = (π/2) t², t = row/(rows − 1) (fine near the horizon,
  // where it changes fastest) and columns of azimuth, bilinear between.
  std::vector<Vec3> m_table;
  Vec3 m_horizontal{0, 0, 0}, m_sunIrradiance{0, 0, 0};
  double m_seconds = 0;
};

void PhysicalSky::prepare(bool sun, double sunElevationDeg, double sunAzimuthDeg) {
  const auto start = std::chrono::steady_clock::now();
  atmosphere::AtmosphereParameters parameters;
  parameters.relativeDensity = m_density;
  atmosphere::useRayleigh(parameters, m_air);
  const atmosphere::Atmosphere air(parameters);
  const Vec3 eye = air.pointAtAltitude(m_altitude);
  const Vec3 sunLocal = atmosphere::sunDirection(sunElevationDeg, sunAzimuthDeg);
  m_table.assign(std::size_t(kTableRows) * (kTableColumns + 1), Vec3{});
  tbb::parallel_for(tbb::blocked_range<int>(0, kTableRows), [&](const tbb::blocked_range<int>& r) {
    for (int row = r.begin(); row < r.end(); ++row) {
      const double t = double(row) / (kTableRows - 1);
      // A hair above the horizon: the ray must leave the planet, not graze it.
      const double elevation = std::max(1e-4, M_PI / 2 * t * t);
      for (int column = 0; column <= kTableColumns; ++column) {
        const double azimuth = 2 * M_PI * column / kTableColumns;
        const Vec3 dir{std::cos(elevation) * std::sin(azimuth),
                       std::cos(elevation) * std::cos(azimuth), std::sin(elevation)};
        m_table[row * (kTableColumns + 1) + column] = air.skyRadiance(eye, dir, sunLocal);
      }
    }
  });
  // Horizontal irradiance: midpoint rule in elevation and azimuth on the interpolated table.
  const int ne = 512, na = 512;
  Vec3 sum{0, 0, 0};
  for (int i = 0; i < ne; ++i) {
    const double e = (i + 0.5) / ne * (M_PI / 2);
    Vec3 ring{0, 0, 0};
    for (int j = 0; j < na; ++j) {
      const double a = (j + 0.5) / na * 2 * M_PI;
      ring += radiance({std::cos(e) * std::sin(a), std::cos(e) * std::cos(a), std::sin(e)});
    }
    sum += ring * (std::sin(e) * std::cos(e));
  }
  m_horizontal = sum * ((M_PI / 2) / ne * (2 * M_PI) / na);
  m_sunIrradiance = sun ? air.sunIrradiance(eye, sunLocal) : Vec3{0, 0, 0};
  m_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

Vec3 PhysicalSky::radiance(const Vec3& local) const {
  const double elevation = std::asin(std::clamp(local.z, 0.0, 1.0));
  double azimuth = std::atan2(local.x, local.y);  // clockwise from north
  if (azimuth < 0) azimuth += 2 * M_PI;
  const double r = std::sqrt(elevation / (M_PI / 2)) * (kTableRows - 1);
  const double c = azimuth / (2 * M_PI) * kTableColumns;
  const int r0 = std::min(int(r), kTableRows - 2), c0 = std::min(int(c), kTableColumns - 1);
  const double fr = r - r0, fc = c - c0;
  auto at = [&](int row, int column) { return m_table[row * (kTableColumns + 1) + column]; };
  return (at(r0, c0) * (1 - fc) + at(r0, c0 + 1) * fc) * (1 - fr) +
         (at(r0 + 1, c0) * (1 - fc) + at(r0 + 1, c0 + 1) * fc) * fr;
}

}  // namespace

std::unique_ptr<SkyRadiance> createPhysicalSky(Params& params) {
  const double density = params.number("density", 1, 0, 100, true, false,
                                       "give the air density over the standard one in that range");
  const double altitude =
      params.number("altitude", 0, 0, 50000, false, true,
                    "give the height above the ground in metres, inside the atmosphere");
  // The air's Rayleigh model by name (atmosphere/rayleigh.h), its parameters after ':' with
  // ';' between them ("bodhaine:co2=420").
  const atmosphere::RayleighAir air = atmosphere::rayleighAir(params.text("rayleigh", "bruneton"));
  return std::make_unique<PhysicalSky>(density, altitude, air);
}

}  // namespace radkit
