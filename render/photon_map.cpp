#include "render/photon_map.h"

#include <nanoflann.hpp>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace radkit {

namespace {

/// nanoflann's dataset adaptor: points are the photons' positions. Holds the buffer, not the
/// vector, so moving the owning PhotonMap keeps it valid.
struct PhotonCloud {
  const Photon* data = nullptr;
  std::size_t count = 0;
  std::size_t kdtree_get_point_count() const { return count; }
  float kdtree_get_pt(std::uint32_t i, std::size_t dim) const { return data[i].position[dim]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }
};

using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, PhotonCloud>,
                                                   PhotonCloud, 3, std::uint32_t>;

/// k nearest photons that pass a normal test, kept in a max-heap on distance (O(log k) per
/// candidate; nanoflann's KNNResultSet sorts by insertion, O(k)). Rejected photons never
/// enter, so the k found are the k nearest acceptable ones.
class FacingKnnResultSet {
 public:
  using DistanceType = float;
  using IndexType = std::uint32_t;
  using Entry = std::pair<float, std::uint32_t>;

  FacingKnnResultSet(std::size_t k, const Photon* photons, const PatchMesh& mesh, const Vec3& n,
                     std::vector<Entry>& heap)
      : m_k(k), m_photons(photons), m_mesh(mesh), m_normal(n), m_heap(heap) {
    m_heap.clear();
    m_heap.reserve(k);
  }
  std::size_t size() const { return m_heap.size(); }
  bool full() const { return m_heap.size() == m_k; }
  float worstDist() const { return full() ? m_heap.front().first : std::numeric_limits<float>::max(); }
  bool addPoint(float distance2, std::uint32_t index) {
    const Vec3& pn = m_mesh.patches[m_photons[index].patch].normal;
    if (std::fabs(dot(pn, m_normal)) < kPhotonNormalCosine) return true;  // keep searching
    if (!full()) {
      m_heap.emplace_back(distance2, index);
      std::push_heap(m_heap.begin(), m_heap.end());
    } else if (distance2 < m_heap.front().first) {
      std::pop_heap(m_heap.begin(), m_heap.end());
      m_heap.back() = {distance2, index};
      std::push_heap(m_heap.begin(), m_heap.end());
    }
    return true;
  }
  /// Nearest first.
  void finish() { std::sort_heap(m_heap.begin(), m_heap.end()); }

 private:
  std::size_t m_k;
  const Photon* m_photons;
  const PatchMesh& m_mesh;
  Vec3 m_normal;
  std::vector<Entry>& m_heap;
};

/// Spreads the low 21 bits of v to every third bit (for 63-bit Morton codes).
std::uint64_t spreadBits(std::uint64_t v) {
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffffULL;
  v = (v | v << 16) & 0x1f0000ff0000ffULL;
  v = (v | v << 8) & 0x100f00f00f00f00fULL;
  v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}

/// Orders photons along a Morton (Z-order) curve over their bounding box, so photons near in
/// space sit near in memory: the kd-tree's leaves then read contiguous memory. Stable, so
/// the order stays deterministic.
void sortAlongMortonCurve(std::vector<Photon>& photons) {
  if (photons.size() < 2) return;
  float lo[3], hi[3];
  for (int c = 0; c < 3; ++c) lo[c] = hi[c] = photons[0].position[c];
  for (const Photon& p : photons)
    for (int c = 0; c < 3; ++c) lo[c] = std::min(lo[c], p.position[c]), hi[c] = std::max(hi[c], p.position[c]);
  std::vector<std::pair<std::uint64_t, std::uint32_t>> key(photons.size());
  for (std::size_t i = 0; i < photons.size(); ++i) {
    std::uint64_t code = 0;
    for (int c = 0; c < 3; ++c) {
      const double t = hi[c] > lo[c] ? (photons[i].position[c] - lo[c]) / double(hi[c] - lo[c]) : 0.0;
      code |= spreadBits(std::uint64_t(t * 2097151.0)) << c;
    }
    key[i] = {code, std::uint32_t(i)};
  }
  std::sort(key.begin(), key.end());
  std::vector<Photon> sorted(photons.size());
  for (std::size_t i = 0; i < key.size(); ++i) sorted[i] = photons[key[i].second];
  photons.swap(sorted);
}

}  // namespace

struct PhotonMap::Tree {
  PhotonCloud cloud;
  KdTree index;
  explicit Tree(const std::vector<Photon>& photons)
      : cloud{photons.data(), photons.size()}, index(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10)) {}
  std::size_t memoryBytes() { return index.usedMemory(index); }
};

const char* filterName(IrradianceFilter filter) {
  return filter == IrradianceFilter::Cone ? "cone" : "epanechnikov";
}

