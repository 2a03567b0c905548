#include "photon/map.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>
#include <nanoflann.hpp>

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
  /// Index of the first photon of the part being searched: parts number photons from 0.
  void setBase(std::uint32_t base) { m_base = base; }
  std::size_t size() const { return m_heap.size(); }
  bool full() const { return m_heap.size() == m_k; }
  float worstDist() const {
    return full() ? m_heap.front().first : std::numeric_limits<float>::max();
  }
  bool addPoint(float distance2, std::uint32_t local) {
    const std::uint32_t index = m_base + local;
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
  std::uint32_t m_base = 0;
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

/// The bounds of some photons' positions.
struct PhotonBox {
  float lo[3], hi[3];

  /// \brief The box of photons[0, count); count >= 1.
  static PhotonBox of(const Photon* photons, std::size_t count) {
    PhotonBox b;
    for (int c = 0; c < 3; ++c) b.lo[c] = b.hi[c] = photons[0].position[c];
    for (std::size_t i = 1; i < count; ++i)
      for (int c = 0; c < 3; ++c) {
        b.lo[c] = std::min(b.lo[c], photons[i].position[c]);
        b.hi[c] = std::max(b.hi[c], photons[i].position[c]);
      }
    return b;
  }
  /// Squared distance from q to the box (0 inside).
  float distance2(const float q[3]) const {
    float d2 = 0.f;
    for (int c = 0; c < 3; ++c) {
      const float d = q[c] < lo[c] ? lo[c] - q[c] : (q[c] > hi[c] ? q[c] - hi[c] : 0.f);
      d2 += d * d;
    }
    return d2;
  }
  /// 63-bit Morton code of p over the box: 21 bits per axis, interleaved x, y, z from the
  /// lowest bit up.
  std::uint64_t mortonCode(const float p[3]) const {
    std::uint64_t code = 0;
    for (int c = 0; c < 3; ++c) {
      const double t = hi[c] > lo[c] ? (p[c] - lo[c]) / double(hi[c] - lo[c]) : 0.0;
      code |= spreadBits(std::uint64_t(t * 2097151.0)) << c;
    }
    return code;
  }
};

/// Orders photons along a Morton (Z-order) curve over their bounding box, so photons near in
/// space sit near in memory: the kd-tree's leaves then read contiguous memory (without it,
/// queries ran at half the rate). Keys are unique (code, index) pairs, so the parallel sort gives
/// one order whatever the threads. Returns the codes, ascending; `frame` receives the box.
/// Requires photons.
std::vector<std::uint64_t> sortAlongMortonCurve(std::vector<Photon>& photons, PhotonBox& frame) {
  frame = PhotonBox::of(photons.data(), photons.size());
  std::vector<std::pair<std::uint64_t, std::uint32_t>> key(photons.size());
  tbb::parallel_for(std::size_t(0), photons.size(), [&](std::size_t i) {
    key[i] = {frame.mortonCode(photons[i].position), std::uint32_t(i)};
  });
  tbb::parallel_sort(key.begin(), key.end());
  std::vector<Photon> sorted(photons.size());
  std::vector<std::uint64_t> codes(photons.size());
  tbb::parallel_for(std::size_t(0), key.size(), [&](std::size_t i) {
    sorted[i] = photons[key[i].second];
    codes[i] = key[i].first;
  });
  photons.swap(sorted);
  return codes;
}

/// Appends the ends of the octree cells that partition codes[first, last) (one cell of `depth`,
/// so one Morton range) to `ends`, in order: a cell of more than maxPerCell photons is replaced
/// by its non-empty children. Cells are disjoint, so their photons' boxes are too. The cells
/// depend on the codes and maxPerCell only, never on threads.
void octreeCells(const std::vector<std::uint64_t>& codes, std::size_t first, std::size_t last,
                 int depth, std::size_t maxPerCell, std::vector<std::size_t>& ends) {
  if (last - first <= maxPerCell || depth == 21) {  // 21 levels of 3 bits: one point
    ends.push_back(last);
    return;
  }
  const int shift = 60 - 3 * depth;  // the children's three bits
  const std::uint64_t cell = codes[first] >> (shift + 3) << (shift + 3);
  const auto begin = codes.begin();
  auto childFirst = begin + std::ptrdiff_t(first);
  for (std::uint64_t child = 1; child <= 8; ++child) {
    const auto childLast = child == 8 ? begin + std::ptrdiff_t(last)
                                      : std::lower_bound(childFirst, begin + std::ptrdiff_t(last),
                                                         cell | child << shift);
    if (childLast > childFirst)
      octreeCells(codes, std::size_t(childFirst - begin), std::size_t(childLast - begin), depth + 1,
                  maxPerCell, ends);
    childFirst = childLast;
  }
}

}  // namespace

