#include "hierarchy/gather.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>
#include <tbb/task_group.h>

namespace radkit {

namespace {

/// Blocks of the Gauss-Seidel ordering: subtrees this many cluster levels below the root.
constexpr int kBlockLevel = 6;
/// Push-pull spawns tasks above these levels (clusters, then elements below a face).
constexpr int kParallelClusterLevel = 12;
constexpr int kParallelElementLevel = 3;

Vec3 absDiff(const Vec3& a, const Vec3& b) {
  return {std::fabs(a.x - b.x), std::fabs(a.y - b.y), std::fabs(a.z - b.z)};
}

}  // namespace

HierarchicalSystem::HierarchicalSystem(const Hierarchy& h, std::vector<HLink> links,
                                       GatherOrder order, const std::vector<char>& closed,
                                       const std::vector<char>& hidden)
    : m_h(h), m_links(std::move(links)) {
  tbb::parallel_sort(m_links.begin(), m_links.end(), [](const HLink& a, const HLink& b) {
    return a.receiver < b.receiver || (a.receiver == b.receiver && a.source < b.source);
  });
  m_begin.assign(std::size_t(h.size()) + 1, 0);
  for (const HLink& l : m_links) ++m_begin[l.receiver + 1];
  for (int n = 0; n < h.size(); ++n) m_begin[n + 1] += m_begin[n];
  m_acc.assign(h.size(), Accumulator{});
  m_slotBegin.assign(std::size_t(h.size()) + 1, 0);
  std::vector<int> parts;
  for (int n = 0; n < h.size(); ++n) {
    m_slotBegin[n + 1] = m_slotBegin[n];
    if (h[n].element || linkCount(n) == 0) continue;
    coherentParts(h, n, parts);
    if (parts.size() == 1) continue;
    m_slotTarget.insert(m_slotTarget.end(), parts.begin(), parts.end());
    m_slotBegin[n + 1] += static_cast<int>(parts.size());
  }
  m_slots.assign(m_slotTarget.size(), Accumulator{});
  m_incomingBegin.assign(std::size_t(h.size()) + 1, 0);
  for (int q : m_slotTarget) ++m_incomingBegin[q + 1];
  for (int n = 0; n < h.size(); ++n) m_incomingBegin[n + 1] += m_incomingBegin[n];
  m_incoming.resize(m_slotTarget.size());
  {
    std::vector<int> fill(m_incomingBegin.begin(), m_incomingBegin.end() - 1);
    for (std::size_t k = 0; k < m_slotTarget.size(); ++k)
      m_incoming[fill[m_slotTarget[k]]++] = static_cast<int>(k);
  }
  m_leafIrradiance.assign(h.size(), Vec3{});
  m_fromParent.assign(h.size(), Vec3{});

  // Blocks in tree order; everything above them is gathered first in each sweep.
  const int blockLevel = order == GatherOrder::Jacobi ? 0 : kBlockLevel;
  std::vector<int> stack{h.root()};
  while (!stack.empty()) {
    int n = stack.back();
    stack.pop_back();
    if (h[n].element || h[n].level >= blockLevel) {
      m_blocks.push_back(n);
      continue;
    }
    m_aboveClusters.push_back(n);
    if (linkCount(n) > 0) m_aboveReceivers.push_back(n);
    stack.push_back(h.child(n, 1));
    stack.push_back(h.child(n, 0));
  }
  // Seen share of each node's area: hidden leaves count 0; parents after their children.
  m_visibleFraction.assign(h.size(), 1.0);
  {
    std::vector<double> seen(h.size(), 0.0);
    for (int n = h.size() - 1; n >= 0; --n) {
      if (h[n].isLeaf())
        seen[n] = n < static_cast<int>(hidden.size()) && hidden[n] ? 0.0 : h[n].area;
      if (n > 0 && h[n].parent >= 0) seen[h[n].parent] += seen[n];
      m_visibleFraction[n] = h[n].area > 0 ? std::min(1.0, seen[n] / h[n].area) : 1.0;
    }
  }
  // Row sums, once per set of links: the irradiance every leaf gets when everything has B = 1.
  m_rowScale.assign(h.size(), 1.0);
  std::vector<Vec3> rows = leafIrradiance(unitState());
  for (int n = 0; n < h.size(); ++n) {
    if (!h[n].isLeaf() || !h[n].element || !(rows[n].x > 0)) continue;
    m_largestRowSumError = std::max(m_largestRowSumError, std::fabs(rows[n].x - 1));
    if (n < static_cast<int>(closed.size()) && closed[n]) {
      m_rowScale[n] = 1 / rows[n].x, ++m_normalised;
      continue;
    }
    // Cap ρ·(row sum) at (1 + ρ)/2 < 1: every sweep then contracts, whatever the links.
    const double rho = h[n].reflectanceMax, cap = rho > 0 ? (1 + rho) / (2 * rho) : INFINITY;
    if (rows[n].x > cap) m_rowScale[n] = cap / rows[n].x, ++m_clamped;
  }
  m_blockReceivers.resize(m_blocks.size());
  for (std::size_t b = 0; b < m_blocks.size(); ++b) {
    stack.assign(1, m_blocks[b]);
    while (!stack.empty()) {
      int n = stack.back();
      stack.pop_back();
      if (linkCount(n) > 0) m_blockReceivers[b].push_back(n);
      for (int k = h[n].childCount - 1; k >= 0; --k) stack.push_back(h.child(n, k));
    }
  }
}

void HierarchicalSystem::gather(int r, const SourceState& state) {
  const HNode& R = m_h[r];
  Accumulator acc;
  const int slot0 = m_slotBegin[r], slots = m_slotBegin[r + 1] - slot0;
  for (int k = 0; k < slots; ++k) m_slots[slot0 + k] = Accumulator{};
  const bool quarters = R.element && R.childCount == 4;
  Vec3 toQuarter[4];
  for (int i = m_begin[r]; i < m_begin[r + 1]; ++i) {
    const HLink& l = m_links[i];
    // A source nothing sees sends nothing (its rays' noise may still give a link V > 0).
    if (!state.visibleArea.empty() && !(state.visibleArea[l.source] > 0)) continue;
    if (R.element && m_h[l.source].element) {
      Vec3 e = linkSourceRadiosity(m_h, state.radiosity, l) * (l.formFactor * l.visibility);
      if (quarters && l.receiverShare[0] >= 0) {
        for (int k = 0; k < 4; ++k) toQuarter[k] += e * double(l.receiverShare[k]);
      } else {
        acc.sum += e;
      }
      continue;
    }
    // Transfer between the centres: irradiance e = I_s(−ω) V / (d² + P_s/π) on a surface
    // facing the source, ω the unit direction from r to s.
    const ClusterTransfer t = clusterTransfer(m_h, r, l.source);
    const Vec3& w = t.w;
    Vec3 e = intensityToward(m_h, state, l.source, -w) * (l.visibility / t.denominator);
    auto add = [&](Accumulator& a, int node) {
      if (m_h[node].element) {
        a.sum += e * std::max(0.0, dot(m_h.polygon(node).normal, w));
      } else {
        a.vec[0] += w * e.x, a.vec[1] += w * e.y, a.vec[2] += w * e.z;
      }
    };
    if (slots == 0) {
      add(acc, r);
    } else {
      for (int k = 0; k < slots; ++k) add(m_slots[slot0 + k], m_slotTarget[slot0 + k]);
    }
  }
  m_acc[r] = acc;
  if (quarters)
    for (int k = 0; k < 4; ++k) m_fromParent[R.firstChild + k] = toQuarter[k];
}

HierarchicalSystem::Accumulator HierarchicalSystem::gathered(int n) const {
  Accumulator a = m_acc[n];
  for (int k = m_incomingBegin[n]; k < m_incomingBegin[n + 1]; ++k) a.add(m_slots[m_incoming[k]]);
  return a;
}

void HierarchicalSystem::gatherList(const std::vector<int>& receivers, const SourceState& state) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, receivers.size(), 256),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i < range.end(); ++i)
                        gather(receivers[i], state);
                    });
}

