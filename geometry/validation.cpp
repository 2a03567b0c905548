// Scene validation and normalisation. Exact predicates (CGAL, Epick kernel) decide
// degeneracy; CGAL's Polygon Mesh Processing finds self-intersections.
#include "geometry/validation.h"

#include "geometry/patch_mesh.h"
#include "geometry/positions.h"
#include "util/errors.h"
#include "util/format.h"
#include "util/setting_names.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/manifoldness.h>
#include <CGAL/Polygon_mesh_processing/merge_border_vertices.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_mesh_to_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Polygon_mesh_processing/stitch_borders.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/intersections.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/parallel_sort.h>

namespace radkit {

namespace PMP = CGAL::Polygon_mesh_processing;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point3 = Kernel::Point_3;

namespace {

Point3 toCgal(const Vec3& v) { return {v.x, v.y, v.z}; }

std::string faceName(const Surface& s, std::size_t f) {
  return s.source + ", face " + std::to_string(f);
}

std::string fmt(double v) { return formatNumber(v); }

Vec3 newellNormal(const std::vector<Vec3>& p) {
  Vec3 n;
  for (std::size_t k = 0; k < p.size(); ++k) n += cross(p[k], p[(k + 1) % p.size()]);
  return n * 0.5;
}

std::vector<Vec3> facePoints(const Surface& s, const Face& f) {
  std::vector<Vec3> p;
  for (int v : f.vertices) p.push_back(s.vertices[v]);
  return p;
}

/// A face's corner positions in a fixed order, so one polygon gives one key however its
/// corners are numbered or where its list starts.
std::vector<Vec3> sortedCorners(const Surface& s, const Face& f) {
  std::vector<Vec3> p = facePoints(s, f);
  std::sort(p.begin(), p.end(), [](const Vec3& a, const Vec3& b) {
    return a.x != b.x ? a.x < b.x : a.y != b.y ? a.y < b.y : a.z < b.z;
  });
  return p;
}

/// The hash of sortedCorners(s, f), without a vector for the faces of three or four corners.
std::uint64_t cornerHash(const Surface& s, const Face& f) {
  auto less = [](const Vec3& a, const Vec3& b) {
    return a.x != b.x ? a.x < b.x : a.y != b.y ? a.y < b.y : a.z < b.z;
  };
  Vec3 inline4[4];
  std::vector<Vec3> many;
  Vec3* p = inline4;
  const std::size_t n = f.vertices.size();
  if (n > 4) {
    many.resize(n);
    p = many.data();
  }
  for (std::size_t k = 0; k < n; ++k) p[k] = s.vertices[f.vertices[k]];
  std::sort(p, p + n, less);
  std::uint64_t h = 1469598103934665603ull;
  for (std::size_t k = 0; k < n; ++k)
    for (double c : {p[k].x, p[k].y, p[k].z}) {
      std::uint64_t bits;
      c = c == 0 ? 0.0 : c;  // -0 and +0 are one position
      std::memcpy(&bits, &c, sizeof bits);
      h = (h ^ bits) * 1099511628211ull;
    }
  return h;
}

/// Warns about faces that repeat another face's polygon with the same orientation: two
/// coincident faces each see the other's light half-counted (the dense method hides it, the
/// hierarchical method reports a large imbalance). Back-to-back copies are a two-sided panel
/// and are left alone. One warning per pair of surfaces; 16 bytes per face.
void warnOnCoincidentFaces(const Scene& scene, LoadReport& report) {
  struct Key {
    std::uint64_t hash;
    std::uint32_t surface, face;
  };
  std::vector<Key> keys;
  std::size_t total = 0;
  for (const Surface& s : scene.surfaces) total += s.faces.size();
  keys.resize(total);
  std::size_t first = 0;
  for (std::size_t si = 0; si < scene.surfaces.size(); ++si) {
    const Surface& s = scene.surfaces[si];
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, s.faces.size(), 4096),
        [&](const tbb::blocked_range<std::size_t>& range) {
          for (std::size_t f = range.begin(); f != range.end(); ++f)
            keys[first + f] = {cornerHash(s, s.faces[f]), std::uint32_t(si), std::uint32_t(f)};
        });
    first += s.faces.size();
  }
  // The keys are distinct (surface, face), so the order is the same however the sort splits.
  tbb::parallel_sort(keys.begin(), keys.end(), [](const Key& a, const Key& b) {
    return a.hash != b.hash         ? a.hash < b.hash
           : a.surface != b.surface ? a.surface < b.surface
                                    : a.face < b.face;
  });
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::array<std::size_t, 3>> pairs;
  for (std::size_t a = 0; a < keys.size(); ++a)
    for (std::size_t b = a + 1; b < keys.size() && keys[b].hash == keys[a].hash; ++b) {
      const Surface& sa = scene.surfaces[keys[a].surface];
      const Surface& sb = scene.surfaces[keys[b].surface];
      const Face& fa = sa.faces[keys[a].face];
      const Face& fb = sb.faces[keys[b].face];
      if (sortedCorners(sa, fa) != sortedCorners(sb, fb)) continue;  // a hash collision
      if (dot(newellNormal(facePoints(sa, fa)), newellNormal(facePoints(sb, fb))) <= 0) continue;
      auto [it, added] =
          pairs.try_emplace({keys[a].surface, keys[b].surface},
                            std::array<std::size_t, 3>{0, keys[a].face, keys[b].face});
      ++it->second[0];
    }
  for (const auto& [surfaces, found] : pairs) {
    const Surface& sa = scene.surfaces[surfaces.first];
    const Surface& sb = scene.surfaces[surfaces.second];
    const std::string which = surfaces.first == surfaces.second
                                  ? sa.source + " has " + std::to_string(found[0]) +
                                        " face(s) repeating another of its faces"
                                  : sa.source + " and " + sb.source + " share " +
                                        std::to_string(found[0]) + " coincident face(s)";
    report.warnings.push_back(
        which + " (e.g. face " + std::to_string(found[1]) + " and face " +
        std::to_string(found[2]) + ": the same polygon facing the same way). Light between " +
        "coincident faces is wrong in both methods. Fix: remove the copies (" + setting("repair") +
        " removes "
        "them within one surface).");
  }
}

