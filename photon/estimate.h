// Per-patch radiosity from photon tallies: the photon power landing on a patch over its area
// is its irradiance H, and B = E + ρ H as in the radiosity equation. With standard errors.
#pragma once

#include <string>
#include <vector>

#include "geometry/patch_mesh.h"
#include "geometry/scene.h"
#include "photon/map.h"

namespace radkit {

/// Photon estimate of one named surface.
struct SurfaceEstimate {
  std::string name;
  double area = 0;       ///< scene units²
  Vec3 irradiance;       ///< H_S = Φ_S / A_S, W/m²
  Vec3 radiosity;        ///< B_S = Ē_S + ρ_S H_S, W/m² (the area-weighted mean over its patches)
  Vec3 irradianceError;  ///< estimated standard error of H_S
  Vec3 radiosityError;   ///< estimated standard error of B_S (ρ_S times that of H_S)
  Vec3 causticIrradiance;       ///< the part of H_S carried by caustic (L S+ D) photons
  Vec3 causticIrradianceError;  ///< its estimated standard error
  std::size_t photons = 0;      ///< photons stored on the surface
};

/// Per-patch and per-surface estimates.
struct PhotonRadiosity {
  std::vector<Vec3> irradiance;      ///< per patch, W/m²
  std::vector<Vec3> radiosity;       ///< per patch, B_i = E_i + ρ_i H_i
  std::vector<Vec3> radiosityError;  ///< per patch, estimated standard error of B_i
  std::vector<SurfaceEstimate> surfaces;
};

/// \brief Tallies the photons of `paths` emitted photons (any order of paths, but the photons
/// of one path contiguous, as tracePhotons leaves them) into H_i = Σ_{p on i} Φ_p / A_i and
/// B_i = E_i + ρ_i H_i, with ρ the diffuse albedo the radiosity system uses.
/// The standard error treats each path j as one draw X_j (the power it leaves on the
/// patch or surface): Var(Σ_j X_j) = N/(N−1) · (Σ_j X_j² − (Σ_j X_j)²/N), paths that leave
/// nothing counting as zeros. Deterministic (serial).
PhotonRadiosity estimateRadiosity(const Scene& scene, const PatchMesh& mesh,
                                  const std::vector<Photon>& photons, std::size_t paths);

}  // namespace radkit
