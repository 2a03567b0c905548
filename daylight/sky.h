// The sky a scene declares ("sky" in the scene file, docs/daylight.md) as radiance over
// directions in scene coordinates: a uniform sky, the CIE standard overcast sky, or the
// physical sky of atmosphere/ (tabulated once per run), with the sun beside it.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "geometry/scene.h"

namespace radkit {

class SkyModel {
 public:
  /// \throws std::invalid_argument for a description the loader would have refused.
  explicit SkyModel(const SkyDescription& sky);

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
  std::string typeName() const;
  /// Seconds spent tabulating the physical sky (0 for the others).
  double tableSeconds() const { return m_tableSeconds; }

  /// The local frame (x east, y north, z up) of a scene direction, and back.
  Vec3 toLocal(const Vec3& d) const { return {dot(d, m_east), dot(d, m_north), dot(d, m_up)}; }
  Vec3 toScene(const Vec3& l) const { return m_east * l.x + m_north * l.y + m_up * l.z; }

 private:
  Vec3 skyRadiance(const Vec3& local) const;  ///< above the horizon
  Vec3 tableLookup(const Vec3& local) const;
  void tabulatePhysical();

  SkyDescription m_sky;
  Vec3 m_up, m_north, m_east;
  bool m_sunUp = false;
  Vec3 m_sunDirection{0, 0, 1}, m_sunIrradiance{0, 0, 0};
  double m_sunCosRadius = 1;
  Vec3 m_horizontalSky{0, 0, 0}, m_horizontalSun{0, 0, 0}, m_groundRadiance{0, 0, 0};
  // The physical sky: radiance at rows of elevation e = (π/2) t², t = row/(rows − 1) (fine
  // near the horizon, where it changes fastest) and columns of azimuth, bilinear between.
  int m_rows = 0, m_columns = 0;
  std::vector<Vec3> m_table;
  double m_tableSeconds = 0;
};

}  // namespace radkit
