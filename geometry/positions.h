// Vertices at one position, found in linear time. Internal to geometry/.
#pragma once

#include <cstdint>
#include <cstring>
#include <vector>

#include "util/vec3.h"

namespace radkit {

/// How many vertices lie at the position of an earlier one (positions compare with ==, so -0
/// and +0 are one; NaN is never equal). Open addressing over 4-byte slots: 8 bytes a vertex
/// and no allocation per entry, where a std::set of positions took 80. `stopAtFirst` returns
/// 1 at the first repeat.
inline std::size_t repeatedPositions(const std::vector<Vec3>& vertices, bool stopAtFirst = false) {
  if (vertices.size() < 2) return 0;
  std::size_t slots = 16;
  while (slots < 2 * vertices.size()) slots *= 2;
  std::vector<std::uint32_t> table(slots, 0);  // vertex + 1; 0 is empty
  auto hash = [](const Vec3& v) {
    std::uint64_t h = 1469598103934665603ull;
    for (double c : {v.x, v.y, v.z}) {
      c = c == 0 ? 0.0 : c;
      std::uint64_t bits;
      std::memcpy(&bits, &c, sizeof bits);
      h = (h ^ bits) * 1099511628211ull;
    }
    return h ^ (h >> 29);
  };
  std::size_t repeats = 0;
  for (std::size_t k = 0; k < vertices.size(); ++k) {
    const Vec3& v = vertices[k];
    for (std::size_t at = hash(v) & (slots - 1);; at = (at + 1) & (slots - 1)) {
      if (table[at] == 0) {
        table[at] = std::uint32_t(k + 1);
        break;
      }
      const Vec3& o = vertices[table[at] - 1];
      if (o.x == v.x && o.y == v.y && o.z == v.z) {
        ++repeats;
        if (stopAtFirst) return repeats;
        break;
      }
    }
  }
  return repeats;
}

}  // namespace radkit
