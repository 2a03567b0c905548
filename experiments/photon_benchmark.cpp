#include "experiments/photon_benchmark.h"

#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <cmath>

#include "util/format.h"
#include "util/sampling.h"

namespace radkit {

RateMeasurement measureClosestHitRate(const PatchMesh& mesh, const Visibility& rays,
                                      std::size_t count, std::uint64_t seed) {
  const Bounds3 box = mesh.bounds();
  std::atomic<std::size_t> hits{0};
  const auto start = std::chrono::steady_clock::now();
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 4096),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      std::size_t local = 0;
                      for (std::size_t i = r.begin(); i != r.end(); ++i) {
                        Rng rng(seed, i, 2);
                        const Vec3 o{box.lo.x + (box.hi.x - box.lo.x) * rng.uniform(),
                                     box.lo.y + (box.hi.y - box.lo.y) * rng.uniform(),
                                     box.lo.z + (box.hi.z - box.lo.z) * rng.uniform()};
                        // Uniform on the sphere: z uniform in [−1, 1], φ uniform (Archimedes); pdf
                        // 1/(4π).
                        const double z = 1 - 2 * rng.uniform(), phi = 2 * M_PI * rng.uniform();
                        const double s = std::sqrt(std::max(0.0, 1 - z * z));
                        if (rays.closestHit(o, {s * std::cos(phi), s * std::sin(phi), z}, 0))
                          ++local;
                      }
                      hits += local;
                    });
  const double seconds = secondsSince(start);
  return {count, seconds, count ? double(hits.load()) / double(count) : 0.0};
}

RateMeasurement measureKdTreeQueries(const PhotonMap& map, const PatchMesh& mesh,
                                     std::size_t queries, int k, IrradianceFilter filter) {
  if (map.empty() || queries == 0) return {};
  const std::size_t stride = std::max<std::size_t>(1, map.size() / queries);
  const std::size_t count = (map.size() + stride - 1) / stride;
  const auto start = std::chrono::steady_clock::now();
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 256),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i != r.end(); ++i) {
                        const Photon& p = map.photons()[i * stride];
                        map.irradiance(p.point(), mesh.patches[p.patch].normal, k, filter);
                      }
                    });
  return {count, secondsSince(start)};
}

}  // namespace radkit