void checkMaterials(const Scene& scene) {
  for (const Material& m : scene.materials) {
    std::string where = scene.file + ": material \"" + m.name + "\"";
    for (int c = 0; c < 3; ++c) {
      const double e = m.emission[c];
      if (!(e >= 0) || !std::isfinite(e))
        throw InputError(
            where + ": emission " + fmt(e) + " (channel " + std::to_string(c) +
            ") must be a finite number >= 0. Fix: use 0 for surfaces that do not emit.");
      // Radiosity multiplies emission by areas and 1/(1-ρ) and sums squares of powers: beyond
      // these bounds results under- or overflow a double (1e-320 gave B = 0 silently).
      if (e != 0 && !(e >= kMinEmission && e <= kMaxEmission))
        throw InputError(where + ": emission " + fmt(e) + " (channel " + std::to_string(c) +
                         ") is outside [" + fmt(kMinEmission) + ", " + fmt(kMaxEmission) +
                         "], where results stay finite and exact. Fix: give it in a unit "
                         "that brings it into that range (results scale linearly), or 0.");
    }
  }
}

/// What is wrong with face f as given, tested in this order; no allocation, so the search for
/// the first bad face can run over millions of faces. `vertex`: the first index out of range.
enum class FaceProblem { None, TooFewVertices, MissingVertex, RepeatedVertex, Degenerate };
FaceProblem faceProblem(const Surface& s, std::size_t f, int& vertex) {
  const Face& face = s.faces[f];
  const std::size_t n = face.vertices.size();
  if (n < 3) return FaceProblem::TooFewVertices;
  for (int v : face.vertices)
    if (v < 0 || v >= int(s.vertices.size())) {
      vertex = v;
      return FaceProblem::MissingVertex;
    }
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = a + 1; b < n; ++b)
      if (face.vertices[a] == face.vertices[b]) return FaceProblem::RepeatedVertex;
  const Vec3& p0 = s.vertices[face.vertices[0]];
  const Vec3& p1 = s.vertices[face.vertices[1]];
  bool allCollinear = true;
  for (std::size_t k = 2; k < n && allCollinear; ++k)
    allCollinear = CGAL::collinear(toCgal(p0), toCgal(p1), toCgal(s.vertices[face.vertices[k]]));
  if (allCollinear) return FaceProblem::Degenerate;
  Vec3 normal;  // newellNormal without the copy of the points
  for (std::size_t k = 0; k < n; ++k)
    normal += cross(s.vertices[face.vertices[k]], s.vertices[face.vertices[(k + 1) % n]]);
  return length(normal * 0.5) == 0 ? FaceProblem::Degenerate : FaceProblem::None;
}

/// Exact checks of one face as given: vertex indices, repeats, collinearity.
void checkFace(const Surface& s, std::size_t f) {
  int vertex = 0;
  switch (faceProblem(s, f, vertex)) {
    case FaceProblem::None:
      return;
    case FaceProblem::TooFewVertices:
      throw InputError(faceName(s, f) + " has " + std::to_string(s.faces[f].vertices.size()) +
                       " vertices. Fix: a face needs at least 3.");
    case FaceProblem::MissingVertex:
      throw InputError(faceName(s, f) + " names vertex " + std::to_string(vertex) +
                       ", which does not exist.");
    case FaceProblem::RepeatedVertex:
      throw InputError(faceName(s, f) +
                       " repeats a vertex (degenerate face). Fix: remove the repeated point, "
                       "or give " +
                       setting("repair") + " to drop such faces.");
    case FaceProblem::Degenerate:
      throw InputError(faceName(s, f) +
                       " is degenerate: its vertices are collinear, so its area "
                       "is zero. Fix: remove the face or correct its vertices, or give " +
                       setting("repair") +
                       " "
                       "to drop such faces.");
  }
}

/// Two faces of one surface running an edge the same way.
struct EdgeClash {
  std::size_t face = 0, other = 0;
  std::pair<int, int> edge;
};

