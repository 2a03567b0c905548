#include "hierarchy/gather.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <type_traits>

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

/// Nodes split, per end of a cluster link, while resolving it into facing nodes; past this the
/// straddling nodes left are estimated (projectedSum). Links that carry much are refined by the
/// oracle long before a node this large straddles them.
constexpr int kMaxExpansions = 256;
/// A closed leaf's row sum is divided out only within these bounds (see the constructor).
constexpr double kNormaliseLow = 0.8, kNormaliseHigh = 1.25;
/// Bounds on a landing's distance correction: overlapping nodes are the oracle's to refine.
constexpr double kMinLandingScale = 0.25, kMaxLandingScale = 4.0;
/// Receivers whose cluster links are resolved into landings at once.
constexpr std::size_t kLandingChunk = 1 << 16;
/// Reflectance from which the row-sum fill ramps in, and at which it is whole.
constexpr double kFillFrom = 0.75, kFillFull = 0.9;
/// Slack on "every normal within 90° of ω" (radians): rounding, not geometry.
constexpr double kFacingSlack = 1e-9;

/// The nodes below n that face unit direction w as a whole, down to input faces: (node, n·w)
/// for elements, (node, -1) for clusters whose whole normal cone faces w, (node, -2) for
/// clusters left straddling after kMaxExpansions splits. Nodes facing away are left out.
void facingNodes(const Hierarchy& h, int n, const Vec3& w, std::vector<std::pair<int, float>>& out,
                 long long& approximate) {
  out.clear();
  std::vector<int> queue{n};
  int expansions = 0;
  for (std::size_t i = 0; i < queue.size(); ++i) {
    const int k = queue[i];
    const HNode& node = h[k];
    if (node.element) {
      const double c = dot(h.normal(k), w);
      if (c > 0) out.push_back({k, float(c)});
      continue;
    }
    const double phi = angleBetween(node.coneAxis, w);
    if (phi + node.coneAngle <= 0.5 * kPi - kFacingSlack) {
      out.push_back({k, -1.0f});
    } else if (phi - node.coneAngle >= 0.5 * kPi) {
      continue;  // every face below looks away
    } else if (expansions < kMaxExpansions) {
      ++expansions;
      queue.push_back(h.child(k, 0));
      queue.push_back(h.child(k, 1));
    } else {
      out.push_back({k, -2.0f});
      ++approximate;
    }
  }
}

}  // namespace

