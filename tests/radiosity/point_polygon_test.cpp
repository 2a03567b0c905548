// point-polygon against Howell's closed forms (docs/oracles.md), with convergence tables.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "geometry/ray_scene.h"
#include "output/run_files.h"
#include "radiosity/form_factors.h"
#include "radiosity/surface_form_factors.h"
#include "test_scenes.h"
#include "util/params.h"

namespace radkit {
namespace {
FormFactorResult compute(const test::MeshBuilder& b, const FormFactorSettings& s = {}) {
  RayScene visibility(b.mesh());
  return computeFormFactors(b.mesh(), visibility, s);
}

/// F from surface a to surface b (Σ A_i F_ij / A_a).
double surfaceF(const FormFactorResult& r, const test::MeshBuilder& b, int from, int to) {
  return surfaceFormFactors(b.mesh(), r.matrix)(from, to);
}
}  // namespace

TEST(PointPolygon, Construct) {
  test::MeshBuilder b = test::parallelRectangles(1, 1, 1);
  BruteForceVisibility vis(b.mesh());
  FormFactorSettings s;
  EXPECT_EQ(makeFormFactorMethod(b.mesh(), vis, s)->name(), "point-polygon");
  EXPECT_EQ(formFactorMethodNames().front(), "point-polygon");
  s.method = "radiant-wishes";
  EXPECT_THROW(makeFormFactorMethod(b.mesh(), vis, s), std::invalid_argument);
}

// C-11: the tabulated digits first, then the method on single patches and on meshes.
TEST(PointPolygon, ExactParallelRectangles) {
  EXPECT_NEAR(test::c11ParallelRectangles(1, 1), 0.19982489569838746, 1e-15);
  EXPECT_NEAR(test::c11ParallelRectangles(0.5, 0.5), 0.068590, 5e-7);
  EXPECT_NEAR(test::c11ParallelRectangles(2, 2), 0.415253, 5e-7);
  EXPECT_NEAR(test::c11ParallelRectangles(1, 5), 0.359167, 5e-7);
  EXPECT_NEAR(test::c11ParallelRectangles(1 / 0.5, 1.5 / 0.5), 0.4755764365, 1e-10);
  struct Case {
    double a, b, c;
    int n;
  };
  for (Case k : {Case{1, 1, 1, 1}, Case{0.5, 0.5, 1, 1}, Case{2, 2, 1, 1}, Case{1, 5, 1, 1},
                 Case{1, 1.5, 0.5, 1}, Case{1, 1.5, 0.5, 4}, Case{1, 1, 1, 5}}) {
    test::MeshBuilder b = test::parallelRectangles(k.a, k.b, k.c, k.n);
    FormFactorResult r = compute(b);
    double exact = test::c11ParallelRectangles(k.a / k.c, k.b / k.c);
    EXPECT_NEAR(surfaceF(r, b, 0, 1), exact, 1e-4) << k.a << "x" << k.b << " at " << k.c;
    EXPECT_NEAR(surfaceF(r, b, 0, 1), exact, 1e-5);  // far cells: ~1e-4 relative per entry
    EXPECT_EQ(r.diagnostics.raysCast, 0);            // nothing can block: no rays
  }
}

// C-14: the singular shared edge. Reciprocity W·F12(W,H) = H·F12(H,W) checks the formula.
TEST(PointPolygon, ExactPerpendicularSharedEdge) {
  EXPECT_NEAR(test::c14PerpendicularRectangles(1, 1), 0.20004377607540316, 1e-15);
  EXPECT_NEAR(test::c14PerpendicularRectangles(1, 2), 0.232853, 5e-7);
  EXPECT_NEAR(test::c14PerpendicularRectangles(2, 1), 0.116426, 5e-7);
  EXPECT_NEAR(test::c14PerpendicularRectangles(0.5, 0.5), 0.240636, 5e-7);
  EXPECT_NEAR(1 * test::c14PerpendicularRectangles(1, 2),
              2 * test::c14PerpendicularRectangles(2, 1), 1e-14);
  struct Case {
    double w, h;
    int n;
  };
  for (Case k : {Case{1, 1, 1}, Case{1, 2, 1}, Case{2, 1, 1}, Case{0.5, 0.5, 1}, Case{1, 1, 4},
                 Case{1, 2, 3}}) {
    test::MeshBuilder b = test::perpendicularRectangles(1, k.w, k.h, k.n);
    FormFactorResult r = compute(b);
    double exact = test::c14PerpendicularRectangles(k.w, k.h);
    EXPECT_NEAR(surfaceF(r, b, 0, 1), exact, 1e-4) << "W=" << k.w << " H=" << k.h << " n=" << k.n;
    EXPECT_NEAR(surfaceF(r, b, 1, 0), exact * k.w / k.h, 1e-4);
  }
}

// Coaxial disks meshed as inscribed N-gons (fans of triangles). A1F12 grows with either
// surface, so the closed form for radii r·cos(π/N) (inscribed circles) and r brackets the
// polygons' exact A1F12; the method must land inside the bracket (to its 1e-4 accuracy).
TEST(PointPolygon, ExactCoaxialDisks) {
  EXPECT_NEAR(test::coaxialDisks(1, 1, 1), (3 - std::sqrt(5.0)) / 2, 1e-15);
  EXPECT_NEAR(test::coaxialDisks(0.1, 0.2, 0.5), 0.133931, 5e-7);
  struct Case {
    double r1, r2, h;
  };
  const int sides = 48;
  for (Case k : {Case{1, 1, 1}, Case{0.1, 0.2, 0.5}, Case{1, 0.5, 0.3}}) {
    test::MeshBuilder b;
    b.addDisk("d1", {0, 0, 0}, {0, 0, 1}, k.r1, sides);
    b.addDisk("d2", {0, 0, k.h}, {0, 0, -1}, k.r2, sides);
    FormFactorResult r = compute(b);
    double c = std::cos(M_PI / sides);
    double a1 = sides * 0.5 * k.r1 * k.r1 * std::sin(2 * M_PI / sides);  // N-gon area
    double lowAF = M_PI * k.r1 * k.r1 * c * c * test::coaxialDisks(k.r1 * c, k.r2 * c, k.h);
    double highAF = M_PI * k.r1 * k.r1 * test::coaxialDisks(k.r1, k.r2, k.h);
    double af = a1 * surfaceF(r, b, 0, 1);
    EXPECT_GE(af, lowAF - 1e-4 * a1);
    EXPECT_LE(af, highAF + 1e-4 * a1);
    std::printf("[ disks ] r1=%g r2=%g h=%g N=%d  A1F12: low %.6f  ours %.6f  high %.6f\n", k.r1,
                k.r2, k.h, sides, lowAF, af, highAF);
  }
}

// Unit cube: opposite and adjacent faces, closure and reciprocity, for 1×1 and 3×3 faces.
TEST(PointPolygon, ExactCube) {
  const double opposite = 0.199824895698387, adjacent = 0.200043776075403;
  EXPECT_NEAR(opposite + 4 * adjacent, 1.0, 1e-14);
  for (int n : {1, 3}) {
    test::MeshBuilder b = test::cubeInterior(n);
    FormFactorResult r = compute(b);
    EXPECT_NEAR(surfaceF(r, b, 0, 1), opposite, 1e-4) << n;
    EXPECT_NEAR(surfaceF(r, b, 0, 2), adjacent, 1e-4) << n;
    EXPECT_NEAR(surfaceF(r, b, 4, 5), opposite, 1e-4) << n;
    EXPECT_NEAR(r.diagnostics.rowSumMin, 1.0, 1e-4) << n;
    EXPECT_NEAR(r.diagnostics.rowSumMax, 1.0, 1e-4) << n;
    EXPECT_LT(r.diagnostics.maxRelativeReciprocityError, 1e-12);
    std::printf("[ cube ] n=%d  opposite err %.2e  adjacent err %.2e  row sums [%.8f, %.8f]\n", n,
                surfaceF(r, b, 0, 1) - opposite, surfaceF(r, b, 0, 2) - adjacent,
                r.diagnostics.rowSumMin, r.diagnostics.rowSumMax);
  }
}

// Inside a sphere F_ij = A_j/A. A meshed sphere has flat facets whose normals differ from the
// sphere's by up to δ ~ edge/(2R); neighbouring facets keep an O(1) relative error (near their
// shared edge the facets are flatter than the sphere), but each row's misdirected fraction
// Σ_j |F_ij − A_j/A| falls with the facet size. Closure (row sums 1) is exact for the
// closed polyhedron.
TEST(PointPolygon, ExactSphereInterior) {
  double previous = 1;
  for (int level : {1, 2, 3}) {
    test::MeshBuilder b = test::icosphereInterior(level);
    FormFactorResult r = compute(b);
    const PatchMesh& m = b.mesh();
    double total = m.totalArea(), worst = 0;
    std::vector<double> rowError(m.size(), 0.0);
    for (int i = 0; i < m.size(); ++i)
      for (int j = 0; j < m.size(); ++j)
        rowError[i] += std::fabs(formFactorAt(r.matrix, i, j) - m.patches[j].area / total);
    for (double e : rowError) worst = std::max(worst, e);
    std::printf(
        "[ sphere ] level %d (%4d facets): max_i sum_j |F_ij - A_j/A| = %.3e, row sums "
        "[%.8f, %.8f]\n",
        level, m.size(), worst, r.diagnostics.rowSumMin, r.diagnostics.rowSumMax);
    EXPECT_NEAR(r.diagnostics.rowSumMin, 1.0, 1e-4);
    EXPECT_NEAR(r.diagnostics.rowSumMax, 1.0, 1e-4);
    EXPECT_LT(worst, 0.7 * previous);
    previous = worst;
  }
}

// Error falls as the quadrature grows: fixed rules of order 1..4 (no refinement) on C-11,
// then the adaptive rule at three tolerances on the singular C-14.
TEST(PointPolygon, ExactQuadratureConvergence) {
  test::MeshBuilder c11 = test::parallelRectangles(1, 1, 1);
  double exact = test::c11ParallelRectangles(1, 1), previous = 1;
  for (int order = 1; order <= 4; ++order) {
    FormFactorSettings s;
    s.quadrature.order = order;
    s.quadrature.maxDepth = 0;
    FormFactorResult r = compute(c11, s);
    double err = std::fabs(surfaceF(r, c11, 0, 1) - exact);
    std::printf("[ quadrature ] C-11 X=Y=1  order %d fixed  points %lld  |error| %.3e\n", order,
                r.diagnostics.quadraturePoints, err);
    EXPECT_LT(err, previous);
    previous = err;
  }
  test::MeshBuilder c14 = test::perpendicularRectangles(1, 1, 1);
  exact = test::c14PerpendicularRectangles(1, 1);
  previous = 1;
  for (double tol : {1e-2, 1e-4, 1e-6, 1e-8}) {
    FormFactorSettings s;
    s.quadrature.tolerance = tol;
    s.quadrature.maxDepth = 20;
    FormFactorResult r = compute(c14, s);
    double err = std::fabs(surfaceF(r, c14, 0, 1) - exact);
    std::printf("[ quadrature ] C-14 W=H=1  tolerance %.0e  points %lld  |error| %.3e\n", tol,
                r.diagnostics.quadraturePoints, err);
    // Non-increasing: a loose tolerance may already accept the first cells' answer.
    EXPECT_LE(err, std::max(previous, 1e-12));
    EXPECT_LT(err, tol);
    previous = err;
  }
}

namespace {
/// Unit squares one apart (C-11, X = Y = 1) and a blocker in the plane z = 1/2 covering
/// x < xEdge (and all y): the squares are patches 0 and 1.
test::MeshBuilder blockedSquares(double xEdge) {
  test::MeshBuilder b = test::parallelRectangles(1, 1, 1);
  b.addRectangle("blocker", {-5, -5, 0.5}, {xEdge + 5, 0, 0}, {0, 11, 0});
  return b;
}
}  // namespace

// A blocker covering x < 1/2 at mid-height blocks the segment (x1, x2) exactly when
// x1 + x2 < 1; the reflection x → 1 − x maps blocked onto unblocked pairs and keeps the
// kernel, so exactly half of F survives: F = C-11(1,1)/2. A blocker over everything leaves 0.
TEST(PointPolygon, ExactOcclusion) {
  test::MeshBuilder full = blockedSquares(6);
  FormFactorResult r = compute(full);
  EXPECT_EQ(formFactorAt(r.matrix, 0, 1), 0.0);
  EXPECT_EQ(formFactorAt(r.matrix, 1, 0), 0.0);
  EXPECT_GT(r.diagnostics.raysCast, 0);

  test::MeshBuilder half = blockedSquares(0.5);
  FormFactorSettings s;
  s.samples = 256;
  BruteForceVisibility brute(half.mesh());
  RayScene embree(half.mesh());
  FormFactorResult a = computeFormFactors(half.mesh(), brute, s);
  FormFactorResult e = computeFormFactors(half.mesh(), embree, s);
  double exact = test::c11ParallelRectangles(1, 1) / 2;
  // Visible fraction from 256 stratified segments: binomial bound, 4 standard errors.
  EXPECT_NEAR(formFactorAt(a.matrix, 0, 1), exact, 4 * 2 * exact * std::sqrt(0.25 / 256));
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      EXPECT_EQ(formFactorAt(a.matrix, i, j), formFactorAt(e.matrix, i, j)) << i << "," << j;
}

// Error falls as K grows: mean |F − exact| over 16 seeds for the half-blocked squares.
TEST(PointPolygon, StatisticalVisibilityConvergence) {
  test::MeshBuilder half = blockedSquares(0.5);
  RayScene embree(half.mesh());
  double exact = test::c11ParallelRectangles(1, 1) / 2, previous = 1;
  for (int K : {4, 16, 64, 256}) {
    double sum = 0;
    const int seeds = 16;
    for (int seed = 1; seed <= seeds; ++seed) {
      FormFactorSettings s;
      s.samples = K;
      s.seed = std::uint64_t(seed);
      FormFactorResult r = computeFormFactors(half.mesh(), embree, s);
      sum += std::fabs(formFactorAt(r.matrix, 0, 1) - exact);
    }
    double err = sum / seeds;
    std::printf("[ visibility ] half-blocked C-11  K=%3d  mean |error| over %d seeds %.3e\n", K,
                seeds, err);
    EXPECT_LT(err, previous);
    previous = err;
  }
}

}  // namespace radkit