/// A surface's directed edges grouped by their first vertex and sorted by their second (with
/// the corner that runs it, corners numbered face by face): the edge questions of validation
/// answered in linear time and memory (8 bytes a corner), in parallel, with no map.
class DirectedEdges {
 public:
  explicit DirectedEdges(const Surface& s) {
    const std::size_t n = s.vertices.size();
    m_start.assign(n + 1, 0);
    m_faceStart.reserve(s.faces.size() + 1);
    std::uint64_t corners = 0;
    for (const Face& f : s.faces) {
      m_faceStart.push_back(corners);
      corners += f.vertices.size();
      for (int v : f.vertices) ++m_start[std::size_t(v) + 1];
    }
    m_faceStart.push_back(corners);
    for (std::size_t v = 0; v < n; ++v) m_start[v + 1] += m_start[v];
    m_edges.resize(corners);
    std::vector<std::uint64_t> fill(m_start.begin(), m_start.end() - 1);
    std::uint64_t corner = 0;
    for (const Face& f : s.faces) {
      const auto& v = f.vertices;
      for (std::size_t k = 0; k < v.size(); ++k, ++corner)
        m_edges[fill[std::size_t(v[k])]++] =
            std::uint64_t(std::uint32_t(v[(k + 1) % v.size()])) << 32 | corner;
    }
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1024),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        for (std::size_t a = range.begin(); a != range.end(); ++a)
                          std::sort(m_edges.begin() + std::ptrdiff_t(m_start[a]),
                                    m_edges.begin() + std::ptrdiff_t(m_start[a + 1]));
                      });
  }
  std::size_t vertices() const { return m_start.size() - 1; }
  bool empty() const { return m_edges.empty(); }
  /// The face a corner belongs to.
  std::size_t faceOf(std::uint64_t corner) const {
    return std::size_t(std::upper_bound(m_faceStart.begin(), m_faceStart.end(), corner) -
                       m_faceStart.begin() - 1);
  }
  /// Entries from a: (b << 32 | corner), sorted.
  const std::uint64_t* begin(std::size_t a) const { return m_edges.data() + m_start[a]; }
  const std::uint64_t* end(std::size_t a) const { return m_edges.data() + m_start[a + 1]; }
  /// How many corners run a -> b.
  std::size_t count(std::size_t a, std::uint32_t b) const {
    const std::uint64_t lo = std::uint64_t(b) << 32, hi = lo | 0xffffffffull;
    return std::size_t(std::upper_bound(begin(a), end(a), hi) -
                       std::lower_bound(begin(a), end(a), lo));
  }

 private:
  std::vector<std::uint64_t> m_start, m_faceStart, m_edges;
};

/// The first directed edge used twice within the surface: two faces wound against each other,
/// or three faces on one edge. "First" as a walk over the faces in order meets it.
std::optional<EdgeClash> firstEdgeClash(const Surface& s) {
  const DirectedEdges edges(s);
  constexpr std::uint64_t kNone = ~std::uint64_t(0);
  struct Found {
    std::uint64_t corner = kNone, firstCorner = 0, a = 0, b = 0;
  };
  const Found found = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, edges.vertices(), 1024), Found{},
      [&](const tbb::blocked_range<std::size_t>& range, Found best) {
        for (std::size_t a = range.begin(); a != range.end(); ++a)
          for (const std::uint64_t* e = edges.begin(a); e + 1 < edges.end(a); ++e)
            // e and e + 1 run the same edge: e + 1 is where the walk meets it again (the
            // later ones of a group come after it).
            if ((e[0] >> 32) == (e[1] >> 32) &&
                (e == edges.begin(a) || (e[-1] >> 32) != (e[0] >> 32)) &&
                (e[1] & 0xffffffffull) < best.corner)
              best = {e[1] & 0xffffffffull, e[0] & 0xffffffffull, a, e[0] >> 32};
        return best;
      },
      [](const Found& x, const Found& y) { return x.corner <= y.corner ? x : y; });
  if (found.corner == kNone) return std::nullopt;
  return EdgeClash{
      edges.faceOf(found.corner), edges.faceOf(found.firstCorner), {int(found.a), int(found.b)}};
}

/// Hears from CGAL's orient_polygon_soup which polygons it reversed and which edges have more
/// than two faces. CGAL copies the visitor, so the record lives outside it.
struct OrientationRecord {
  std::vector<char> reversed;
  std::vector<std::array<std::size_t, 3>> nonManifoldEdges;  ///< vertex, vertex, faces
  std::size_t nonManifoldVertices = 0;
  std::set<std::pair<std::size_t, std::size_t>> seen;  ///< non-manifold edges reported
};
struct OrientationVisitor : PMP::Default_orientation_visitor {
  OrientationRecord* record;
  explicit OrientationVisitor(OrientationRecord* r) : record(r) {}
  void polygon_orientation_reversed(std::size_t p) { record->reversed[p] ^= 1; }
  void non_manifold_edge(std::size_t a, std::size_t b, std::size_t faces) {
    // CGAL reports an edge once per face beyond the second; keep one entry per edge.
    if (record->seen.insert(std::minmax(a, b)).second)
      record->nonManifoldEdges.push_back({a, b, faces});
  }
  void non_manifold_vertex(std::size_t, std::size_t) { ++record->nonManifoldVertices; }
};

/// Signed volume enclosed by a surface whose every edge has exactly two faces (a closed
/// mesh), positive when its faces point outward; nullopt when the surface is not closed.
std::optional<double> closedSignedVolume(const Surface& s) {
  const DirectedEdges edges(s);
  if (edges.empty()) return std::nullopt;
  // Closed: every edge has two faces, counting both directions.
  const bool closed = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, edges.vertices(), 1024), true,
      [&](const tbb::blocked_range<std::size_t>& range, bool ok) {
        for (std::size_t a = range.begin(); a != range.end() && ok; ++a)
          for (const std::uint64_t* e = edges.begin(a); e != edges.end(a) && ok;) {
            const std::uint32_t b = std::uint32_t(*e >> 32);
            std::size_t ab = 0;
            for (; e != edges.end(a) && std::uint32_t(*e >> 32) == b; ++e) ++ab;
            ok = ab + edges.count(b, std::uint32_t(a)) == 2;
          }
        return ok;
      },
      [](bool x, bool y) { return x && y; });
  if (!closed) return std::nullopt;
  // Relative to a vertex, so a model far from the origin keeps its digits.
  const Vec3 o = s.vertices[s.faces[0].vertices[0]];
  double volume = 0;
  for (const Face& f : s.faces)
    for (std::size_t k = 1; k + 1 < f.vertices.size(); ++k) {
      const Vec3 a = s.vertices[f.vertices[0]] - o, b = s.vertices[f.vertices[k]] - o,
                 c = s.vertices[f.vertices[k + 1]] - o;
      volume += dot(a, cross(b, c)) / 6;
    }
  return volume;
}