HierarchicalSystem::HierarchicalSystem(const Hierarchy& h, std::vector<HLink> links,
                                       GatherOrder order, SourceState& scratch,
                                       const std::vector<float>& rowTarget,
                                       const std::vector<char>& hidden)
    : m_h(h), m_links(std::move(links)) {
  m_links.shrink_to_fit();  // refinement grew it by doubling
  tbb::parallel_sort(m_links.begin(), m_links.end(), [](const HLink& a, const HLink& b) {
    return a.receiver < b.receiver || (a.receiver == b.receiver && a.source < b.source);
  });
  m_begin.assign(std::size_t(h.size()) + 1, 0);
  for (const HLink& l : m_links) ++m_begin[l.receiver + 1];
  for (int n = 0; n < h.size(); ++n) m_begin[n + 1] += m_begin[n];
  m_gathered.assign(h.size(), Vec3{});
  m_hidden = hidden;
  buildLandings();
  m_firstSplit = h.firstSplitNode();
  m_fromParent.assign(std::size_t(h.size() - m_firstSplit), Vec3{});

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
  m_rowSum.assign(h.size(), 0.0);
  m_fillSurfaces = static_cast<int>(h.base().surfaceBegin.size()) - 1;
  m_meanIncoming.assign(m_fillSurfaces, Vec3{});
  // Each leaf's raw row sum is written straight into m_rowSum (all channels agree with B = 1).
  // B = 1 on the leaves, pulled up: the same state unitState() makes.
  m_rowPass = true;
  {
    std::vector<Vec3> kept;
    for (int n = 0; n < h.size(); ++n)
      if (h[n].isLeaf()) kept.push_back(scratch.radiosity[n]), scratch.radiosity[n] = {1, 1, 1};
    setVisibleArea(scratch);
    pull(h, scratch);
    leafIrradiance(scratch);
    std::size_t k = 0;
    for (int n = 0; n < h.size(); ++n)
      if (h[n].isLeaf()) scratch.radiosity[n] = kept[k++];
  }
  m_rowPass = false;
  m_deficit.assign(h.size(), 0.0);
  for (int n = 0; n < h.size(); ++n) {
    const double row = m_rowSum[n];
    if (!h[n].isLeaf() || !h[n].element || !(row > 0)) {
      m_rowSum[n] = 0;
      continue;
    }
    m_largestRowSumError = std::max(m_largestRowSumError, std::fabs(row - 1));
    const double target = n < static_cast<int>(rowTarget.size()) ? rowTarget[n] : 0.0;
    if (target > 0) {
      // The leaf's links add up to row instead of target: the share they miss (or count
      // twice) is filled with the light its surface receives on average per unit of row sum.
      // Dividing each leaf's irradiance by its own row sum instead was biased: rows are noisy
      // (±15 % per leaf on the Cornell box) and E[1/row] > 1/E[row] brought 1-2 % too much
      // light. Filling is linear in the noise, and exact wherever the light is uniform (a
      // furnace). A row sum far from its target means links that are wrong: cap it instead.
      // The fill's light is a mean, while what the links miss is mostly dim light from nearby
      // clusters: on real models in a room (ρ 0.7) it put 1-4 % too much light on the model,
      // against −2.5 … +1.6 % for the links alone. A row sum's error is amplified about
      // ρ/(1 − ρ) times in B, so the fill pays where ρ is high (it keeps a furnace at ρ = 0.95
      // exact): it ramps in from ρ = kFillFrom to full at kFillFull.
      const double ratio = row / target;
      const double weight =
          std::clamp((h[n].reflectanceMax - kFillFrom) / (kFillFull - kFillFrom), 0.0, 1.0);
      if (weight > 0 && ratio >= kNormaliseLow && ratio <= kNormaliseHigh) {
        m_deficit[n] = weight * (target - row);
        m_rowSum[n] = row + m_deficit[n], ++m_normalised;
        continue;
      }
      if (weight > 0) ++m_unnormalised;
    }
    // Cap ρ·(row sum) at (1 + ρ)/2 < 1: every sweep then contracts, whatever the links.
    const double rho = h[n].reflectanceMax, cap = rho > 0 ? (1 + rho) / (2 * rho) : INFINITY;
    if (row > cap) m_rowScale[n] = cap / row, m_rowSum[n] = cap, ++m_clamped;
  }
  // Without a leaf to fill, the fill's per-leaf arrays are not kept.
  if (std::all_of(m_deficit.begin(), m_deficit.end(), [](double d) { return d == 0; }))
    std::vector<double>().swap(m_deficit);
  else
    m_leafRaw.assign(h.size(), Vec3{});
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

void HierarchicalSystem::resolveLink(int i, const ClusterTransfer& t,
                                     std::vector<std::pair<int, float>>& found,
                                     std::vector<SourceLanding>* sources,
                                     std::vector<ReceiverLanding>& receivers,
                                     long long& approximate) const {
  const Hierarchy& h = m_h;
  const HLink& l = m_links[i];
  const int r = l.receiver;
  auto scale = [&](const Vec3& a, const Vec3& b, double soft) {
    const Vec3 d = a - b;
    return float(
        std::clamp(t.denominator / (dot(d, d) + soft), kMinLandingScale, kMaxLandingScale));
  };
  if (sources) {
    facingNodes(h, l.source, -t.w, found, approximate);
    for (auto [node, c] : found)
      sources->push_back({node, c < 0 ? (c < -1.5f ? kApproximate : kVector) : c,
                          scale(h[node].centre, h[r].centre, projectedArea(h, node, -t.w) / kPi)});
  }
  facingNodes(h, r, t.w, found, approximate);
  const Vec3 between = h[l.source].centre - h[r].centre;
  const double soft = t.denominator - dot(between, between);  // P_s/π
  for (auto [node, c] : found) {
    // A hidden leaf receives nothing (nothing sees it).
    if (node < static_cast<int>(m_hidden.size()) && m_hidden[node] && h[node].isLeaf()) continue;
    float factor = c;
    if (c < -1.5f)
      factor = float(projectedArea(h, node, t.w) / h[node].area);
    else if (c < 0)
      factor = kVector;
    receivers.push_back({node, factor, scale(h[node].centre, h[l.source].centre, soft)});
  }
}

void HierarchicalSystem::buildLandings() {
  const Hierarchy& h = m_h;
  const std::size_t L = m_links.size();
  m_linkDirection.assign(L, Vec3{});
  m_linkGeometry.assign(L, 0.0);
  // Receivers in chunks, each resolved in parallel and appended in receiver order
  // (deterministic); a chunk's per-receiver parts are all that exists twice, where parts for
  // every receiver at once held about twice the landings (400 MiB at a million faces).
  struct Part {
    std::vector<SourceLanding> sources;
    std::vector<ReceiverLanding> receivers;
    std::vector<int> sourceCount, receiverCount;  // per link of this receiver
    long long approximate = 0;
  };
  std::vector<int> receivers;
  for (int n = 0; n < h.size(); ++n)
    if (linkCount(n) > 0) receivers.push_back(n);
  m_sourceBegin.assign(L + 1, 0);
  std::vector<int> receiverBegin(L + 1, 0);
  std::vector<ReceiverLanding> byLink;  // every receiver end, in link order
  std::size_t li = 0;
  for (std::size_t first = 0; first < receivers.size(); first += kLandingChunk) {
    const std::size_t end = std::min(receivers.size(), first + kLandingChunk);
    std::vector<Part> parts(end - first);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(first, end, 16),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        std::vector<std::pair<int, float>> found;
                        for (std::size_t i = range.begin(); i < range.end(); ++i) {
                          const int r = receivers[i];
                          Part& part = parts[i - first];
                          for (int k = m_begin[r]; k < m_begin[r + 1]; ++k) {
                            const HLink& l = m_links[k];
                            if (h[r].element && h[l.source].element) {
                              part.sourceCount.push_back(0), part.receiverCount.push_back(0);
                              continue;
                            }
                            const ClusterTransfer t = clusterTransfer(h, r, l.source);
                            m_linkDirection[k] = t.w;
                            m_linkGeometry[k] = double(l.visibility) / (kPi * t.denominator);
                            const std::size_t s0 = part.sources.size();
                            const std::size_t r0 = part.receivers.size();
                            resolveLink(k, t, found, &part.sources, part.receivers,
                                        part.approximate);
                            part.sourceCount.push_back(int(part.sources.size() - s0));
                            part.receiverCount.push_back(int(part.receivers.size() - r0));
                          }
                        }
                      });
    std::size_t sources = 0, landings = 0;
    for (const Part& part : parts)
      sources += part.sources.size(), landings += part.receivers.size();
    reserveFor(m_sourceLandings, m_sourceLandings.size() + sources);
    reserveFor(byLink, byLink.size() + landings);
    for (Part& part : parts) {
      m_approximateLandings += part.approximate;
      m_sourceLandings.insert(m_sourceLandings.end(), part.sources.begin(), part.sources.end());
      byLink.insert(byLink.end(), part.receivers.begin(), part.receivers.end());
      for (std::size_t k = 0; k < part.sourceCount.size(); ++k, ++li) {
        m_sourceBegin[li + 1] = m_sourceBegin[li] + part.sourceCount[k];
        receiverBegin[li + 1] = receiverBegin[li] + part.receiverCount[k];
      }
      part = Part{};  // copied: its memory goes now
    }
  }
  // By target node, in link order within each (a stable counting sort): a node's gathered
  // light is summed from them when it is pushed down, so no accumulator per (receiver, node)
  // slot is kept (96 bytes each, millions of slots at a million faces).
  m_incomingBegin.assign(std::size_t(h.size()) + 1, 0);
  for (const ReceiverLanding& t : byLink) ++m_incomingBegin[t.node + 1];
  for (int n = 0; n < h.size(); ++n) m_incomingBegin[n + 1] += m_incomingBegin[n];
  m_incoming.resize(byLink.size());
  {
    std::vector<int> at(m_incomingBegin.begin(), m_incomingBegin.end() - 1);
    std::vector<int> lastFrom(h.size(), -1);  // receiver of each node's last landing so far
    for (std::size_t link = 0; link < L; ++link) {
      const int from = m_links[link].receiver;
      for (int k = receiverBegin[link]; k < receiverBegin[link + 1]; ++k) {
        const ReceiverLanding& t = byLink[k];
        const bool first = lastFrom[t.node] != from;
        lastFrom[t.node] = from;
        const int index = static_cast<int>(link);
        m_incoming[at[t.node]++] = {first ? -index - 1 : index, t.factor, t.scale};
      }
    }
  }
  m_linkIrradiance.assign(L, Vec3{});
  m_landingCount =
      static_cast<long long>(m_sourceLandings.size()) + static_cast<long long>(m_incoming.size());
}

