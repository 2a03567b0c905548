// The sky a scene declares ("sky" in the scene file, docs/daylight.md) as radiance over
// directions in scene coordinates: its model (sky/registry.cpp) in the scene's frame, with the
// sun beside it and the ground's glow below the horizon.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "geometry/scene.h"
#include "sky/sky_radiance.h"

namespace radkit {

class SkyModel {
 public:
  /// \throws std::invalid_argument for a description the loader would have refused.
  explicit SkyModel(const SkyDescription& sky);
  ~SkyModel();

  /// Radiance (W m⁻² sr⁻¹) arriving from unit direction `d` (scene coordinates, pointing away
  /// from the scene): the sky above the horizon, the ground's glow below it. The sun's disc
  /// is not included (sunIrradiance is).
  Vec3 radiance(const Vec3& d) const;
  /// Whether `d` lies above the horizon (what the sky view factor counts).
  bool aboveHorizon(const Vec3& d) const { return dot(d, m_up) > 0; }

  bool hasSun() const { return m_sunUp; }
  Vec3 sunDirection() const { return m_sunDirection; }  ///< unit, towards the sun
  /// Irradiance on a plane facing the sun (W/m² per channel), zero with the sun down.
  Vec3 sunIrradiance() const { return m_sunIrradiance; }
  double sunCosRadius() const { return m_sunCosRadius; }

  /// Unobstructed irradiance on a horizontal plane facing up: from the sky (without the
  /// ground's glow) and from the sun.
  Vec3 horizontalSky() const { return m_horizontalSky; }
  Vec3 horizontalSun() const { return m_horizontalSun; }

  const SkyDescription& description() const { return m_sky; }
  /// The model's name (sky/registry.cpp).
  const std::string& typeName() const { return m_sky.model; }
  /// What report.json says of the model beyond its name (SkyRadiance::report).
  std::map<std::string, double> modelReport() const { return m_model->report(); }

  /// The local frame (x east, y north, z up) of a scene direction, and back.
  Vec3 toLocal(const Vec3& d) const { return {dot(d, m_east), dot(d, m_north), dot(d, m_up)}; }
  Vec3 toScene(const Vec3& l) const { return m_east * l.x + m_north * l.y + m_up * l.z; }

 private:
  SkyDescription m_sky;
  std::unique_ptr<SkyRadiance> m_model;
  Vec3 m_up, m_north, m_east;
  bool m_sunUp = false;
  Vec3 m_sunDirection{0, 0, 1}, m_sunIrradiance{0, 0, 0};
  double m_sunCosRadius = 1;
  Vec3 m_horizontalSky{0, 0, 0}, m_horizontalSun{0, 0, 0}, m_groundRadiance{0, 0, 0};
};

}  // namespace radkit
