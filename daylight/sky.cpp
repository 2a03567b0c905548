#include "daylight/sky.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "atmosphere/atmosphere.h"

namespace radkit {

namespace {
/// The physical sky's table: 2° of azimuth hides nothing of the Mie peak's width at g = 0.76
/// (tests/daylight compares the table's irradiance with direct evaluation).
constexpr int kTableRows = 96, kTableColumns = 192;
constexpr double kDeg = M_PI / 180;
}  // namespace

SkyModel::SkyModel(const SkyDescription& sky) : m_sky(sky) {
  m_up = normalize(sky.up);
  m_north = sky.north - m_up * dot(sky.north, m_up);
  if (!(length(m_up) > 0) || !(length(m_north) > 1e-9))
    throw std::invalid_argument("sky: \"up\" and \"north\" must be non-zero and not parallel");
  m_north = normalize(m_north);
  m_east = cross(m_north, m_up);
  const Vec3 sunLocal = atmosphere::sunDirection(sky.sunElevationDeg, sky.sunAzimuthDeg);
  m_sunDirection = toScene(sunLocal);
  m_sunCosRadius = std::cos(sky.sunAngularRadiusDeg * kDeg);

  switch (sky.type) {
    case SkyDescription::Type::Uniform:
      m_horizontalSky = sky.radiance * M_PI;
      break;
    case SkyDescription::Type::CieOvercast:
      // ∫ L_z (1 + 2 cos θ)/3 cos θ dω = 2π L_z (1/2 + 2/3)/3 = 7π L_z / 9.
      m_horizontalSky = sky.zenithRadiance * (7 * M_PI / 9);
      break;
    case SkyDescription::Type::Physical:
      tabulatePhysical();
      break;
  }
  if (sky.sun && sky.type != SkyDescription::Type::Physical && sky.sunElevationDeg > 0)
    m_sunIrradiance = sky.sunIrradiance;
  m_sunUp = sky.sun && maxComponent(m_sunIrradiance) > 0;
  if (!m_sunUp) m_sunIrradiance = {0, 0, 0};
  m_horizontalSun = m_sunIrradiance * std::max(0.0, sunLocal.z);
  m_groundRadiance = (m_horizontalSky + m_horizontalSun) * (sky.groundReflectance / M_PI);
}

std::string SkyModel::typeName() const {
  switch (m_sky.type) {
    case SkyDescription::Type::Uniform:
      return "uniform";
    case SkyDescription::Type::CieOvercast:
      return "cie-overcast";
    case SkyDescription::Type::Physical:
      return "physical";
  }
  return "?";
}

Vec3 SkyModel::radiance(const Vec3& d) const {
  const Vec3 local = toLocal(d);
  if (local.z <= 0) return m_groundRadiance;
  return skyRadiance(local);
}

Vec3 SkyModel::skyRadiance(const Vec3& local) const {
  switch (m_sky.type) {
    case SkyDescription::Type::Uniform:
      return m_sky.radiance;
    case SkyDescription::Type::CieOvercast:
      return m_sky.zenithRadiance * ((1 + 2 * std::min(1.0, local.z)) / 3);
    case SkyDescription::Type::Physical:
      return tableLookup(local);
  }
  return {0, 0, 0};
}

Vec3 SkyModel::tableLookup(const Vec3& local) const {
  const double elevation = std::asin(std::clamp(local.z, 0.0, 1.0));
  double azimuth = std::atan2(local.x, local.y);  // clockwise from north
  if (azimuth < 0) azimuth += 2 * M_PI;
  const double r = std::sqrt(elevation / (M_PI / 2)) * (m_rows - 1);
  const double c = azimuth / (2 * M_PI) * m_columns;
  const int r0 = std::min(int(r), m_rows - 2), c0 = std::min(int(c), m_columns - 1);
  const double fr = r - r0, fc = c - c0;
  auto at = [&](int row, int column) { return m_table[row * (m_columns + 1) + column]; };
  return (at(r0, c0) * (1 - fc) + at(r0, c0 + 1) * fc) * (1 - fr) +
         (at(r0 + 1, c0) * (1 - fc) + at(r0 + 1, c0 + 1) * fc) * fr;
}

void SkyModel::tabulatePhysical() {
  const auto start = std::chrono::steady_clock::now();
  atmosphere::AtmosphereParameters parameters;
  parameters.relativeDensity = m_sky.density;
  const atmosphere::Atmosphere air(parameters);
  const Vec3 eye = air.pointAtAltitude(m_sky.altitude);
  const Vec3 sun = atmosphere::sunDirection(m_sky.sunElevationDeg, m_sky.sunAzimuthDeg);
  m_rows = kTableRows, m_columns = kTableColumns;
  m_table.assign(std::size_t(m_rows) * (m_columns + 1), Vec3{});
  tbb::parallel_for(tbb::blocked_range<int>(0, m_rows), [&](const tbb::blocked_range<int>& range) {
    for (int row = range.begin(); row < range.end(); ++row) {
      const double t = double(row) / (m_rows - 1);
      // A hair above the horizon: the ray must leave the planet, not graze it.
      const double elevation = std::max(1e-4, M_PI / 2 * t * t);
      for (int column = 0; column <= m_columns; ++column) {
        const double azimuth = 2 * M_PI * column / m_columns;
        const Vec3 dir{std::cos(elevation) * std::sin(azimuth),
                       std::cos(elevation) * std::cos(azimuth), std::sin(elevation)};
        m_table[row * (m_columns + 1) + column] = air.skyRadiance(eye, dir, sun);
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
      ring += tableLookup({std::cos(e) * std::sin(a), std::cos(e) * std::cos(a), std::sin(e)});
    }
    sum += ring * (std::sin(e) * std::cos(e));
  }
  m_horizontalSky = sum * ((M_PI / 2) / ne * (2 * M_PI) / na);
  if (m_sky.sun) m_sunIrradiance = air.sunIrradiance(eye, sun);
  m_tableSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace radkit