/// A closed mesh wound inward receives light only on the inside. That is right for a room
/// seen from within (an emitter inside its bounds), and almost always a fault otherwise (a
/// scan or export whose normals point into the model): warn with the fix.
void checkOrientation(const Scene& scene, const Surface& s, LoadReport& report) {
  const std::optional<double> volume = closedSignedVolume(s);
  // An emitting one lights its own inside (a spherical furnace): nothing to warn about.
  if (!volume || *volume >= 0 || scene.materials[s.material].emits()) return;
  Vec3 lo = s.vertices[0], hi = s.vertices[0];
  for (const Vec3& v : s.vertices)
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], v[k]), hi[k] = std::max(hi[k], v[k]);
  for (const Surface& e : scene.surfaces) {
    if (&e == &s || !scene.materials[e.material].emits() || e.vertices.empty()) continue;
    Vec3 c;
    for (const Vec3& v : e.vertices) c += v;
    c = c / double(e.vertices.size());
    if (c.x > lo.x && c.y > lo.y && c.z > lo.z && c.x < hi.x && c.y < hi.y && c.z < hi.z)
      return;  // a light inside it: a room or a lamp shade
  }
  report.warnings.push_back(
      s.source + " is a closed mesh whose faces point inward (signed volume " + fmt(*volume) +
      "), and no light is inside it: it will receive light only on faces nothing reaches and "
      "stay dark. Fix: add \"reverse\": true to this surface (or, if it is a room, put its "
      "light inside it).");
}

/// Faces that share an edge (either direction), as one label per face.
std::vector<std::size_t> edgeConnectedParts(const Surface& s) {
  std::vector<std::size_t> parent(s.faces.size());
  for (std::size_t f = 0; f < parent.size(); ++f) parent[f] = f;
  auto root = [&](std::size_t f) {
    while (parent[f] != f) f = parent[f] = parent[parent[f]];
    return f;
  };
  std::map<std::pair<int, int>, std::size_t> firstFace;
  for (std::size_t f = 0; f < s.faces.size(); ++f) {
    const auto& v = s.faces[f].vertices;
    for (std::size_t k = 0; k < v.size(); ++k) {
      const int a = v[k], b = v[(k + 1) % v.size()];
      const auto [it, inserted] = firstFace.emplace(std::minmax(a, b), f);
      if (!inserted) parent[root(f)] = root(it->second);
    }
  }
  std::vector<std::size_t> part(s.faces.size());
  for (std::size_t f = 0; f < part.size(); ++f) part[f] = root(f);
  return part;
}

/// Makes the winding of each edge-connected part of a surface consistent (CGAL's
/// orient_polygon_soup), keeping the winding most of the part's faces had (on a tie, that of
/// its first face), and warns naming the faces reversed. Throws where no consistent winding
/// exists: an edge shared by three or more faces, or a one-sided surface (Möbius strip).
void repairOrientation(Surface& s, LoadReport& report) {
  if (!firstEdgeClash(s)) return;  // the common case costs one pass over the edges
  // A face listed twice with the same winding is a mistake, not a flipped face: reversing one
  // copy would make a two-sided sheet nobody asked for.
  std::map<std::vector<int>, std::size_t> byVertices;
  for (std::size_t f = 0; f < s.faces.size(); ++f) {
    std::vector<int> key = s.faces[f].vertices;
    std::rotate(key.begin(), std::min_element(key.begin(), key.end()), key.end());
    const auto [it, inserted] = byVertices.emplace(key, f);
    if (!inserted)
      throw InputError(faceName(s, f) + " repeats face " + std::to_string(it->second) +
                       " (same vertices, same winding). Fix: remove one of them (or reverse it, "
                       "for a sheet lit from both sides), or give " +
                       setting("repair") + " to remove every such copy.");
  }
  std::vector<Point3> points;
  for (const Vec3& v : s.vertices) points.push_back(toCgal(v));
  std::vector<std::vector<std::size_t>> polygons;
  for (const Face& f : s.faces) polygons.emplace_back(f.vertices.begin(), f.vertices.end());
  OrientationRecord record;
  record.reversed.assign(polygons.size(), 0);
  PMP::orient_polygon_soup(points, polygons,
                           CGAL::parameters::visitor(OrientationVisitor(&record)));
  if (!record.nonManifoldEdges.empty()) {
    const auto& e = record.nonManifoldEdges.front();
    throw InputError(s.source + ": the edge between vertices " + std::to_string(e[0]) + " and " +
                     std::to_string(e[1]) + " is shared by " + std::to_string(e[2]) +
                     " faces (non-manifold), so no side of them is the front. Fix: give " +
                     setting("repair") +
                     " to "
                     "cut such edges (and report what changed), or split the surface so that every "
                     "edge has at most two faces.");
  }
  const std::vector<std::size_t> part = edgeConnectedParts(s);
  std::map<std::size_t, std::pair<std::size_t, std::size_t>> counts;  // part: reversed, faces
  for (std::size_t f = 0; f < part.size(); ++f) {
    counts[part[f]].first += record.reversed[f];
    counts[part[f]].second += 1;
  }
  std::map<std::size_t, bool> keepReversed;  // part: flip CGAL's choice back
  for (std::size_t f = 0; f < part.size(); ++f) {
    if (keepReversed.count(part[f])) continue;  // f is the part's first face
    const auto [reversed, faces] = counts[part[f]];
    keepReversed[part[f]] = 2 * reversed > faces || (2 * reversed == faces && record.reversed[f]);
  }
  std::vector<std::size_t> flipped;
  for (std::size_t f = 0; f < s.faces.size(); ++f)
    if (bool(record.reversed[f]) != keepReversed[part[f]]) {
      std::reverse(s.faces[f].vertices.begin(), s.faces[f].vertices.end());
      flipped.push_back(f);
    }
  if (const auto clash = firstEdgeClash(s))
    throw InputError(faceName(s, clash->face) + " and face " + std::to_string(clash->other) +
                     " run the edge between vertices " + std::to_string(clash->edge.first) +
                     " and " + std::to_string(clash->edge.second) +
                     " the same way whichever "
                     "faces are reversed: the surface has one side only (like a Möbius strip). "
                     "Fix: cut it into surfaces that each have a front and a back, or give " +
                     setting("repair") +
                     " "
                     "to cut it along one edge.");
  std::string list;
  for (std::size_t k = 0; k < flipped.size() && k < 10; ++k)
    list += (k ? ", " : "") + std::to_string(flipped[k]);
  if (flipped.size() > 10) list += " and " + std::to_string(flipped.size() - 10) + " more";
  const bool one = flipped.size() == 1;
  report.warnings.push_back(s.source + ": " + std::to_string(flipped.size()) +
                            (one ? " face was" : " faces were") + " wound against " +
                            (one ? "its" : "their") + " neighbours and reversed to match them (" +
                            (one ? "face " : "faces ") + list + "). Fix: reverse " +
                            (one ? "it" : "them") + " in the input to silence this warning.");
}

