#include "daylight/sky.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "atmosphere/atmosphere.h"

namespace radkit {

namespace {
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

  // The loader checked the parameters; a description built in code is checked here.
  try {
    m_model = skyRegistry().make(sky.model, sky.parameters);
  } catch (const ParamError& e) {
    throw std::invalid_argument(std::string("sky: ") + e.what());
  }
  m_model->prepare(sky.sun, sky.sunElevationDeg, sky.sunAzimuthDeg);
  m_horizontalSky = m_model->horizontalIrradiance();
  if (m_model->computesSun())
    m_sunIrradiance = m_model->sunIrradiance();
  else if (sky.sun && sky.sunElevationDeg > 0)
    m_sunIrradiance = sky.sunIrradiance;
  m_sunUp = sky.sun && maxComponent(m_sunIrradiance) > 0;
  if (!m_sunUp) m_sunIrradiance = {0, 0, 0};
  m_horizontalSun = m_sunIrradiance * std::max(0.0, sunLocal.z);
  m_groundRadiance = (m_horizontalSky + m_horizontalSun) * (sky.groundReflectance / M_PI);
}

SkyModel::~SkyModel() = default;

Vec3 SkyModel::radiance(const Vec3& d) const {
  const Vec3 local = toLocal(d);
  if (local.z <= 0) return m_groundRadiance;
  return m_model->radiance(local);
}

}  // namespace radkit