void HierarchicalSystem::releaseGatherArrays() {
  auto release = [](auto& v) { std::remove_reference_t<decltype(v)>().swap(v); };
  release(m_gathered), release(m_linkDirection), release(m_linkGeometry);
  release(m_sourceBegin), release(m_sourceLandings), release(m_incomingBegin);
  release(m_incoming), release(m_hidden), release(m_linkIrradiance), release(m_leafIrradiance);
  release(m_fromParent), release(m_visibleFraction), release(m_rowScale), release(m_deficit);
  release(m_rowSum), release(m_leafRaw), release(m_meanIncoming), release(m_blockReceivers);
  m_released = true;
}

void HierarchicalSystem::gather(int r, const SourceState& state) {
  const HNode& R = m_h[r];
  Vec3 sum;
  const bool quarters = R.element && R.childCount == 4;
  const bool seenOnly = !state.visibleArea.empty();
  Vec3 toQuarter[4];
  for (int i = m_begin[r]; i < m_begin[r + 1]; ++i) {
    const HLink& l = m_links[i];
    // A source nothing sees sends nothing (its rays' noise may still give a link V > 0).
    if (seenOnly && !(state.visibleArea[l.source] > 0)) {
      m_linkIrradiance[i] = Vec3{};
      continue;
    }
    if (R.element && m_h[l.source].element) {
      Vec3 e = linkSourceRadiosity(m_h, state.radiosity, l) * (l.formFactor * l.visibility);
      if (quarters && l.receiverShare[0] >= 0) {
        for (int k = 0; k < 4; ++k) toQuarter[k] += e * double(l.receiverShare[k]);
      } else {
        sum += e;
      }
      continue;
    }
    // Irradiance e = I_s(−ω) V / (d² + P_s/π) on a surface facing the source; its landings
    // take it when they are pushed down (gathered()).
    m_linkIrradiance[i] = sourceIntensity(i, state) * m_linkGeometry[i];
  }
  m_gathered[r] = sum;
  if (quarters)
    for (int k = 0; k < 4; ++k) m_fromParent[R.firstChild + k - m_firstSplit] = toQuarter[k];
}