/// Winds each edge-connected part the way most of its input faces were (on a tie, as its first
/// face was): CGAL reversed the faces flagged in `reversed`. Returns how many faces end up
/// wound against their input.
std::size_t keepMajorityWinding(Surface& s, const std::vector<char>& reversed) {
  const std::vector<std::size_t> part = edgeConnectedParts(s);
  std::map<std::size_t, std::pair<std::size_t, std::size_t>> counts;  // part: reversed, faces
  for (std::size_t f = 0; f < part.size(); ++f) {
    counts[part[f]].first += reversed[f];
    counts[part[f]].second += 1;
  }
  std::map<std::size_t, bool> flipPart;
  for (std::size_t f = 0; f < part.size(); ++f)
    if (!flipPart.count(part[f])) {
      const auto [rev, faces] = counts[part[f]];
      flipPart[part[f]] = 2 * rev > faces || (2 * rev == faces && reversed[f]);
    }
  std::size_t against = 0;
  for (std::size_t f = 0; f < s.faces.size(); ++f) {
    if (flipPart[part[f]]) std::reverse(s.faces[f].vertices.begin(), s.faces[f].vertices.end());
    against += bool(reversed[f]) != flipPart[part[f]];
  }
  return against;
}

/// Drops vertices that lie exactly on the line through their neighbours (exact predicate).
std::vector<int> withoutCollinearVertices(const Surface& s, const std::vector<int>& v) {
  std::vector<int> out;
  for (std::size_t k = 0; k < v.size(); ++k) {
    const Vec3& a = s.vertices[v[(k + v.size() - 1) % v.size()]];
    const Vec3& b = s.vertices[v[k]];
    const Vec3& c = s.vertices[v[(k + 1) % v.size()]];
    if (!CGAL::collinear(toCgal(a), toCgal(b), toCgal(c))) out.push_back(v[k]);
  }
  return out;
}

double nonPlanarity(const std::vector<Vec3>& p, double* diameter) {
  Vec3 n = normalize(newellNormal(p));
  Vec3 c;
  for (const Vec3& q : p) c += q;
  c = c / double(p.size());
  double dev = 0, diam = 0;
  for (const Vec3& q : p) {
    dev = std::max(dev, std::fabs(dot(q - c, n)));
    for (const Vec3& r : p) diam = std::max(diam, length(q - r));
  }
  *diameter = diam;
  return dev / diam;
}

bool isConvex(const std::vector<Vec3>& p) {
  Vec3 n = newellNormal(p);
  for (std::size_t k = 0; k < p.size(); ++k) {
    const Vec3& a = p[k];
    const Vec3& b = p[(k + 1) % p.size()];
    const Vec3& c = p[(k + 2) % p.size()];
    if (dot(cross(b - a, c - b), n) <= 0) return false;
  }
  return true;
}

/// Ear clipping in the polygon's own plane; triangles keep the polygon's orientation.
std::vector<Face> triangulate(const Surface& s, const std::vector<int>& v) {
  std::vector<Vec3> p;
  for (int i : v) p.push_back(s.vertices[i]);
  Vec3 n = newellNormal(p);
  std::vector<int> left(v.begin(), v.end());
  std::vector<Face> out;
  auto at = [&](int i) { return s.vertices[i]; };
  auto inside = [&](const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c) {
    return dot(cross(b - a, q - a), n) >= 0 && dot(cross(c - b, q - b), n) >= 0 &&
           dot(cross(a - c, q - c), n) >= 0;
  };
  std::size_t guard = 0;
  while (left.size() > 3 && guard++ < 10 * v.size() * v.size()) {
    bool clipped = false;
    for (std::size_t k = 0; k < left.size() && !clipped; ++k) {
      int ia = left[(k + left.size() - 1) % left.size()], ib = left[k],
          ic = left[(k + 1) % left.size()];
      Vec3 a = at(ia), b = at(ib), c = at(ic);
      if (dot(cross(b - a, c - b), n) <= 0) continue;  // reflex vertex: not an ear
      bool empty = true;
      for (int iq : left)
        if (iq != ia && iq != ib && iq != ic && inside(at(iq), a, b, c)) empty = false;
      if (!empty) continue;
      out.push_back(Face{{ia, ib, ic}});
      left.erase(left.begin() + k);
      clipped = true;
    }
    if (!clipped) break;  // not simple in projection: fall back to a fan below
  }
  for (std::size_t k = 1; k + 1 < left.size(); ++k)
    out.push_back(Face{{left[0], left[k], left[k + 1]}});
  return out;
}

