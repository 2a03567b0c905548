// PhotonMap: photons stored on diffuse surfaces, a kd-tree over them (nanoflann) and the
// density estimate of irradiance from the k nearest photons (Jensen 1996; Jensen 2001, ch. 7).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "geometry/patch_mesh.h"
#include "util/vec3.h"

namespace radkit {

/// One photon hit on a diffuse surface: where, how much power arrived, on which patch, and
/// which emitted photon (path) it belongs to. Compact (float) as in Jensen 2001 §5.
struct Photon {
  float position[3];
  float power[3];           ///< incident power per RGB channel, scene units² · W/m²
  std::int32_t patch = -1;  ///< index into the PatchMesh
  std::uint32_t path = 0;   ///< index of the emitted photon whose path deposited it
  bool caustic = false;     ///< the path went emitter → (mirror | glass)+ → here (L S+ D)
  /// Toward where the photon came from, octahedral-encoded in 2 × 16 bits (Cigolle et al.
  /// 2014; error below 0.01°): what glossy BSDFs need to weigh the photon.
  std::uint16_t incoming[2] = {0, 0};

  Vec3 point() const { return {position[0], position[1], position[2]}; }
  Vec3 flux() const { return {power[0], power[1], power[2]}; }
  void setIncoming(const Vec3& unitDirection);
  Vec3 incomingDirection() const;
};

/// The kernel that weights photons in the irradiance estimate. Both vanish at the k-th
/// photon's distance r and integrate to one over the disc of radius r.
enum class IrradianceFilter {
  /// K(d) = 2/(πr²) · (1 − d²/r²)  (Silverman 1986, eq. 4.5 in two dimensions).
  Epanechnikov,
  /// Jensen's cone filter with k_cone = 1: K(d) = 3/(πr²) · (1 − d/r), i.e. weights
  /// 1 − d/(k_cone r) normalised by (1 − 2/(3 k_cone)) πr² (Jensen 2001, eq. 7.8).
  Cone,
};

const char* filterName(IrradianceFilter filter);

/// Result of one density estimate.
struct IrradianceEstimate {
  Vec3 irradiance;    ///< incident flux per area, W/m² per channel
  double radius = 0;  ///< distance to the k-th photon (0 when fewer than 2 were found)
  int photons = 0;    ///< photons gathered
};

/// Default most photons in one kd-tree of a PhotonMap: 2^19, which cut a 3.7M-photon map into
/// enough parts to build on two cores while a lookup still tests few part boxes.
constexpr std::size_t kMaxPhotonsPerKdPart = std::size_t(1) << 19;

/// \brief A kd-tree over photons. Queries only accept photons whose patch normal is within
/// ~25° of the query normal, so a corner's other wall does not leak into the estimate.
/// Queries are const and thread-safe. The mesh must outlive the map. The map reorders the
/// photons along a Morton curve (memory locality); photons() is that order.
class PhotonMap {
 public:
  /// \param maxPhotonsPerPart a map of more photons is cut into octree cells of at most this
  ///        many, whose kd-trees are built in parallel (queries give the same result)
  PhotonMap(const PatchMesh& mesh, std::vector<Photon> photons,
            std::size_t maxPhotonsPerPart = kMaxPhotonsPerKdPart);
  ~PhotonMap();
  PhotonMap(PhotonMap&&) noexcept;
  PhotonMap& operator=(PhotonMap&&) noexcept;

  std::size_t size() const { return m_photons.size(); }
  bool empty() const { return m_photons.empty(); }
  const std::vector<Photon>& photons() const { return m_photons; }
  /// Bytes of the photons plus the kd-tree nodes and index.
  std::size_t memoryBytes() const;
  /// Kd-trees the map was cut into (1 for a small map, 0 for an empty one).
  std::size_t kdParts() const;

  /// \brief Indices of (at most) k nearest photons to `x` on surfaces facing along `normal`,
  /// nearest first, with their squared distances.
  void nearest(const Vec3& x, const Vec3& normal, int k, std::vector<std::uint32_t>& index,
               std::vector<float>& distance2) const;

  /// \brief Irradiance at surface point x (unit normal n) from the k nearest photons:
  /// E(x) ≈ Σ_p K(d_p) ΔΦ_p (Jensen 2001, eq. 7.6 with a normalised kernel).
  IrradianceEstimate irradiance(const Vec3& x, const Vec3& n, int k, IrradianceFilter filter) const;
  /// \brief Reflected radiance at x from the k nearest photons, Σ_p K(d_p) f(ω_p) ΔΦ_p, with
  /// f the BSDF for the photon's (world) incoming direction ω_p toward the viewer (Jensen
  /// 2001, eq. 7.6). Returned in `irradiance`; with f = 1 it is irradiance().
  IrradianceEstimate reflected(const Vec3& x, const Vec3& n, int k, IrradianceFilter filter,
                               const std::function<Vec3(const Vec3& incoming)>& f) const;

  /// \brief Precomputes the estimate at every `stride`-th photon (Christensen 1999, "Faster
  /// photon map global illumination"), for cheap final-gather lookups. Parallel.
  void precomputeIrradiance(int k, IrradianceFilter filter, int stride);
  bool hasPrecomputed() const { return !m_precomputed.empty(); }
  /// \brief The precomputed irradiance of the nearest precomputed photon facing along n;
  /// zero when x lies outside that photon's own estimate radius (a region with no photons).
  /// Requires precomputeIrradiance().
  Vec3 precomputedIrradiance(const Vec3& x, const Vec3& n) const;

 private:
  struct Tree;
  const PatchMesh* m_mesh;
  std::size_t m_maxPhotonsPerPart;
  std::vector<Photon> m_photons;
  std::unique_ptr<Tree> m_tree;
  std::vector<Photon> m_precomputed;  ///< position, patch and irradiance (in `power`)
  std::vector<float> m_precomputedRadius;
  std::unique_ptr<Tree> m_precomputedTree;
};

/// Normal agreement a photon needs to count in an estimate: cos 25°.
constexpr double kPhotonNormalCosine = 0.906;

/// The two maps a photon image reads: the global map (every stored photon) and the caustic
/// map (photons whose path went emitter → (mirror | glass)+ → diffuse).
struct PhotonMaps {
  std::unique_ptr<PhotonMap> global, caustic;
};

/// \brief Splits stored photons into the global and caustic maps and builds both kd-trees.
PhotonMaps buildPhotonMaps(const PatchMesh& mesh, std::vector<Photon> photons);

}  // namespace radkit