void HierarchicalSystem::updateMeanIncoming() {
  // Per surface, over its leaves with a row-sum target: Σ A H / Σ A row, from this sweep's
  // links alone (the next sweep fills with it: at convergence the two agree).
  if (m_deficit.empty()) return;  // no leaf is filled
  std::vector<Vec3> light(m_fillSurfaces);
  std::vector<double> rows(m_fillSurfaces, 0.0);
  for (int n = 0; n < m_h.size(); ++n) {
    if (m_deficit.empty() || !m_h[n].isLeaf() || !m_h[n].element || m_rowSum[n] <= 0) continue;
    if (m_deficit[n] == 0 && m_rowScale[n] != 1) continue;  // capped: not a fill leaf
    const int s = m_h.surfaceOf(n);
    light[s] += m_leafRaw[n] * m_h[n].area;
    rows[s] += (m_rowSum[n] - m_deficit[n]) * m_h[n].area;
  }
  for (int s = 0; s < m_fillSurfaces; ++s)
    m_meanIncoming[s] = rows[s] > 0 ? light[s] / rows[s] : Vec3{};
}

Vec3 HierarchicalSystem::sourceIntensity(int i, const SourceState& state) const {
  // π I_s(−ω) summed over the parts of s that face r, each at its own distance (scale).
  const Vec3& w = m_linkDirection[i];
  Vec3 intensity;
  for (int k = m_sourceBegin[i]; k < m_sourceBegin[i + 1]; ++k) {
    const SourceLanding& s = m_sourceLandings[k];
    const double seen = state.visibleArea.empty() ? m_h[s.node].area : state.visibleArea[s.node];
    Vec3 part;
    if (s.cosine >= 0) {
      part = state.radiosity[s.node] * (seen * double(s.cosine));
    } else if (s.cosine == kVector) {
      const auto& phi = state.powerVector[m_h[s.node].cluster];
      part = Vec3{-dot(phi[0], w), -dot(phi[1], w), -dot(phi[2], w)};
    } else {
      const auto& phi = state.powerVector[m_h[s.node].cluster];
      const Vec3 power = state.radiosity[s.node] * seen;
      for (int c = 0; c < 3; ++c) part[c] = projectedSum(power[c], phi[c], -w);
    }
    intensity += part * double(s.scale);
  }
  return intensity;
}