/// Splits a non-planar quadrilateral along the diagonal that leaves the better-shaped pair.
std::vector<Face> splitQuad(const Surface& s, const std::vector<int>& v) {
  auto worst = [&](int a, int b, int c, int d) {
    return std::max(polygonAspectRatio({s.vertices[a], s.vertices[b], s.vertices[c]}),
                    polygonAspectRatio({s.vertices[a], s.vertices[c], s.vertices[d]}));
  };
  if (worst(v[0], v[1], v[2], v[3]) <= worst(v[1], v[2], v[3], v[0]))
    return {Face{{v[0], v[1], v[2]}}, Face{{v[0], v[2], v[3]}}};
  return {Face{{v[1], v[2], v[3]}}, Face{{v[1], v[3], v[0]}}};
}

/// Makes every face a triangle or a planar convex quad.
void normaliseFaces(Surface& s, LoadReport& report) {
  // A triangle that passed checkFace has no vertex on the line through its neighbours: it
  // stays as it is, and a mesh of triangles is left alone (no copy of its faces).
  if (std::all_of(s.faces.begin(), s.faces.end(),
                  [](const Face& f) { return f.vertices.size() == 3; }))
    return;
  std::vector<Face> out;
  std::size_t warned = 0;
  for (std::size_t f = 0; f < s.faces.size(); ++f) {
    if (s.faces[f].vertices.size() == 3) {
      out.push_back(s.faces[f]);
      continue;
    }
    std::vector<int> v = withoutCollinearVertices(s, s.faces[f].vertices);
    std::vector<Vec3> p;
    for (int i : v) p.push_back(s.vertices[i]);
    if (v.size() == 3) {
      out.push_back(Face{v});
      continue;
    }
    double diameter = 0;
    double dev = nonPlanarity(p, &diameter);
    bool planar = dev <= kPlanarityTolerance;
    if (!planar && warned++ < 5)
      report.warnings.push_back(faceName(s, f) + " is not planar (deviation " +
                                fmt(dev * diameter) + " = " + fmt(100 * dev) +
                                "% of its size): split into triangles.");
    if (v.size() == 4 && planar && isConvex(p)) {
      out.push_back(Face{v});
    } else {
      std::vector<Face> tris = (v.size() == 4 && isConvex(p)) ? splitQuad(s, v) : triangulate(s, v);
      out.insert(out.end(), tris.begin(), tris.end());
    }
  }
  if (warned > 5)
    report.warnings.push_back(s.source + ": " + std::to_string(warned - 5) +
                              " more non-planar faces split.");
  s.faces = std::move(out);
}

/// Vertices at the position of an earlier vertex of the surface: faces meeting there are not
/// joined, which subdivision turns into cracks and T-junctions.
std::size_t unweldedVertices(const Surface& s) { return repeatedPositions(s.vertices); }

std::string count(std::size_t n, const std::string& one, const std::string& many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

}  // namespace

bool MeshRepair::changed() const {
  return weldedVertices + duplicateFaces + degenerateFaces + nonManifoldEdges +
             nonManifoldVertices + stitchedEdges + reversedFaces >
         0;
}

std::string MeshRepair::describe() const {
  std::vector<std::string> parts;
  if (weldedVertices)
    parts.push_back("welded " + count(weldedVertices, "duplicate vertex", "duplicate vertices"));
  if (duplicateFaces)
    parts.push_back("removed " + count(duplicateFaces, "duplicate face", "duplicate faces"));
  if (degenerateFaces)
    parts.push_back("removed " + count(degenerateFaces, "degenerate face", "degenerate faces"));
  if (nonManifoldEdges)
    parts.push_back("cut " + count(nonManifoldEdges, "non-manifold edge", "non-manifold edges"));
  if (nonManifoldVertices)
    parts.push_back("split " +
                    count(nonManifoldVertices, "non-manifold vertex", "non-manifold vertices"));
  if (stitchedEdges)
    parts.push_back("stitched " + count(stitchedEdges, "border edge", "border edges"));
  if (reversedFaces)
    parts.push_back("reversed " + count(reversedFaces, "face", "faces") +
                    " to match their neighbours");
  std::string text;
  for (const std::string& p : parts) text += (text.empty() ? "" : ", ") + p;
  return text.empty() ? "nothing to repair" : text;
}

