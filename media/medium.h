// Participating media for the volumetric path tracer and the cloud marcher: grey extinction
// σ_t(x) (1/m), a single-scattering albedo and a phase function. A homogeneous box for tests,
// and a cloud layer built the real-time way (Schneider 2015) (weather map, noise, height
// gradients).
#pragma once

#include <memory>
#include <vector>

#include "noise/noise3d.h"
#include "phase/phase_function.h"
#include "util/vec3.h"

namespace radkit::media {

class Medium {
 public:
  virtual ~Medium() = default;
  /// Extinction coefficient σ_t at p (1/m), zero outside bounds().
  virtual double extinction(const Vec3& p) const = 0;
  /// An upper bound of extinction() over bounds(): delta and ratio tracking's majorant.
  virtual double majorant() const = 0;
  /// The box outside which the medium is empty.
  virtual Bounds3 bounds() const = 0;
  /// σ_s / σ_t, the same everywhere.
  virtual double albedo() const = 0;
  virtual const PhaseFunction& phase() const = 0;
};

/// \brief The part [t0, t1] of the ray o + t·d (t ≥ 0) inside box b; false when it misses.
bool clipRay(const Bounds3& b, const Vec3& o, const Vec3& d, double& t0, double& t1);

/// Constant σ_t inside an axis-aligned box.
class HomogeneousBox final : public Medium {
 public:
  HomogeneousBox(const Bounds3& box, double extinction, double albedo,
                 std::unique_ptr<PhaseFunction> phase);
  double extinction(const Vec3& p) const override;
  double majorant() const override { return m_sigmaT; }
  Bounds3 bounds() const override { return m_box; }
  double albedo() const override { return m_albedo; }
  const PhaseFunction& phase() const override { return *m_phase; }

 private:
  Bounds3 m_box;
  double m_sigmaT, m_albedo;
  std::unique_ptr<PhaseFunction> m_phase;
};

/// A cloud layer over a horizontal square (x east, y north, z up, metres), after Schneider
/// (2015): a weather map gives coverage and cloud type per column; the type sets a height
/// gradient (stratus low and thin, stratocumulus, cumulus tall); the base shape texture, eroded
/// by the detail texture near the edges, gives the density; σ_t = extinction · density.
struct CloudLayerSettings {
  double bottom = 1500, top = 4000;  ///< altitude of the layer (m)
  double size = 16000;               ///< side of the square the layer covers (m)
  double coverage = 0.5;             ///< mean cloud cover in [0, 1]
  double cloudType = 0.8;  ///< 0 stratus, 0.5 stratocumulus, 1 cumulus (mean; the map varies it)
  double extinction =
      0.08;  ///< σ_t of dense cloud (1/m): OPAC cumulus 0.05–0.12, stratus 0.04–0.06
  double albedo = 0.999;         ///< water droplets absorb almost nothing in the visible
  double shapePeriod = 6000;     ///< metres per period of the shape texture
  double detailPeriod = 800;     ///< metres per period of the detail texture
  double detailErosion = 0.35;   ///< how much detail noise erodes the shape at its edges
  double weatherPeriod = 16000;  ///< metres per period of the weather map
  int shapeSize = 128, detailSize = 64;
  std::uint32_t seed = 1;
};

class CloudLayer final : public Medium {
 public:
  CloudLayer(const CloudLayerSettings& settings, std::unique_ptr<PhaseFunction> phase);
  double extinction(const Vec3& p) const override;
  double majorant() const override { return m_s.extinction; }
  Bounds3 bounds() const override;
  double albedo() const override { return m_s.albedo; }
  const PhaseFunction& phase() const override { return *m_phase; }
  /// Density in [0, 1] at p (extinction / settings.extinction).
  double density(const Vec3& p) const;
  /// The weather map at (x, y): coverage and cloud type in [0, 1].
  void weather(double x, double y, double& coverage, double& type) const;
  const CloudLayerSettings& settings() const { return m_s; }

 private:
  /// Bilinear, wrapping lookup of a weather grid (m_weatherSize² floats over weatherPeriod).
  double weatherGrid(const std::vector<float>& grid, double x, double y) const;
  /// Local coverage from the weather noise value: 0 below m_threshold, rising to 1.
  double coverageFromNoise(double n) const;

  CloudLayerSettings m_s;
  CloudNoise m_noise;
  std::unique_ptr<PhaseFunction> m_phase;
  int m_weatherSize = 0;
  std::vector<float> m_weatherNoise, m_weatherType;  ///< the weather map's two noise fields
  double m_threshold = 0;  ///< weather noise where coverage starts, calibrated to the cover
};

}  // namespace radkit::media