double HierarchicalSystem::linkPower(int i, const SourceState& unit) const {
  if (m_released) throw std::logic_error("HierarchicalSystem: its gather arrays were released");
  const HLink& l = m_links[i];
  const HNode& R = m_h[l.receiver];
  if (R.element && m_h[l.source].element) return R.area * l.formFactor * double(l.visibility);
  const Vec3& w = m_linkDirection[i];
  const double intensity = sourceIntensity(i, unit).x;
  // What the faces below each landing take: A n·ω e in all (push-down keeps it over seen area).
  // The receiver end resolved again (the system keeps it by target node, not by link).
  std::vector<std::pair<int, float>> found;
  std::vector<ReceiverLanding> landings;
  long long approximate = 0;
  resolveLink(i, clusterTransfer(m_h, l.receiver, l.source), found, nullptr, landings, approximate);
  double projected = 0;
  for (const ReceiverLanding& t : landings) {
    const HNode& node = m_h[t.node];
    projected += (t.factor == kVector ? dot(node.areaNormal, w) : node.area * double(t.factor)) *
                 double(t.scale);
  }
  return intensity * m_linkGeometry[i] * projected;
}

HierarchicalSystem::Accumulator HierarchicalSystem::gathered(int n) const {
  Accumulator a;
  a.sum = m_gathered[n];
  // One slot at a time: what one receiver's links bring to n, summed as one accumulator first
  // (the order the sums have always been taken in).
  Accumulator s;
  for (int k = m_incomingBegin[n]; k < m_incomingBegin[n + 1]; ++k) {
    const IncomingLanding& t = m_incoming[k];
    int link = t.link;
    if (link < 0) {  // the first landing of a slot
      if (k > m_incomingBegin[n]) a.add(s);
      s = Accumulator{};
      link = -link - 1;
    }
    const Vec3 el = m_linkIrradiance[link] * double(t.scale);
    if (t.factor == kVector) {
      const Vec3& w = m_linkDirection[link];
      s.vec[0] += w * el.x, s.vec[1] += w * el.y, s.vec[2] += w * el.z;
    } else {
      s.sum += el * double(t.factor);
    }
  }
  if (m_incomingBegin[n + 1] > m_incomingBegin[n]) a.add(s);
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
      const Vec3& nrm = h.normal(c);
      vec[0] += nrm * w.x, vec[1] += nrm * w.y, vec[2] += nrm * w.z;
    } else {
      for (int ch = 0; ch < 3; ++ch) vec[ch] += state.powerVector[child.cluster][ch];
    }
  }
  state.radiosity[n] = seen > 0 ? power / seen : Vec3{};
  if (!(lo <= hi)) lo = hi = 0;  // nothing below is seen
  state.radiosityMin[n] = lo, state.radiosityMax[n] = hi;
  if (hidden) state.visibleArea[n] = seen;
  if (!node.element) state.powerVector[node.cluster] = vec;
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
    // An input face turns its ancestors' irradiance vector into what its normal sees: exact,
    // since only sources that every face below a landing node faces are kept as vectors.
    // Irradiance travels down per unit of seen area: the links' rays found the hidden part of
    // a node blocked, so what they bring falls on the rest (a floor element half under a block
    // gives its light to the uncovered half, not to leaves that nothing sees).
    const double seen = m_visibleFraction[n];
    Vec3 h = inherited.sum;  // per unit of seen area
    if (node.level == 0) {
      // Every vector term came from a source this face's cone faces: n·(e ω) >= 0 each.
      const Vec3& nrm = m_h.normal(n);
      h = Vec3{std::max(0.0, dot(nrm, inherited.vec[0])), std::max(0.0, dot(nrm, inherited.vec[1])),
               std::max(0.0, dot(nrm, inherited.vec[2]))} +
          inherited.sum;
      h = seen > 0 ? h / seen : Vec3{};
    }
    if (seen > 0)
      h += (gathered(n).sum + (n >= m_firstSplit ? m_fromParent[n - m_firstSplit] : Vec3{})) / seen;
    if (node.isLeaf()) {
      h *= seen;
      if (!m_leafRaw.empty()) m_leafRaw[n] = h;
      if (!m_deficit.empty() && m_deficit[n] != 0) {
        const Vec3 fill = m_meanIncoming[m_h.surfaceOf(n)] * m_deficit[n];
        h = {std::max(0.0, h.x + fill.x), std::max(0.0, h.y + fill.y), std::max(0.0, h.z + fill.z)};
      } else {
        h *= m_rowScale[n];
      }
      if (!state) {
        if (m_rowPass)
          m_rowSum[n] = h.x;
        else
          m_leafIrradiance[n] = h;
        return change;
      }
      const SurfaceRadiometry& rad = m_h.radiometry(n);
      Vec3 b = (m_emission ? (*m_emission)[n] : rad.emission) + mul(rad.reflectance, h);
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
  if (m_released) throw std::logic_error("HierarchicalSystem: its gather arrays were released");
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
  updateMeanIncoming();
  return change;
}