MeshRepair repairMesh(Surface& s) {
  MeshRepair r;
  r.surface = s.source;
  std::vector<Point3> points;
  for (const Vec3& v : s.vertices) points.push_back(toCgal(v));
  std::vector<std::vector<std::size_t>> polygons;
  for (const Face& f : s.faces) polygons.emplace_back(f.vertices.begin(), f.vertices.end());
  r.weldedVertices = PMP::merge_duplicate_points_in_polygon_soup(points, polygons);
  // A face repeating a vertex or with all vertices on a line has no area and no front.
  const std::size_t before = polygons.size();
  polygons.erase(
      std::remove_if(polygons.begin(), polygons.end(),
                     [&](const std::vector<std::size_t>& p) {
                       if (std::set<std::size_t>(p.begin(), p.end()).size() != p.size() ||
                           p.size() < 3)
                         return true;
                       for (std::size_t k = 2; k < p.size(); ++k)
                         if (!CGAL::collinear(points[p[0]], points[p[1]], points[p[k]]))
                           return false;
                       return true;
                     }),
      polygons.end());
  r.degenerateFaces = before - polygons.size();
  // Copies wound the other way are kept: they make a sheet lit from both sides.
  r.duplicateFaces = PMP::merge_duplicate_polygons_in_polygon_soup(
      points, polygons,
      CGAL::parameters::erase_all_duplicates(false).require_same_orientation(true));
  PMP::remove_isolated_points_in_polygon_soup(points, polygons);
  if (polygons.empty())
    throw InputError(s.source +
                     ": no face is left after removing degenerate and duplicate faces. Fix: "
                     "check the mesh's faces.");
  OrientationRecord record;
  record.reversed.assign(polygons.size(), 0);
  PMP::orient_polygon_soup(points, polygons,
                           CGAL::parameters::visitor(OrientationVisitor(&record)));
  r.nonManifoldEdges = record.nonManifoldEdges.size();
  r.nonManifoldVertices = record.nonManifoldVertices;
  CGAL::Surface_mesh<Point3> mesh;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, mesh);
  r.stitchedEdges = PMP::stitch_borders(mesh);
  const std::size_t vertices = mesh.number_of_vertices();
  PMP::merge_duplicated_vertices_in_boundary_cycles(mesh);
  r.weldedVertices += vertices - mesh.number_of_vertices();
  r.nonManifoldVertices += PMP::duplicate_non_manifold_vertices(mesh);
  mesh.collect_garbage();  // faces keep their order: `record.reversed` still indexes them
  points.clear();
  polygons.clear();
  PMP::polygon_mesh_to_polygon_soup(mesh, points, polygons);
  s.vertices.clear();
  for (const Point3& p : points) s.vertices.push_back({p.x(), p.y(), p.z()});
  s.faces.clear();
  for (const auto& p : polygons) s.faces.push_back(Face{std::vector<int>(p.begin(), p.end())});
  r.reversedFaces = keepMajorityWinding(s, record.reversed);
  return r;
}

std::size_t countSelfIntersections(const Surface& surface,
                                   const std::function<void(double)>& progress) {
  auto done = [&](double f) {
    if (progress) progress(f);
  };
  std::vector<Point3> points;
  for (const Vec3& v : surface.vertices) points.push_back(toCgal(v));
  std::vector<std::vector<std::size_t>> triangles;
  for (const Face& f : surface.faces)
    for (std::size_t k = 1; k + 1 < f.vertices.size(); ++k)
      triangles.push_back(
          {std::size_t(f.vertices[0]), std::size_t(f.vertices[k]), std::size_t(f.vertices[k + 1])});
  // Faces that meet at copies of a vertex would count as crossing: weld them first.
  done(0.1);
  PMP::merge_duplicate_points_in_polygon_soup(points, triangles);
  done(0.2);
  // orient_polygon_soup duplicates non-manifold vertices so that the soup becomes a mesh.
  PMP::orient_polygon_soup(points, triangles);
  done(0.3);
  CGAL::Surface_mesh<Point3> mesh;
  PMP::polygon_soup_to_polygon_mesh(points, triangles, mesh);
  done(0.4);
  using FacePair =
      std::pair<CGAL::Surface_mesh<Point3>::Face_index, CGAL::Surface_mesh<Point3>::Face_index>;
  std::vector<FacePair> pairs;
  // Sequential: CGAL's parallel search (CGAL_LINKED_WITH_TBB) took more than twice as long on
  // two cores (15 s against 6.7 s for a million-triangle terrain on a busy machine).
  PMP::self_intersections(faces(mesh), mesh, std::back_inserter(pairs));
  done(0.9);
  // Faces that orient_polygon_soup cut apart at a non-manifold edge or vertex share corners
  // by position only, and CGAL counts their touching as crossing. Two triangles with an edge
  // in common meet only there unless coplanar on one side of it; with one corner p in common,
  // they meet beyond p exactly when the edge opposite p in one meets the other triangle.
  auto corners = [&](CGAL::Surface_mesh<Point3>::Face_index f) {
    std::vector<Point3> p;
    for (auto v : vertices_around_face(mesh.halfedge(f), mesh)) p.push_back(mesh.point(v));
    return p;
  };
  auto others = [](const std::vector<Point3>& t, const std::vector<Point3>& from) {
    std::vector<Point3> own;  // t's corners that `from` lacks
    for (const Point3& q : t)
      if (std::find(from.begin(), from.end(), q) == from.end()) own.push_back(q);
    return own;
  };
  std::size_t crossing = 0;
  for (const FacePair& pair : pairs) {
    const std::vector<Point3> a = corners(pair.first), b = corners(pair.second);
    const std::vector<Point3> onlyA = others(a, b), onlyB = others(b, a);
    bool touching = false;
    if (onlyB.size() == 1 && onlyA.size() == 1) {
      // Coplanar, they touch only when the edge separates their third corners.
      std::vector<Point3> edge;
      for (const Point3& q : a)
        if (q != onlyA[0]) edge.push_back(q);
      touching = !CGAL::coplanar(a[0], a[1], a[2], onlyB[0]) ||
                 CGAL::coplanar_orientation(edge[0], edge[1], onlyA[0], onlyB[0]) == CGAL::NEGATIVE;
    } else if (onlyB.size() == 2 && onlyA.size() == 2) {
      touching = !CGAL::do_intersect(Kernel::Segment_3(onlyA[0], onlyA[1]),
                                     Kernel::Triangle_3(b[0], b[1], b[2])) &&
                 !CGAL::do_intersect(Kernel::Segment_3(onlyB[0], onlyB[1]),
                                     Kernel::Triangle_3(a[0], a[1], a[2]));
    }
    crossing += !touching;
  }
  return crossing;
}