void pullNode(const Hierarchy& h, int n, SourceState& state) {
  const HNode& node = h[n];
  if (node.isLeaf()) {
    state.radiosityMin[n] = state.radiosityMax[n] = maxComponent(state.radiosity[n]);
    return;
  }
  Vec3 power;
  std::array<Vec3, 3> vec{};
  double lo = INFINITY, hi = -INFINITY, seen = 0;
  const bool hidden = !state.visibleArea.empty();
  for (int k = 0; k < node.childCount; ++k) {
    int c = h.child(n, k);
    const HNode& child = h[c];
    const double a = hidden ? state.visibleArea[c] : child.area;
    Vec3 w = state.radiosity[c] * a;
    power += w;
    seen += a;
    if (a > 0) lo = std::min(lo, state.radiosityMin[c]), hi = std::max(hi, state.radiosityMax[c]);
    if (node.element) continue;
    if (child.element) {
      const Vec3& nrm = h.polygon(c).normal;
      vec[0] += nrm * w.x, vec[1] += nrm * w.y, vec[2] += nrm * w.z;
    } else {
      for (int ch = 0; ch < 3; ++ch) vec[ch] += state.powerVector[c][ch];
    }
  }
  state.radiosity[n] = seen > 0 ? power / seen : Vec3{};
  if (!(lo <= hi)) lo = hi = 0;  // nothing below is seen
  state.radiosityMin[n] = lo, state.radiosityMax[n] = hi;
  if (hidden) state.visibleArea[n] = seen;
  if (!node.element) state.powerVector[n] = vec;
}

void pull(const Hierarchy& h, SourceState& state) {
  // Children have larger numbers than their parents (clusters in preorder, split elements
  // appended), so a reverse walk pulls every child before its parent.
  for (int n = h.size() - 1; n >= 0; --n) pullNode(h, n, state);
}