#include "radiosity/occluder_culling.h"

namespace radkit {
// Rows ask the culling once per (patch, surface); "nothing can block" there must imply it
// for every pair of that surface. A room with a box inside and a crumpled (non-planar)
// sheet: both answers occur, and no pair the surface test dismisses is blockable.
TEST(PointPolygon, SurfaceCullingImpliesPairCulling) {
  test::MeshBuilder builder = test::cubeInterior(4);
  const Vec3 lo{0.3, 0.3, 0}, e{0.3, 0, 0}, f{0, 0.3, 0}, up{0, 0, 0.4};
  builder.addRectangle("box side", lo, e, up, 2, 2);
  builder.addRectangle("box top", lo + up, e, f, 2, 2);
  builder.addTriangles("sheet", {{0.7, 0.7, 0.5},
                                 {0.9, 0.7, 0.6},
                                 {0.7, 0.9, 0.6},
                                 {0.9, 0.7, 0.6},
                                 {0.9, 0.9, 0.5},
                                 {0.7, 0.9, 0.6}});
  const PatchMesh& mesh = builder.mesh();
  PatchTable table(mesh);
  OccluderCulling culling(mesh, table);
  ASSERT_EQ(culling.surfaceCount(), int(mesh.surfaceBegin.size()) - 1);
  int clear = 0, maybe = 0;
  for (int i = 0; i < table.size(); ++i)
    for (int s = 0; s < culling.surfaceCount(); ++s) {
      if (culling.mayBeBlockedFromSurface(i, s)) {
        ++maybe;
        continue;
      }
      ++clear;
      for (int j = mesh.surfaceBegin[s]; j < mesh.surfaceBegin[s + 1]; ++j)
        if (j != i) {
          EXPECT_FALSE(culling.mayBeBlocked(i, j)) << i << " " << j;
        }
    }
  EXPECT_GT(clear, 50);
  EXPECT_GT(maybe, 50);
}
}  // namespace radkit

