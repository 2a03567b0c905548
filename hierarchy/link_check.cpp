#include "hierarchy/link_check.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "util/sampling.h"

namespace radkit {

std::vector<LinkCheck> checkLinks(const Hierarchy& h, const HierarchicalSystem& system,
                                  const Visibility& visibility, int count, std::uint64_t seed,
                                  int samples) {
  const std::vector<HLink>& links = system.links();
  std::vector<LinkCheck> out;
  if (links.empty() || count <= 0) return out;
  Rng pick(seed, 0x6c696e6b73ULL, 0);
  std::vector<int> chosen;
  for (int k = 0; k < count; ++k)
    chosen.push_back(static_cast<int>(pick.uniform() * double(links.size())));
  std::sort(chosen.begin(), chosen.end());
  chosen.erase(std::unique(chosen.begin(), chosen.end()), chosen.end());
  return checkLinksAt(h, system, visibility, chosen, seed, samples);
}

std::vector<LinkCheck> checkLinksAt(const Hierarchy& h, const HierarchicalSystem& system,
                                    const Visibility& visibility, const std::vector<int>& chosen,
                                    std::uint64_t seed, int samples) {
  const std::vector<HLink>& links = system.links();
  std::vector<LinkCheck> out;
  const SourceState unit = system.unitState();
  out.resize(chosen.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chosen.size(), 4),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      std::vector<double> u;
                      std::vector<int> scratch;
                      for (std::size_t i = range.begin(); i < range.end(); ++i) {
                        const HLink& l = links[chosen[i]];
                        LinkCheck& c = out[i];
                        c.receiver = l.receiver, c.source = l.source;
                        c.kind = linkKind(h, l);
                        c.model = system.linkPower(chosen[i], unit);
                        Rng rng(seed, h.key(l.receiver), h.key(l.source));
                        latinHypercube(samples, 6, rng, u, scratch);
                        double sum = 0, sum2 = 0;
                        for (int k = 0; k < samples; ++k) {
                          const double* q = &u[std::size_t(k) * 6];
                          Vec3 nx, ny;
                          const Vec3 x = h.samplePoint(l.receiver, q[0], q[1], q[2], nx);
                          const Vec3 y = h.samplePoint(l.source, q[3], q[4], q[5], ny);
                          const Vec3 d = y - x;
                          const double d2 = dot(d, d);
                          double f = 0;
                          if (d2 > 0) {
                            const double cr = dot(nx, d), cs = -dot(ny, d);
                            if (cr > 0 && cs > 0 && !visibility.occluded(x, nx, y, ny))
                              f = cr * cs / (kPi * d2 * d2);
                          }
                          sum += f, sum2 += f * f;
                        }
                        const double areas = h[l.receiver].area * h[l.source].area;
                        const double mean = sum / samples;
                        const double var = std::max(0.0, sum2 / samples - mean * mean);
                        c.reference = areas * mean;
                        c.referenceError = areas * std::sqrt(var / std::max(1, samples - 1));
                      }
                    });
  return out;
}

std::vector<LinkCheckSummary> summariseLinkChecks(const std::vector<LinkCheck>& checks) {
  std::vector<LinkCheckSummary> out(4);
  std::vector<int> relative(4, 0);
  for (int k = 0; k < 4; ++k) out[k].kind = static_cast<LinkKind>(k);
  std::vector<double> variance(4, 0.0);
  for (const LinkCheck& c : checks) {
    LinkCheckSummary& s = out[static_cast<int>(c.kind)];
    ++s.links;
    s.model += c.model, s.reference += c.reference;
    variance[static_cast<int>(c.kind)] += c.referenceError * c.referenceError;
    if (c.reference > 0) {
      s.meanAbsoluteRelative += std::fabs(c.model - c.reference) / c.reference;
      ++relative[static_cast<int>(c.kind)];
    }
  }
  for (int k = 0; k < 4; ++k) {
    out[k].referenceError = std::sqrt(variance[k]);
    if (relative[k] > 0) out[k].meanAbsoluteRelative /= relative[k];
  }
  return out;
}

}  // namespace radkit