HierarchicalSystem::Change HierarchicalSystem::pushPull(int n, const Accumulator& inherited,
                                                        SourceState* state) {
  const HNode& node = m_h[n];
  Change change;
  auto recurse = [&](const Accumulator& down, bool parallel) {
    if (parallel) {
      std::vector<Change> changes(node.childCount);
      tbb::task_group tasks;
      for (int k = 0; k < node.childCount; ++k)
        tasks.run([&, k] { changes[k] = pushPull(m_h.child(n, k), down, state); });
      tasks.wait();
      for (const Change& c : changes) change.add(c);
    } else {
      for (int k = 0; k < node.childCount; ++k) change.add(pushPull(m_h.child(n, k), down, state));
    }
  };
  if (!node.element) {
    Accumulator down = inherited;
    down.add(gathered(n));
    recurse(down, node.level < kParallelClusterLevel);
  } else {
    // An input face turns its ancestors' irradiance vector into what its normal sees: exact
    // while the light comes from in front of the face, which the clusters' coherent parts
    // (normals within a narrow cone, each gathering its own links) make the rule.
    // Irradiance travels down per unit of seen area: the links' rays found the hidden part of
    // a node blocked, so what they bring falls on the rest (a floor element half under a block
    // gives its light to the uncovered half, not to leaves that nothing sees).
    const double seen = m_visibleFraction[n];
    Vec3 h = inherited.sum;  // per unit of seen area
    if (node.level == 0) {
      const Vec3& nrm = m_h.polygon(n).normal;
      h = {std::max(0.0, dot(nrm, inherited.vec[0])), std::max(0.0, dot(nrm, inherited.vec[1])),
           std::max(0.0, dot(nrm, inherited.vec[2]))};
      h = seen > 0 ? h / seen : Vec3{};
    }
    if (seen > 0) h += (gathered(n).sum + m_fromParent[n]) / seen;
    if (node.isLeaf()) {
      h *= seen * m_rowScale[n];
      m_leafIrradiance[n] = h;
      if (!state) return change;
      const SurfaceRadiometry& rad = m_h.radiometry(n);
      Vec3 b = rad.emission + mul(rad.reflectance, h);
      Vec3 diff = absDiff(b, state->radiosity[n]);
      state->radiosity[n] = b;
      state->radiosityMin[n] = state->radiosityMax[n] = maxComponent(b);
      return {maxComponent(diff), node.area * (diff.x + diff.y + diff.z)};
    }
    Accumulator down;
    down.sum = h;
    recurse(down, node.level < kParallelElementLevel);
  }
  if (state) pullNode(m_h, n, *state);
  return change;
}

HierarchicalSystem::Change HierarchicalSystem::sweep(SourceState& state) {
  gatherList(m_aboveReceivers, state);
  // What the clusters above each block gathered, summed down to the block's root.
  std::vector<Accumulator> blockInherited(m_blocks.size());
  {
    std::vector<std::pair<int, Accumulator>> stack{{m_h.root(), Accumulator{}}};
    std::size_t b = 0;
    while (!stack.empty()) {
      auto [n, acc] = stack.back();
      stack.pop_back();
      if (b < m_blocks.size() && n == m_blocks[b]) {
        blockInherited[b++] = acc;
        continue;
      }
      acc.add(gathered(n));
      stack.push_back({m_h.child(n, 1), acc});
      stack.push_back({m_h.child(n, 0), acc});
    }
  }
  Change change;
  for (std::size_t b = 0; b < m_blocks.size(); ++b) {
    gatherList(m_blockReceivers[b], state);
    change.add(pushPull(m_blocks[b], blockInherited[b], &state));
  }
  for (auto it = m_aboveClusters.rbegin(); it != m_aboveClusters.rend(); ++it)
    pullNode(m_h, *it, state);
  return change;
}

std::vector<Vec3> HierarchicalSystem::leafIrradiance(const SourceState& state) {
  std::vector<int> all;
  for (int n = 0; n < m_h.size(); ++n)
    if (linkCount(n) > 0) all.push_back(n);
  gatherList(all, state);
  pushPull(m_h.root(), Accumulator{}, nullptr);
  return m_leafIrradiance;
}

void HierarchicalSystem::setVisibleArea(SourceState& state) const {
  state.visibleArea.resize(m_h.size());
  for (int n = 0; n < m_h.size(); ++n) state.visibleArea[n] = m_visibleFraction[n] * m_h[n].area;
}

SourceState HierarchicalSystem::unitState() const {
  SourceState s;
  s.radiosity.assign(m_h.size(), Vec3{1, 1, 1});
  s.radiosityMin.assign(m_h.size(), 1.0);
  s.radiosityMax.assign(m_h.size(), 1.0);
  s.powerVector.resize(m_h.size());
  setVisibleArea(s);
  pull(m_h, s);  // power vectors over the seen area, as the solve's pull makes them
  return s;
}

}  // namespace radkit