void validateScene(Scene& scene, LoadReport& report, bool repair,
                   const ValidationSettings& settings) {
  auto progress = [&](const std::string& stage, double f) {
    if (settings.progress) settings.progress(stage, f);
  };
  if (scene.surfaces.empty())
    throw InputError(scene.file + ": the scene has no surfaces. Fix: add at least one surface.");
  checkMaterials(scene);
  std::set<std::string> names;
  for (std::size_t si = 0; si < scene.surfaces.size(); ++si) {
    Surface& s = scene.surfaces[si];
    const std::string checking = "checking " + s.name;
    // A line break in a name splits every CSV row and report line it is written to.
    for (char c : s.name)
      if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
        throw InputError(s.source + ": the surface name \"" + s.name +
                         "\" holds a control character (a line break or tab). Fix: use "
                         "printable characters only.");
    if (!names.insert(s.name).second)
      throw InputError(s.source + ": the surface name \"" + s.name +
                       "\" is used twice. Fix: give each surface its own name.");
    if (s.faces.empty())
      throw InputError(s.source + " has no faces. Fix: give it a polygon or a non-empty mesh.");
    for (std::size_t v = 0; v < s.vertices.size(); ++v) {
      const Vec3& p = s.vertices[v];
      if (!isFinite(p))
        throw InputError(s.source + ", vertex " + std::to_string(v) +
                         " has a NaN or infinite coordinate. Fix: correct the coordinates.");
      // Embree refuses (asserts on) rays whose origin lies beyond about 1.8e18 in float.
      if (std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)}) > kMaxCoordinate)
        throw InputError(s.source + ", vertex " + std::to_string(v) + " has a coordinate of " +
                         fmt(std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)})) +
                         ", beyond the " + fmt(kMaxCoordinate) +
                         " the ray tracer handles. Fix: "
                         "use a larger unit or move the scene nearer the origin.");
    }
    if (repair) {
      for (std::size_t f = 0; f < s.faces.size(); ++f)
        for (int v : s.faces[f].vertices)
          if (v < 0 || v >= int(s.vertices.size()))
            throw InputError(faceName(s, f) + " names vertex " + std::to_string(v) +
                             ", which does not exist.");
      MeshRepair r = repairMesh(s);
      if (r.changed()) {
        report.warnings.push_back(s.source + ": repaired: " + r.describe() + ".");
        report.repairs.push_back(std::move(r));
      }
    } else if (std::size_t n = unweldedVertices(s)) {
      report.warnings.push_back(
          s.source + ": " + count(n, "vertex repeats", "vertices repeat") +
          " the position of another, so the faces there are not joined. Fix: give " +
          setting("repair") + " to weld them.");
    }
    progress(checking, 0.2);
    // The first face that fails, found in parallel, then worded by checkFace.
    const std::size_t bad = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, s.faces.size(), 4096), s.faces.size(),
        [&](const tbb::blocked_range<std::size_t>& range, std::size_t first) {
          int vertex = 0;
          for (std::size_t f = range.begin(); f != range.end() && f < first; ++f)
            if (faceProblem(s, f, vertex) != FaceProblem::None) return f;
          return first;
        },
        [](std::size_t a, std::size_t b) { return std::min(a, b); });
    if (bad < s.faces.size()) checkFace(s, bad);
    progress(checking, 0.5);
    repairOrientation(s, report);
    progress(checking, 0.8);
    normaliseFaces(s, report);
    progress(checking, 1.0);
    const bool selfCheck =
        settings.selfIntersections &&
        (si >= settings.surfaceSelfIntersections.size() || settings.surfaceSelfIntersections[si]);
    if (selfCheck) {
      const std::string stage = "self-intersections " + s.name;
      progress(stage, 0.0);
      const std::size_t n = countSelfIntersections(s, [&](double f) { progress(stage, f); });
      progress("self-intersections " + s.name, 1.0);
      if (n)
        report.warnings.push_back(
            s.source + " intersects itself (" + std::to_string(n) +
            " pairs of triangles cross): form factors near the crossing are unreliable.");
    }
  }
  progress("checking orientation", 0.0);
  for (std::size_t si = 0; si < scene.surfaces.size(); ++si) {
    checkOrientation(scene, scene.surfaces[si], report);
    progress("checking orientation", double(si + 1) / double(scene.surfaces.size()));
  }
  progress("checking coincident faces", 0.0);
  warnOnCoincidentFaces(scene, report);
  progress("checking coincident faces", 1.0);
  bool emits = std::any_of(scene.surfaces.begin(), scene.surfaces.end(),
                           [&](const Surface& s) { return scene.materials[s.material].emits(); });
  if (!emits && !scene.sky)
    report.warnings.push_back(scene.file + ": no surface emits, so every radiosity is zero.");
}

}  // namespace radkit