std::vector<Vec3> HierarchicalSystem::leafIrradiance(const SourceState& state) {
  if (m_released) throw std::logic_error("HierarchicalSystem: its gather arrays were released");
  std::vector<int> all;
  for (int n = 0; n < m_h.size(); ++n)
    if (linkCount(n) > 0) all.push_back(n);
  gatherList(all, state);
  if (!m_rowPass) m_leafIrradiance.assign(m_h.size(), Vec3{});
  pushPull(m_h.root(), Accumulator{}, nullptr);
  return std::move(m_leafIrradiance);
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
  s.powerVector.resize(m_h.clusterCount());
  setVisibleArea(s);
  pull(m_h, s);  // power vectors over the seen area, as the solve's pull makes them
  return s;
}

namespace {
template <class T>
std::size_t capacityBytes(const std::vector<T>& v) {
  return v.capacity() * sizeof(T);
}
}  // namespace

std::size_t HierarchicalSystem::bytes() const {
  std::size_t b = capacityBytes(m_links) + capacityBytes(m_begin) + capacityBytes(m_gathered) +
                  capacityBytes(m_linkDirection) + capacityBytes(m_linkGeometry) +
                  capacityBytes(m_sourceBegin) + capacityBytes(m_sourceLandings) +
                  capacityBytes(m_incomingBegin) + capacityBytes(m_incoming) +
                  capacityBytes(m_hidden) + capacityBytes(m_linkIrradiance) +
                  capacityBytes(m_leafIrradiance) + capacityBytes(m_fromParent) +
                  capacityBytes(m_visibleFraction) + capacityBytes(m_rowScale) +
                  capacityBytes(m_deficit) + capacityBytes(m_rowSum) + capacityBytes(m_leafRaw) +
                  capacityBytes(m_meanIncoming) + capacityBytes(m_blocks) +
                  capacityBytes(m_aboveReceivers) + capacityBytes(m_aboveClusters);
  for (const std::vector<int>& v : m_blockReceivers) b += capacityBytes(v);
  return b;
}

}  // namespace radkit