PhotonMap::PhotonMap(const PatchMesh& mesh, std::vector<Photon> photons)
    : m_mesh(&mesh), m_photons(std::move(photons)) {
  sortAlongMortonCurve(m_photons);
  if (!m_photons.empty()) m_tree = std::make_unique<Tree>(m_photons);
}

PhotonMap::~PhotonMap() = default;
PhotonMap::PhotonMap(PhotonMap&&) noexcept = default;
PhotonMap& PhotonMap::operator=(PhotonMap&&) noexcept = default;

std::size_t PhotonMap::memoryBytes() const {
  std::size_t bytes = m_photons.capacity() * sizeof(Photon) + m_precomputed.capacity() * sizeof(Photon) +
                      m_precomputedRadius.capacity() * sizeof(float);
  if (m_tree) bytes += m_tree->memoryBytes();
  if (m_precomputedTree) bytes += m_precomputedTree->memoryBytes();
  return bytes;
}

void PhotonMap::nearest(const Vec3& x, const Vec3& normal, int k, std::vector<std::uint32_t>& index,
                        std::vector<float>& distance2) const {
  index.clear();
  distance2.clear();
  if (!m_tree || k <= 0) return;
  const float query[3] = {float(x.x), float(x.y), float(x.z)};
  std::vector<std::pair<float, std::uint32_t>> heap;
  FacingKnnResultSet result(std::size_t(k), m_photons.data(), *m_mesh, normal, heap);
  m_tree->index.findNeighbors(result, query, nanoflann::SearchParams());
  result.finish();
  for (const auto& [d2, i] : heap) {
    index.push_back(i);
    distance2.push_back(d2);
  }
}

IrradianceEstimate PhotonMap::irradiance(const Vec3& x, const Vec3& n, int k, IrradianceFilter filter) const {
  std::vector<std::uint32_t> index;
  std::vector<float> distance2;
  nearest(x, n, k, index, distance2);
  IrradianceEstimate e;
  e.photons = int(index.size());
  if (index.size() < 2) return e;
  // r is the distance to the farthest photon gathered; it gets weight zero, which makes the
  // estimate unbiased where the density is uniform (E[(k−1)/Λ(r)] = 1 for a Poisson process).
  const double r2 = distance2.back();
  if (!(r2 > 0)) return e;
  e.radius = std::sqrt(r2);
  Vec3 sum;
  for (std::size_t p = 0; p < index.size(); ++p) {
    const double t2 = distance2[p] / r2;
    const double w = filter == IrradianceFilter::Cone ? 3 * (1 - std::sqrt(t2)) : 2 * (1 - t2);
    sum += m_photons[index[p]].flux() * w;
  }
  e.irradiance = sum / (M_PI * r2);
  return e;
}

void PhotonMap::precomputeIrradiance(int k, IrradianceFilter filter, int stride) {
  const std::size_t count = (m_photons.size() + stride - 1) / std::size_t(stride);
  m_precomputed.assign(count, Photon{});
  m_precomputedRadius.assign(count, 0.f);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 256), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      Photon p = m_photons[i * stride];
      IrradianceEstimate e = irradiance(p.point(), m_mesh->patches[p.patch].normal, k, filter);
      for (int c = 0; c < 3; ++c) p.power[c] = float(e.irradiance[c]);
      m_precomputed[i] = p;
      m_precomputedRadius[i] = float(e.radius);
    }
  });
  m_precomputedTree = count ? std::make_unique<Tree>(m_precomputed) : nullptr;
}

Vec3 PhotonMap::precomputedIrradiance(const Vec3& x, const Vec3& n) const {
  if (!m_precomputedTree) return {};
  const float query[3] = {float(x.x), float(x.y), float(x.z)};
  std::vector<std::pair<float, std::uint32_t>> heap;
  FacingKnnResultSet result(1, m_precomputed.data(), *m_mesh, n, heap);
  m_precomputedTree->index.findNeighbors(result, query, nanoflann::SearchParams());
  if (result.size() == 0) return {};
  const auto [distance2, index] = heap.front();
  const double r = m_precomputedRadius[index];
  if (double(distance2) > r * r) return {};
  return m_precomputed[index].flux();
}

PhotonMaps buildPhotonMaps(const PatchMesh& mesh, std::vector<Photon> photons) {
  std::vector<Photon> caustic;
  for (const Photon& p : photons)
    if (p.caustic) caustic.push_back(p);
  PhotonMaps maps;
  maps.global = std::make_unique<PhotonMap>(mesh, std::move(photons));
  maps.caustic = std::make_unique<PhotonMap>(mesh, std::move(caustic));
  return maps;
}

}  // namespace radkit