/// The kd-tree over a map. nanoflann builds one tree on one thread, which took half of a
/// 2M-photon run; so a large map is cut into octree cells (contiguous in Morton order, disjoint
/// in space) whose trees are built in parallel. A query searches the part with the nearest
/// box, then every other part whose box is nearer than the k-th photon found, so it returns
/// exactly the neighbours one tree would.
struct PhotonMap::Tree {
  struct Part {
    PhotonCloud cloud;
    KdTree index;
    std::uint32_t base;
    PhotonBox box;
    Part(const Photon* photons, std::size_t count, std::uint32_t first)
        : cloud{photons + first, count},
          index(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10)),
          base(first),
          box(PhotonBox::of(photons + first, count)) {}
  };
  std::vector<std::unique_ptr<Part>> parts;
  PhotonBox frame;  ///< the box the photons' Morton codes were taken over

  /// \param ends the parts' ends in photons, ascending; no part is empty (octreeCells)
  Tree(const std::vector<Photon>& photons, const std::vector<std::size_t>& ends, const PhotonBox& f)
      : frame(f) {
    parts.resize(ends.size());
    tbb::parallel_for(std::size_t(0), ends.size(), [&](std::size_t p) {
      const std::size_t first = p ? ends[p - 1] : 0;
      parts[p] = std::make_unique<Part>(photons.data(), ends[p] - first, std::uint32_t(first));
    });
  }

  /// Feeds every part that can hold one of the k nearest to `result`: the part whose box is
  /// nearest first (it holds the query, or is beside it), then any other whose box is nearer
  /// than the k-th photon found. No sort: with k = 1 lookups (final gathering) a sort of the
  /// parts cost more than the lookup.
  void search(FacingKnnResultSet& result, const float q[3]) const {
    if (parts.size() == 1) {
      parts[0]->index.findNeighbors(result, q, nanoflann::SearchParams());
      return;
    }
    thread_local std::vector<float> boxDistance2;
    boxDistance2.resize(parts.size());
    std::size_t nearest = 0;
    for (std::size_t p = 0; p < parts.size(); ++p) {
      boxDistance2[p] = parts[p]->box.distance2(q);
      if (boxDistance2[p] < boxDistance2[nearest]) nearest = p;
    }
    auto visit = [&](std::size_t p) {
      result.setBase(parts[p]->base);
      parts[p]->index.findNeighbors(result, q, nanoflann::SearchParams());
    };
    visit(nearest);
    for (std::size_t p = 0; p < parts.size(); ++p)
      // The slack covers float rounding between a box's distance and its photons' distances.
      if (p != nearest && (!result.full() || boxDistance2[p] <= result.worstDist() * (1.f + 1e-5f)))
        visit(p);
  }

  std::size_t memoryBytes() const {
    std::size_t bytes = 0;
    for (const auto& part : parts) bytes += sizeof(Part) + part->index.usedMemory(part->index);
    return bytes;
  }
};

const char* filterName(IrradianceFilter filter) {
  return filter == IrradianceFilter::Cone ? "cone" : "epanechnikov";
}

PhotonMap::PhotonMap(const PatchMesh& mesh, std::vector<Photon> photons,
                     std::size_t maxPhotonsPerPart)
    : m_mesh(&mesh),
      m_maxPhotonsPerPart(std::max<std::size_t>(1, maxPhotonsPerPart)),
      m_photons(std::move(photons)) {
  if (m_photons.empty()) return;
  PhotonBox frame;
  const std::vector<std::uint64_t> codes = sortAlongMortonCurve(m_photons, frame);
  std::vector<std::size_t> ends;
  octreeCells(codes, 0, codes.size(), 0, m_maxPhotonsPerPart, ends);
  m_tree = std::make_unique<Tree>(m_photons, ends, frame);
}

PhotonMap::~PhotonMap() = default;
PhotonMap::PhotonMap(PhotonMap&&) noexcept = default;
PhotonMap& PhotonMap::operator=(PhotonMap&&) noexcept = default;

