// Speed references for photon mapping, measured in the same run as the tracing: Embree's raw
// closest-hit rate on random rays in the scene, and the kd-tree's build and query rates.
#pragma once

#include <cstdint>
#include <vector>

#include "geometry/patch_mesh.h"
#include "geometry/visibility.h"
#include "photon/map.h"

namespace radkit {

struct RateMeasurement {
  std::size_t count = 0;  ///< operations timed
  double seconds = 0;
  double hitFraction = 0;  ///< closest-hit rates: the share of rays that hit something
  double perSecond() const { return seconds > 0 ? double(count) / seconds : 0.0; }
};

/// \brief Closest-hit queries per second (all threads, TBB) on `rays` random rays: origins
/// uniform in the mesh's bounding box, directions uniform on the sphere; stream (seed, i, 2).
RateMeasurement measureClosestHitRate(const PatchMesh& mesh, const Visibility& rays,
                                      std::size_t count, std::uint64_t seed);

/// \brief k-nearest irradiance estimates per second (all threads) at `queries` stored
/// photons' positions (every photons/queries-th one).
RateMeasurement measureKdTreeQueries(const PhotonMap& map, const PatchMesh& mesh,
                                     std::size_t queries, int k, IrradianceFilter filter);

}  // namespace radkit
