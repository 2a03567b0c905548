// A sky model: the radiance of the sky over the upper hemisphere, the plugin behind a scene's
// "sky": {"type": NAME, ...} (docs/daylight.md). The keys every sky has (sun, up, north,
// ground_reflectance, samples) are read by the scene loader; every other key is the model's
// own, read and range-checked by its create function (util/params.h), and the registry refuses
// the rest. A new model is one .cpp, one line in sky/registry.cpp and one in
// sky/CMakeLists.txt; scenes, `radkit terrain --sky` and the reports find it there.
#pragma once

#include <map>
#include <memory>
#include <string>

#include "util/registry.h"
#include "util/vec3.h"

namespace radkit {

class SkyRadiance {
 public:
  virtual ~SkyRadiance() = default;

  /// Whether the model's radiance depends on where the sun stands, so a scene must give one.
  virtual bool needsSun() const { return false; }
  /// Whether the model computes the sun's irradiance itself (from its atmosphere); the others
  /// take it from the scene's "sun" ("irradiance" or "illuminance").
  virtual bool computesSun() const { return false; }

  /// \brief Called once, before radiance(), with the sun's position (degrees; azimuth clockwise
  ///        from north). Heavy set-up (a table) happens here, not in the create function, so
  ///        that loading a scene only checks parameters.
  virtual void prepare(bool sun, double sunElevationDeg, double sunAzimuthDeg) {
    (void)sun, (void)sunElevationDeg, (void)sunAzimuthDeg;
  }

  /// Radiance (W m⁻² sr⁻¹ per channel) arriving from local direction d (x east, y north, z up,
  /// unit, d.z > 0).
  virtual Vec3 radiance(const Vec3& local) const = 0;
  /// ∫ L cos θ dω over the upper hemisphere: the irradiance of an open horizontal plane (W/m²).
  virtual Vec3 horizontalIrradiance() const = 0;
  /// The sun's normal irradiance (W/m²) for a model that computes it; zero with the sun down.
  virtual Vec3 sunIrradiance() const { return {0, 0, 0}; }

  /// What report.json says of the model beyond its name (parameters, set-up seconds); empty
  /// when there is nothing to say.
  virtual std::map<std::string, double> report() const { return {}; }
};

/// The sky models: uniform, cie-overcast, physical. An entry's example is a typical daylight
/// (10 000 lux on an open horizontal plane for the models whose brightness is a parameter; none
/// for the physical sky, whose defaults are the standard atmosphere), which `radkit terrain
/// --sky NAME` uses when no parameters are given.
using SkyRegistry = Registry<SkyRadiance>;
const SkyRegistry& skyRegistry();

}  // namespace radkit