std::size_t PhotonMap::kdParts() const { return m_tree ? m_tree->parts.size() : 0; }

std::size_t PhotonMap::memoryBytes() const {
  std::size_t bytes = m_photons.capacity() * sizeof(Photon) +
                      m_precomputed.capacity() * sizeof(Photon) +
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
  m_tree->search(result, query);
  result.finish();
  for (const auto& [d2, i] : heap) {
    index.push_back(i);
    distance2.push_back(d2);
  }
}

namespace {

/// Octahedral map of the unit sphere onto [−1, 1]² (Cigolle et al. 2014, JCGT 3(2)).
double signNotZero(double v) { return v >= 0 ? 1.0 : -1.0; }
std::uint16_t quantise(double v) {
  return std::uint16_t(std::lround((std::clamp(v, -1.0, 1.0) * 0.5 + 0.5) * 65535));
}

}  // namespace

void Photon::setIncoming(const Vec3& w) {
  const double l1 = std::abs(w.x) + std::abs(w.y) + std::abs(w.z);
  double u = w.x / l1, v = w.y / l1;
  if (w.z < 0) {
    const double fu = (1 - std::abs(v)) * signNotZero(u), fv = (1 - std::abs(u)) * signNotZero(v);
    u = fu, v = fv;
  }
  incoming[0] = quantise(u);
  incoming[1] = quantise(v);
}

Vec3 Photon::incomingDirection() const {
  const double u = incoming[0] / 65535.0 * 2 - 1, v = incoming[1] / 65535.0 * 2 - 1;
  Vec3 w{u, v, 1 - std::abs(u) - std::abs(v)};
  if (w.z < 0) {
    const double fx = (1 - std::abs(v)) * signNotZero(u), fy = (1 - std::abs(u)) * signNotZero(v);
    w.x = fx, w.y = fy;
  }
  return normalize(w);
}

IrradianceEstimate PhotonMap::irradiance(const Vec3& x, const Vec3& n, int k,
                                         IrradianceFilter filter) const {
  return reflected(x, n, k, filter, nullptr);
}

IrradianceEstimate PhotonMap::reflected(const Vec3& x, const Vec3& n, int k,
                                        IrradianceFilter filter,
                                        const std::function<Vec3(const Vec3&)>& f) const {
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
    const Photon& photon = m_photons[index[p]];
    sum += (f ? mul(f(photon.incomingDirection()), photon.flux()) : photon.flux()) * w;
  }
  e.irradiance = sum / (M_PI * r2);
  return e;
}

void PhotonMap::precomputeIrradiance(int k, IrradianceFilter filter, int stride) {
  const std::size_t count = (m_photons.size() + stride - 1) / std::size_t(stride);
  m_precomputed.assign(count, Photon{});
  m_precomputedRadius.assign(count, 0.f);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 256),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i != r.end(); ++i) {
                        Photon p = m_photons[i * stride];
                        IrradianceEstimate e =
                            irradiance(p.point(), m_mesh->patches[p.patch].normal, k, filter);
                        for (int c = 0; c < 3; ++c) p.power[c] = float(e.irradiance[c]);
                        m_precomputed[i] = p;
                        m_precomputedRadius[i] = float(e.radius);
                      }
                    });
  if (!count) {
    m_precomputedTree = nullptr;
    return;
  }
  // Every stride-th photon of a Morton order is in Morton order: its own octree cells, which
  // are fewer than the map's (each part costs a k = 1 lookup a box test).
  std::vector<std::uint64_t> codes(count);
  tbb::parallel_for(std::size_t(0), count, [&](std::size_t i) {
    codes[i] = m_tree->frame.mortonCode(m_precomputed[i].position);
  });
  std::vector<std::size_t> ends;
  octreeCells(codes, 0, count, 0, m_maxPhotonsPerPart, ends);
  m_precomputedTree = std::make_unique<Tree>(m_precomputed, ends, m_tree->frame);
}

Vec3 PhotonMap::precomputedIrradiance(const Vec3& x, const Vec3& n) const {
  if (!m_precomputedTree) return {};
  const float query[3] = {float(x.x), float(x.y), float(x.z)};
  std::vector<std::pair<float, std::uint32_t>> heap;
  FacingKnnResultSet result(1, m_precomputed.data(), *m_mesh, n, heap);
  m_precomputedTree->search(result, query);
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