namespace radkit {
namespace {

// The method's own parameters: "pair_levels=0" in FormFactorSettings::parameters (the text of
// --ff point-polygon:pair_levels=0) is the --ff-pair-levels 0 of the settings, row for row;
// a key the method does not read is refused naming the keys it does, and so is a key given to
// a method that reads none.
TEST(PointPolygon, ExactItsOwnParameterEqualsTheSettingAndUnknownKeysAreRefused) {
  // Small squares far apart: the default picks a tensor rule, level 0 the contour cubature.
  test::MeshBuilder b = test::parallelRectangles(0.2, 0.2, 2);
  RayScene scene(b.mesh());
  FormFactorSettings bySetting, byParameter;
  bySetting.quadrature.pairLevels = 0;
  byParameter.parameters = "pair_levels=0";
  RowResult a, c;
  makeFormFactorMethod(b.mesh(), scene, bySetting)->computeRow(0, a);
  makeFormFactorMethod(b.mesh(), scene, byParameter)->computeRow(0, c);
  ASSERT_EQ(a.entries.size(), c.entries.size());
  for (std::size_t k = 0; k < a.entries.size(); ++k)
    EXPECT_EQ(a.entries[k].value, c.entries[k].value);
  EXPECT_EQ(a.pairsByRule[0], c.pairsByRule[0]);
  RowResult d;
  makeFormFactorMethod(b.mesh(), scene, FormFactorSettings{})->computeRow(0, d);
  EXPECT_NE(d.pairsByRule[0], c.pairsByRule[0]);

  FormFactorSettings typo;
  typo.parameters = "pair_level=3";
  try {
    makeFormFactorMethod(b.mesh(), scene, typo);
    ADD_FAILURE() << "pair_level accepted";
  } catch (const ParamError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("form-factor method \"point-polygon\""), std::string::npos) << what;
    EXPECT_NE(what.find("pair_levels"), std::string::npos) << what;
  }
  FormFactorSettings range;
  range.parameters = "pair_levels=9";
  EXPECT_THROW(makeFormFactorMethod(b.mesh(), scene, range), ParamError);
  FormFactorSettings none;
  none.method = "monte-carlo";
  none.parameters = "pair_levels=2";
  EXPECT_THROW(makeFormFactorMethod(b.mesh(), scene, none), ParamError);
  const PluginChoice choice = splitPluginChoice("point-polygon:pair_levels=2;x=1");
  EXPECT_EQ(choice.name, "point-polygon");
  EXPECT_EQ(choice.parameters, "pair_levels=2,x=1");
}

}  // namespace
}  // namespace radkit
