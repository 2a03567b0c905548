// The links against a reference nobody's oracle took part in: for a sample of links, the power
// each delivers to its receiver per unit of its source's radiosity, against a Monte Carlo
// estimate of A_r F_rs = ∫_r ∫_s cosθ_r cosθ_s V / (π d²) over uniform point pairs whose
// visibility comes from rays. `radkit run --method hierarchical --check-links N` writes it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "geometry/visibility.h"
#include "hierarchy/gather.h"

namespace radkit {

struct LinkCheck {
  int receiver = -1, source = -1;
  LinkKind kind = LinkKind::ElementElement;
  double model = 0;           ///< power the link delivers per unit B_s (scene units²)
  double reference = 0;       ///< Monte Carlo A_r F_rs (scene units²)
  double referenceError = 0;  ///< its standard error
};

/// Per link kind: how the sampled links' power compares with the reference's.
struct LinkCheckSummary {
  LinkKind kind = LinkKind::ElementElement;
  int links = 0;
  double model = 0, reference = 0, referenceError = 0;  ///< sums over the kind's links
  double meanAbsoluteRelative = 0;  ///< mean |model − reference| / reference where reference > 0
};

/// \brief Checks `count` links drawn uniformly (seeded) from the system's links, each against
/// `samples` stratified point pairs. Deterministic for a seed; parallel over links.
std::vector<LinkCheck> checkLinks(const Hierarchy& h, const HierarchicalSystem& system,
                                  const Visibility& visibility, int count, std::uint64_t seed,
                                  int samples = 4096);

/// \brief The same for the given link indices.
std::vector<LinkCheck> checkLinksAt(const Hierarchy& h, const HierarchicalSystem& system,
                                    const Visibility& visibility, const std::vector<int>& chosen,
                                    std::uint64_t seed, int samples = 4096);

std::vector<LinkCheckSummary> summariseLinkChecks(const std::vector<LinkCheck>& checks);

}  // namespace radkit
