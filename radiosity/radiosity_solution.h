// From a meshed scene and its form factors to the radiosity system, and from a solution to
// what users read: per-surface radiosity, irradiance, photometric units and energy balance.
#pragma once

#include <string>
#include <vector>

#include "geometry/patch_mesh.h"
#include "geometry/scene.h"
#include "solvers/radiosity_system.h"
#include "util/photometry.h"

namespace radkit {

/// \brief B = E + ρFB for the patches: areas in m² (scene units converted), ρ and E per
/// channel from each patch's surface material. `f` must outlive the system.
RadiositySystem makeRadiositySystem(const Scene& scene, const PatchMesh& mesh,
                                    const FormFactorMatrix& f);

std::vector<Vec3> toVec3(const Channels& c);

/// Irradiance H_i = Σ_j F_ij B_j (W/m²): the flux density arriving at each patch.
std::vector<Vec3> irradiance(const FormFactorMatrix& f, const Channels& radiosity);

/// Area-weighted means over one named surface.
struct SurfaceResult {
  std::string name;
  double area = 0;         ///< m²
  Vec3 radiosity;          ///< W/m²
  Vec3 irradiance;         ///< W/m²
  double luminance = 0;    ///< cd/m²: 683 · Y(B) / π (Lambertian, L = B/π)
  double illuminance = 0;  ///< lux: 683 · Y(H)
  // With a sky (scene.sky): the daylight arriving directly, before interreflection.
  bool daylit = false;
  double skyViewFactor = 0;        ///< area-weighted mean over the surface
  Vec3 daylight;                   ///< W/m², sky and sun
  double daylightIlluminance = 0;  ///< lux: 683 · Y(daylight)
};

/// \brief Per-surface results; Y is the Rec. 709 luminance of the RGB triple.
std::vector<SurfaceResult> surfaceResults(const Scene& scene, const PatchMesh& mesh,
                                          const std::vector<Vec3>& radiosity,
                                          const std::vector<Vec3>& irradiance);

/// Power bookkeeping of a solution, in W per channel. Emitted light is either absorbed
/// (A_i(1-ρ_i)H_i) or leaves the scene (A_i B_i (1 − Σ_j F_ij)); the relative imbalance
/// measures how far the solution and F are from conserving energy.
struct EnergyBalance {
  Vec3 emitted, absorbed, escaped;
  double relativeImbalance = 0;  ///< max over channels |emitted − absorbed − escaped| / emitted
};

/// \param irradiance  everything arriving at each patch (with `daylight` included)
/// \param daylight    light arriving from outside the scene (a sky, the sun), or nullptr; it
///                    counts as emitted: the power the scene takes in
EnergyBalance energyBalance(const Scene& scene, const PatchMesh& mesh, const FormFactorMatrix& f,
                            const std::vector<Vec3>& radiosity, const std::vector<Vec3>& irradiance,
                            const std::vector<Vec3>* daylight = nullptr);

}  // namespace radkit
