// Patch subdivision on OpenMesh's halfedge structure.
//
// Every edge of a surface is split into n equal segments. A quad face becomes an a×b grid
// (bilinear map, a on one pair of opposite edges, b on the other); a triangle becomes n²
// triangles similar to it (n on all three edges). Opposite edges of a quad, and all edges of a
// triangle, must therefore share a count: edges are grouped into classes with union-find and
// each class takes the largest count its edges ask for. Shared edges then carry the same
// points from both sides, so a surface has no T-junctions, and patches keep the face's shape.
#include "geometry/subdivision.h"

#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include "geometry/openmesh_errors.h"
#include "util/errors.h"
#include "util/setting_names.h"

namespace radkit {

namespace {

struct DoubleTraits : public OpenMesh::DefaultTraits {
  typedef OpenMesh::Vec3d Point;
  typedef OpenMesh::Vec3d Normal;
};
using PolyMesh = OpenMesh::PolyMesh_ArrayKernelT<DoubleTraits>;

Vec3 toVec3(const OpenMesh::Vec3d& p) { return {p[0], p[1], p[2]}; }

/// One surface as a halfedge mesh plus its edge classes.
struct SurfaceTopology {
  PolyMesh mesh;
  std::vector<int> edgeClass;       ///< class of each edge
  std::vector<double> classLength;  ///< longest edge of each class
  std::size_t detachedFaces = 0;    ///< faces that joined their neighbours at no vertex
  std::size_t firstDetached = 0;    ///< the first of them (input face index)
};

int findRoot(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

SurfaceTopology buildTopology(const Surface& s) {
  SurfaceTopology t;
  // OpenMesh writes "PolyMeshT::add_face: complex edge" for each face it refuses; the count is
  // reported by subdivide() in radkit's words instead.
  const CapturedOpenMeshErrors quiet;
  std::vector<PolyMesh::VertexHandle> vh;
  for (const Vec3& v : s.vertices) vh.push_back(t.mesh.add_vertex({v.x, v.y, v.z}));
  for (const Face& f : s.faces) {
    std::vector<PolyMesh::VertexHandle> fv;
    for (int v : f.vertices) fv.push_back(vh[v]);
    // Faces meeting only at a vertex (a "complex vertex") cannot join the halfedge mesh;
    // such a face gets its own copies of the vertices and joins its neighbours at none.
    if (!t.mesh.add_face(fv).is_valid()) {
      if (t.detachedFaces++ == 0) t.firstDetached = std::size_t(&f - s.faces.data());
      // The point is copied first: add_vertex takes it by reference and may reallocate the
      // array it lives in (a use after free under ASan).
      for (auto& h : fv) {
        const PolyMesh::Point p = t.mesh.point(h);
        h = t.mesh.add_vertex(p);
      }
      if (!t.mesh.add_face(fv).is_valid())
        throw std::runtime_error(s.source + ": cannot build the surface mesh");
    }
  }
  std::vector<int> parent(t.mesh.n_edges());
  std::iota(parent.begin(), parent.end(), 0);
  auto unite = [&](int a, int b) { parent[findRoot(parent, a)] = findRoot(parent, b); };
  for (auto f : t.mesh.faces()) {
    std::vector<int> e;
    for (auto h : t.mesh.fh_range(f)) e.push_back(t.mesh.edge_handle(h).idx());
    if (e.size() == 4) {
      unite(e[0], e[2]);
      unite(e[1], e[3]);
    } else {
      unite(e[0], e[1]);
      unite(e[1], e[2]);
    }
  }
  std::vector<int> id(parent.size(), -1);
  t.edgeClass.resize(parent.size());
  for (std::size_t e = 0; e < parent.size(); ++e) {
    int r = findRoot(parent, int(e));
    if (id[r] < 0) {
      id[r] = int(t.classLength.size());
      t.classLength.push_back(0);
    }
    t.edgeClass[e] = id[r];
  }
  // The length a class must resolve: quad edges by their length (a×b cells of about h²);
  // a triangle by √area, so its n² similar cells also come out about h² whatever its shape
  // (by its longest edge, a right triangle would get cells of h²/4).
  for (auto f : t.mesh.faces()) {
    std::vector<int> e;
    for (auto h : t.mesh.fh_range(f)) e.push_back(t.edgeClass[t.mesh.edge_handle(h).idx()]);
    if (e.size() == 4) {
      int k = 0;
      for (auto h : t.mesh.fh_range(f)) {
        double len = t.mesh.calc_edge_length(t.mesh.edge_handle(h));
        t.classLength[e[k]] = std::max(t.classLength[e[k]], len);
        ++k;
      }
    } else {
      std::vector<Vec3> p;
      for (auto v : t.mesh.fv_range(f)) p.push_back(toVec3(t.mesh.point(v)));
      double area = 0.5 * length(cross(p[1] - p[0], p[2] - p[0]));
      t.classLength[e[0]] = std::max(t.classLength[e[0]], std::sqrt(area));
    }
  }
  return t;
}

[[noreturn]] void tooManyPatches() {
  throw TooManyPatches("subdivide: the settings need more than " + std::to_string(kMaxPatches) +
                       " patches");
}

/// Segments per edge class for a target edge length h (0: one segment each). Counted in
/// double first: a tiny h would overflow int.
std::vector<int> classCounts(const SurfaceTopology& t, double h) {
  std::vector<int> n(t.classLength.size(), 1);
  if (h > 0)
    for (std::size_t c = 0; c < n.size(); ++c) {
      const double segments = std::ceil(t.classLength[c] / h * (1 - 1e-12));
      if (!(segments <= double(kMaxPatches))) tooManyPatches();  // a class this long needs as many
      n[c] = std::max(1, int(segments));
    }
  return n;
}

long long patchCount(const SurfaceTopology& t, const std::vector<int>& n) {
  long long count = 0;
  for (auto f : t.mesh.faces()) {
    std::vector<int> e;
    for (auto h : t.mesh.fh_range(f)) e.push_back(n[t.edgeClass[t.mesh.edge_handle(h).idx()]]);
    count += e.size() == 4 ? (long long)e[0] * e[1] : (long long)e[0] * e[0];
  }
  return count;
}

/// Emits the patches of one surface into `out` (vertices appended, shared along edges).
void emitPatches(const SurfaceTopology& t, const std::vector<int>& n, int surface, PatchMesh& out) {
  const PolyMesh& m = t.mesh;
  const int base = int(out.vertices.size());
  for (auto v : m.vertices()) out.vertices.push_back(toVec3(m.point(v)));
  // Points along each edge, in the direction of the edge's halfedge 0, ends included.
  std::vector<std::vector<int>> edgePoints(m.n_edges());
  for (auto e : m.edges()) {
    auto h = m.halfedge_handle(e, 0);
    int a = base + m.from_vertex_handle(h).idx(), b = base + m.to_vertex_handle(h).idx();
    int k = n[t.edgeClass[e.idx()]];
    std::vector<int>& pts = edgePoints[e.idx()];
    pts.push_back(a);
    for (int i = 1; i < k; ++i) {
      double u = double(i) / k;
      pts.push_back(int(out.vertices.size()));
      out.vertices.push_back(out.vertices[a] * (1 - u) + out.vertices[b] * u);
    }
    pts.push_back(b);
  }
  // The i-th point along a face's halfedge, whichever way the edge is stored.
  auto along = [&](PolyMesh::HalfedgeHandle h, int i) {
    const std::vector<int>& pts = edgePoints[m.edge_handle(h).idx()];
    return h.idx() % 2 == 0 ? pts[i] : pts[pts.size() - 1 - i];
  };
  auto addPatch = [&](std::initializer_list<int> v) {
    Patch p;
    p.vertexCount = int(v.size());
    std::copy(v.begin(), v.end(), p.vertex.begin());
    p.surface = surface;
    computePatchGeometry(out.vertices, p);
    out.patches.push_back(p);
  };
  for (auto f : m.faces()) {
    std::vector<PolyMesh::HalfedgeHandle> h;
    for (auto he : m.fh_range(f)) h.push_back(he);
    if (h.size() == 4) {
      const int a = n[t.edgeClass[m.edge_handle(h[0]).idx()]];
      const int b = n[t.edgeClass[m.edge_handle(h[1]).idx()]];
      // Grid index (i along h0, j along h1); the border comes from the shared edge points.
      std::vector<int> grid(std::size_t(a + 1) * std::size_t(b + 1));
      auto g = [&](int i, int j) -> int& { return grid[j * (a + 1) + i]; };
      Vec3 c[4];
      for (int k = 0; k < 4; ++k) c[k] = toVec3(m.point(m.from_vertex_handle(h[k])));
      for (int i = 0; i <= a; ++i) {
        g(i, 0) = along(h[0], i);
        g(a - i, b) = along(h[2], i);
      }
      for (int j = 0; j <= b; ++j) {
        g(a, j) = along(h[1], j);
        g(0, b - j) = along(h[3], j);
      }
      for (int j = 1; j < b; ++j)
        for (int i = 1; i < a; ++i) {
          double u = double(i) / a, v = double(j) / b;
          g(i, j) = int(out.vertices.size());
          out.vertices.push_back(c[0] * ((1 - u) * (1 - v)) + c[1] * (u * (1 - v)) +
                                 c[2] * (u * v) + c[3] * ((1 - u) * v));
        }
      for (int j = 0; j < b; ++j)
        for (int i = 0; i < a; ++i) addPatch({g(i, j), g(i + 1, j), g(i + 1, j + 1), g(i, j + 1)});
    } else {
      const int k = n[t.edgeClass[m.edge_handle(h[0]).idx()]];
      // Barycentric lattice P(i,j) = c0 + i/k (c1-c0) + j/k (c2-c0), i + j <= k.
      std::vector<int> lattice(std::size_t(k + 1) * std::size_t(k + 1), -1);
      auto l = [&](int i, int j) -> int& { return lattice[j * (k + 1) + i]; };
      Vec3 c0 = toVec3(m.point(m.from_vertex_handle(h[0])));
      Vec3 c1 = toVec3(m.point(m.from_vertex_handle(h[1])));
      Vec3 c2 = toVec3(m.point(m.from_vertex_handle(h[2])));
      for (int i = 0; i <= k; ++i) {
        l(i, 0) = along(h[0], i);      // c0 -> c1
        l(k - i, i) = along(h[1], i);  // c1 -> c2
        l(0, k - i) = along(h[2], i);  // c2 -> c0
      }
      for (int j = 1; j < k; ++j)
        for (int i = 1; i + j < k; ++i) {
          l(i, j) = int(out.vertices.size());
          out.vertices.push_back(c0 + (c1 - c0) * (double(i) / k) + (c2 - c0) * (double(j) / k));
        }
      for (int j = 0; j < k; ++j)
        for (int i = 0; i + j < k; ++i) {
          addPatch({l(i, j), l(i + 1, j), l(i, j + 1)});
          if (i + j + 1 < k) addPatch({l(i + 1, j), l(i + 1, j + 1), l(i, j + 1)});
        }
    }
  }
}

double maxFaceAreaLimitViolation(const PatchMesh& mesh, int begin, double maxArea) {
  double worst = 0;
  for (int i = begin; i < mesh.size(); ++i) worst = std::max(worst, mesh.patches[i].area / maxArea);
  return worst;
}

/// Edge length h giving about `target` patches in total (counts fall as h grows).
double lengthForPatchCount(const std::vector<const SurfaceTopology*>& tops, long long target) {
  auto total = [&](double h) {
    long long c = 0;
    for (const SurfaceTopology* t : tops) c += patchCount(*t, classCounts(*t, h));
    return c;
  };
  double longest = 0;
  for (const SurfaceTopology* t : tops)
    for (double len : t->classLength) longest = std::max(longest, len);
  double lo = longest * 1e-6, hi = longest * (1 + 1e-9);
  for (int it = 0; it < 100 && hi / lo > 1 + 1e-9; ++it) {
    double mid = std::sqrt(lo * hi);
    (total(mid) > target ? lo : hi) = mid;
  }
  // Of the two bracketing lengths, take the one whose count is nearer the target.
  return std::llabs(total(lo) - target) < std::llabs(total(hi) - target) ? lo : hi;
}

double surfaceArea(const SurfaceTopology& t) {
  double area = 0;
  for (auto f : t.mesh.faces()) {
    std::vector<Vec3> p;
    for (auto v : t.mesh.fv_range(f)) p.push_back(toVec3(t.mesh.point(v)));
    Vec3 n;
    for (std::size_t k = 0; k < p.size(); ++k) n += cross(p[k], p[(k + 1) % p.size()]);
    area += 0.5 * length(n);
  }
  return area;
}

/// Per-surface edge lengths for a patch target spread by area (see subdivide in the header):
/// hGlobal everywhere unless surfaces with more faces than their share starve the others.
std::vector<double> spreadByArea(const Scene& scene, const std::vector<SurfaceTopology>& tops,
                                 long long target, double hGlobal,
                                 std::vector<std::string>* warnings) {
  std::vector<double> h(tops.size(), hGlobal), share(tops.size());
  double total = 0;
  for (std::size_t s = 0; s < tops.size(); ++s) total += share[s] = surfaceArea(tops[s]);
  if (!(total > 0)) return h;
  std::vector<const SurfaceTopology*> open;  // surfaces with room in their share
  std::vector<std::size_t> full, starved;
  double openShare = 0;
  for (std::size_t s = 0; s < tops.size(); ++s) {
    share[s] *= double(target) / total;
    if (double(tops[s].mesh.n_faces()) > share[s]) {
      full.push_back(s);
      continue;
    }
    open.push_back(&tops[s]);
    openShare += share[s];
    if (4.0 * double(patchCount(tops[s], classCounts(tops[s], hGlobal))) < share[s])
      starved.push_back(s);
  }
  if (full.empty() || starved.empty()) return h;
  const double hOpen = lengthForPatchCount(open, std::max(1LL, std::llround(openShare)));
  long long fullFaces = 0;
  std::size_t biggest = full.front();
  for (std::size_t s : full) {
    fullFaces += tops[s].mesh.n_faces();
    if (tops[s].mesh.n_faces() > tops[biggest].mesh.n_faces()) biggest = s;
  }
  for (std::size_t s = 0; s < tops.size(); ++s)
    if (std::find(full.begin(), full.end(), s) == full.end()) h[s] = hOpen;
  if (warnings) {
    const Surface& mesh = scene.surfaces[biggest];
    warnings->push_back(
        mesh.source + ": its " + std::to_string(tops[biggest].mesh.n_faces()) + " faces" +
        (full.size() > 1 ? " (" + std::to_string(fullFaces) + " in the " +
                               std::to_string(full.size()) + " surfaces finer than their share)"
                         : "") +
        " exceed their area's share (" + std::to_string(std::llround(share[biggest])) +
        ") of the " + std::to_string(target) + "-patch target, which left " +
        std::to_string(starved.size()) + " other surface" + (starved.size() == 1 ? "" : "s") +
        " (\"" + scene.surfaces[starved.front()].name + "\"" + (starved.size() > 1 ? ", ..." : "") +
        ") nearly whole. They were split to their own share instead, so " +
        "the scene has more patches than the target. Fix: give " + setting("max_area") +
        " for one patch size "
        "everywhere, or "
        "simplify the mesh.");
  }
  return h;
}

}  // namespace

PatchMesh subdivide(const Scene& scene, const SubdivisionSettings& settings,
                    std::vector<std::string>* warnings) {
  if (!(settings.maxArea >= 0) || !std::isfinite(settings.maxArea) || settings.targetPatches < 0)
    throw std::invalid_argument("subdivide: maxArea and targetPatches must be finite and >= 0");
  if (settings.targetPatches > kMaxPatches) tooManyPatches();
  std::vector<SurfaceTopology> tops;
  for (const Surface& s : scene.surfaces) {
    tops.push_back(buildTopology(s));
    if (warnings && tops.back().detachedFaces > 0)
      warnings->push_back(
          s.source + ": " + std::to_string(tops.back().detachedFaces) + " of its " +
          std::to_string(s.faces.size()) + " faces (the first is face " +
          std::to_string(tops.back().firstDetached) +
          ") touch their neighbours where a surface cannot pass (a vertex where two fans meet, "
          "or an edge of more than two faces: OpenMesh's \"complex vertex\" or \"complex "
          "edge\"); each is split into patches on its own, so no face is lost, but patch edges "
          "there need not line up. Fix: " +
          setting("repair") + " cuts such vertices and edges apart.");
    for (double len : tops.back().classLength)
      if (!std::isfinite(len))
        throw InputError(s.source +
                         " is too large to measure: its edge lengths overflow a double. Fix: "
                         "scale the scene down (coordinates beyond about 1e150 overflow).");
  }
  std::vector<const SurfaceTopology*> all;
  for (const SurfaceTopology& t : tops) all.push_back(&t);
  const double hGlobal =
      settings.targetPatches > 0 ? lengthForPatchCount(all, settings.targetPatches) : 0;
  const std::vector<double> hSurface =
      settings.targetPatches > 0
          ? spreadByArea(scene, tops, settings.targetPatches, hGlobal, warnings)
          : std::vector<double>(tops.size(), 0.0);

  PatchMesh out;
  for (std::size_t s = 0; s < tops.size(); ++s) {
    out.surfaceBegin.push_back(out.size());
    double h = hSurface[s];
    if (settings.maxArea > 0) {
      double hArea = std::sqrt(settings.maxArea);
      h = h > 0 ? std::min(h, hArea) : hArea;
    }
    // Cells of skewed quads or obtuse triangles can exceed h²: shrink h until all fit.
    for (int attempt = 0;; ++attempt) {
      const std::vector<int> counts = classCounts(tops[s], h);
      if (out.size() + patchCount(tops[s], counts) > kMaxPatches) tooManyPatches();
      // Emitted in place and cut back on a retry: a copy of the whole mesh per surface made
      // loading quadratic in the surface count.
      const std::size_t vertexMark = out.vertices.size();
      const int patchMark = out.size();
      emitPatches(tops[s], counts, int(s), out);
      double over =
          settings.maxArea > 0 ? maxFaceAreaLimitViolation(out, patchMark, settings.maxArea) : 0;
      if (over <= 1 + 1e-12 || attempt > 60) break;
      out.vertices.resize(vertexMark);
      out.patches.resize(std::size_t(patchMark));
      h *= std::min(0.98, 1 / std::sqrt(over));
    }
  }
  out.surfaceBegin.push_back(out.size());
  for (const Surface& s : scene.surfaces)
    if (s.cullBack) {
      for (const Surface& t : scene.surfaces) out.cullBack.push_back(t.cullBack ? 1 : 0);
      break;
    }
  return out;
}

PatchMesh subdivideScene(const Scene& scene, const SubdivisionSettings& settings,
                         const std::function<void(const std::string&)>& warn) {
  try {
    std::vector<std::string> warnings;
    PatchMesh mesh = subdivide(scene, settings, &warnings);
    if (warn)
      for (const std::string& w : warnings) warn(w);
    return mesh;
  } catch (const TooManyPatches&) {
    throwTooManyPatches(scene, settings);
  }
}

void throwTooManyPatches(const Scene& scene, const SubdivisionSettings& settings) {
  std::ostringstream option;
  if (settings.maxArea > 0)
    option << setting("max_area") + " " << settings.maxArea;
  else
    option << setting("patches") + " " << settings.targetPatches;
  throw InputError(scene.file + ": " + option.str() + " would split the scene into more than " +
                   std::to_string(kMaxPatches) +
                   " patches, the most radkit meshes. Fix: give a larger " + setting("max_area") +
                   ", or fewer " + setting("patches") + ".");
}

}  // namespace radkit
