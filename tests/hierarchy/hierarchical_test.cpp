// Hierarchical radiosity against oracles nobody on the team wrote: the dense solution of the
// same leaves, the furnace B = E/(1 − ρ) (docs/hierarchical.md), Howell's C-11 view factor
// through cluster links, and determinism across thread counts.
#include <gtest/gtest.h>

#include <tbb/global_control.h>
#include <array>
#include <cmath>
#include <map>

#include "geometry/ray_scene.h"
#include "geometry/scene_loader.h"
#include "hierarchy/hierarchical.h"
#include "hierarchy/link_matrix.h"
#include "hierarchy/refine.h"
#include "radiosity/contour.h"
#include "radiosity/radiosity_pipeline.h"
#include "tests/common/test_util.h"
#include "tests/radiosity/test_scenes.h"
#include "util/sampling.h"

namespace radkit {
namespace {

/// A scene built in code: materials by name, rectangles split into nu×nv input faces (so the
/// cluster tree has something to group).
struct SceneBuilder {
  Scene scene;
  SceneBuilder() {
    scene.name = "test";
    scene.file = "test.json";
  }
  int material(const std::string& name, Vec3 rho, Vec3 emission) {
    Material m;
    m.name = name, m.emission = emission;
    m.params.set("reflectance", rho);
    resolveMaterial(m);
    scene.materials.push_back(m);
    return static_cast<int>(scene.materials.size()) - 1;
  }
  void rectangle(const std::string& name, int material, Vec3 corner, Vec3 e1, Vec3 e2, int nu,
                 int nv) {
    Surface s;
    s.name = name, s.material = material, s.source = "test: " + name;
    for (int b = 0; b <= nv; ++b)
      for (int a = 0; a <= nu; ++a)
        s.vertices.push_back(corner + e1 * (double(a) / nu) + e2 * (double(b) / nv));
    for (int b = 0; b < nv; ++b)
      for (int a = 0; a < nu; ++a) {
        int v = b * (nu + 1) + a;
        s.faces.push_back(Face{{v, v + 1, v + nu + 2, v + nu + 1}});
      }
    scene.surfaces.push_back(s);
  }
  /// The unit cube's six faces facing inwards (normal e1 × e2), n×n input faces each.
  void cube(int n, int walls, int top) {
    rectangle("bottom", walls, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, n, n);
    rectangle("top", top, {0, 0, 1}, {0, 1, 0}, {1, 0, 0}, n, n);
    rectangle("y0", walls, {0, 0, 0}, {0, 0, 1}, {1, 0, 0}, n, n);
    rectangle("y1", walls, {0, 1, 0}, {1, 0, 0}, {0, 0, 1}, n, n);
    rectangle("x0", walls, {0, 0, 0}, {0, 1, 0}, {0, 0, 1}, n, n);
    rectangle("x1", walls, {1, 0, 0}, {0, 0, 1}, {0, 1, 0}, n, n);
  }
};

double maxRelativeDifference(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  double worst = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    for (int c = 0; c < 3; ++c)
      worst = std::max(worst, std::fabs(a[i][c] - b[i][c]) / std::fabs(b[i][c]));
  return worst;
}

TEST(Hierarchy, ClusterTreeBoundsEveryFaceBelowIt) {
  SceneBuilder b;
  int grey = b.material("grey", {0.5, 0.5, 0.5}, {});
  b.cube(3, grey, grey);
  PatchMesh base = subdivide(b.scene, {});
  Hierarchy h(base, std::vector<SurfaceRadiometry>(6, {{0.5, 0.5, 0.5}, {}}));
  ASSERT_EQ(h.size(), 2 * base.size() - 1);
  for (int f = 0; f < base.size(); ++f) {
    int n = h.faceNode(f);
    EXPECT_TRUE(h[n].element);
    // Every ancestor's sphere holds the face's vertices and its cone the face's normal.
    for (int a = h[n].parent; a >= 0; a = h[a].parent) {
      for (int k = 0; k < h.polygon(n).count; ++k)
        EXPECT_LE(length(h.polygon(n).v[k] - h[a].centre), h[a].radius * (1 + 1e-12));
      EXPECT_GE(dot(h[a].coneAxis, base.patches[f].normal), std::cos(h[a].coneAngle) - 1e-12);
    }
  }
  EXPECT_NEAR(h[h.root()].area, 6.0, 1e-12);
  // A split element's quarters tile it.
  int face = h.faceNode(0);
  h.split(face);
  double quarters = 0;
  for (int k = 0; k < 4; ++k) quarters += h[h.child(face, k)].area;
  EXPECT_NEAR(quarters, h[face].area, 1e-15);
}

/// As ε falls, the hierarchy's answer approaches the dense solution on its own leaves: at
/// small ε every link is a leaf-to-leaf link with the dense method's form factor.
void expectApproachesDense(const Scene& scene, double minArea) {
  std::vector<double> errors;
  for (double eps : {1e-2, 1e-3, 1e-5}) {
    HierarchicalSettings s;
    s.epsilon = eps;
    s.minArea = minArea;
    s.stopping.tolerance = 1e-10;
    HierarchicalResult hr = solveHierarchical(scene, s);
    PipelineSettings dense;
    dense.stopping.tolerance = 1e-10;
    PipelineResult d = runPipeline(scene, hr.leaves, dense);
    errors.push_back(maxRelativeDifference(hr.radiosity, d.radiosity));
    std::printf(
        "epsilon %g: %d leaves, max relative difference from dense on the same leaves %.3g\n", eps,
        hr.leaves.size(), errors.back());
  }
  EXPECT_LT(errors[1], errors[0]);
  EXPECT_LT(errors[2], errors[1]);
  // The floor: element links integrate F to 1e-3 relative, the dense method to 1e-6 absolute.
  EXPECT_LT(errors[2], 1e-4) << "at epsilon 1e-5 the links are leaf links";
}

TEST(Hierarchical, ApproachesTheDenseSolutionOfItsLeavesAsEpsilonFalls) {
  SceneBuilder cube;
  int walls = cube.material("walls", {0.6, 0.5, 0.4}, {});
  int lamp = cube.material("lamp", {0.3, 0.3, 0.3}, {1, 1, 1});
  cube.cube(2, walls, lamp);
  expectApproachesDense(cube.scene, 1.0 / 64);  // leaves of at least 1/8 × 1/8

  // Howell's C-11 pair: unit squares one apart, 4×4 faces each, the upper one emitting.
  SceneBuilder squares;
  int grey = squares.material("grey", {0.7, 0.7, 0.7}, {});
  int glow = squares.material("glow", {0.5, 0.5, 0.5}, {1, 1, 1});
  squares.rectangle("lower", grey, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 4, 4);
  squares.rectangle("upper", glow, {0, 0, 1}, {0, 1, 0}, {1, 0, 0}, 4, 4);
  expectApproachesDense(squares.scene, 1.0 / 256);
}

/// Closed cube, uniform ρ = 0.95 and E = 1, faces split into 8×8 input faces so that cluster
/// links carry light: B = E/(1 − ρ) = 20 everywhere (Cohen & Wallace 1993; the furnace). Every
/// leaf's hemisphere is closed, so the enclosure rule holds for each and the answer is exact to
/// the solver's tolerance at a coarse ε too.
TEST(Hierarchical, FurnaceWithClusters) {
  SceneBuilder b;
  int glow = b.material("glow", {0.95, 0.95, 0.95}, {1, 1, 1});
  b.cube(8, glow, glow);
  HierarchicalSettings s;
  s.epsilon = 1e-3;
  s.stopping.tolerance = 1e-10;
  HierarchicalResult hr = solveHierarchical(b.scene, s);
  EXPECT_GT(hr.linksByKind[static_cast<int>(LinkKind::ClusterCluster)], 0);
  EXPECT_EQ(hr.system->normalisedLeaves(), hr.leaves.size());
  EXPECT_GT(hr.system->largestRowSumError(), 1e-3) << "the links alone are not exact";
  for (const Vec3& v : hr.radiosity) EXPECT_NEAR(v.y, 20.0, 20.0 * 1e-8);
  // The balance's escape is estimated by rays (a few slip through seams): within 4 of its
  // standard errors.
  EXPECT_LT(hr.energy.relativeImbalance,
            4 * hr.escapedStandardError.y / hr.energy.emitted.y + 1e-9);
}

/// The furnace again with a box (five faces, open below) resting on the floor: every leaf that
/// sees the enclosure has B = E/(1 − ρ) = 20; the floor under the box sees only the backs of the
/// box's faces, gets no light and keeps B = E = 1. Its rays must not open the floor (then no
/// floor leaf would be normalised), and light gathered by coarse floor elements must go to the
/// part of them that is seen, not to the leaves under the box.
TEST(Hierarchical, FurnaceWithABoxOnTheFloor) {
  SceneBuilder b;
  int glow = b.material("glow", {0.95, 0.95, 0.95}, {1, 1, 1});
  b.cube(4, glow, glow);
  const double lo = 0.25, hi = 0.75, top = 0.4;  // on the floor faces' edges
  b.rectangle("box top", glow, {lo, lo, top}, {hi - lo, 0, 0}, {0, hi - lo, 0}, 2, 2);
  b.rectangle("box y0", glow, {lo, lo, 0}, {hi - lo, 0, 0}, {0, 0, top}, 2, 1);
  b.rectangle("box y1", glow, {lo, hi, 0}, {0, 0, top}, {hi - lo, 0, 0}, 1, 2);
  b.rectangle("box x0", glow, {lo, lo, 0}, {0, 0, top}, {0, hi - lo, 0}, 1, 2);
  b.rectangle("box x1", glow, {hi, lo, 0}, {0, hi - lo, 0}, {0, 0, top}, 2, 1);
  HierarchicalSettings s;
  s.epsilon = 1e-3;
  s.stopping.tolerance = 1e-10;
  HierarchicalResult hr = solveHierarchical(b.scene, s);
  int under = 0;
  for (int i = 0; i < hr.leaves.size(); ++i) {
    const Patch& p = hr.leaves.patches[i];
    const bool covered = p.centroid.z < 1e-9 && p.centroid.x > lo && p.centroid.x < hi &&
                         p.centroid.y > lo && p.centroid.y < hi;
    under += covered;
    EXPECT_NEAR(hr.radiosity[i].y, covered ? 1.0 : 20.0, 20.0 * 1e-8)
        << "leaf " << i << " at (" << p.centroid.x << ", " << p.centroid.y << ", " << p.centroid.z
        << ")";
  }
  EXPECT_GT(under, 0);
  EXPECT_EQ(hr.system->normalisedLeaves(), hr.leaves.size() - under);
}

/// A closed box at ρ = 0.999999 sends out 10⁶ times what it emits. With τ a share of the
/// emitted power alone every link's error (which grows with B) exceeded it, and refinement ran
/// for minutes toward the memory budget (2 M links at 120 s); τ now follows the light leaving
/// the surfaces, so the default settings end with few links and say why the solve stopped.
TEST(Hierarchical, NearSingularBoxRefinesBoundedly) {
  SceneBuilder b;
  int glow = b.material("glow", {0.999999, 0.999999, 0.999999}, {1, 1, 1});
  b.cube(2, glow, glow);
  HierarchicalSettings s;
  s.stopping.maxIterations = 2000;
  HierarchicalResult hr = solveHierarchical(b.scene, s);
  long long links = 0;
  for (long long k : hr.linksByKind) links += k;
  EXPECT_LT(links, 1000000);
  EXPECT_FALSE(hr.solve.exit.empty());
  EXPECT_GT(hr.threshold, 100 * s.epsilon * 6.0)
      << "tau should follow the light leaving the surfaces";
  std::printf("near-singular box: %lld links, %d leaves, exit %s, tau %.3g\n", links,
              hr.leaves.size(), hr.solve.exit.c_str(), hr.threshold);
}

/// The solve after that refinement needs log(1e-6)/log(0.999999) ≈ 13.8 M sweeps: every leaf of
/// the furnace is closed and normalised to a row sum of 1, so B stays uniform and the Jacobi
/// gather's change falls by exactly ρ per sweep (spectral radius 0.999999). It used to sweep
/// to the limit; now, once the rate is stable (three windows of kRateWindowSweeps after the
/// round's links are made, the first without a rate), it stops as predicted_over_budget with a
/// prediction within 1 % of log(tol/change)/log(ρ). Gauss-Seidel blocks stop alike.
TEST(Hierarchical, NearSingularBoxStopsWhenPredictedOverBudget) {
  const double rho = 0.999999;
  SceneBuilder b;
  int glow = b.material("glow", {rho, rho, rho}, {1, 1, 1});
  b.cube(2, glow, glow);
  HierarchicalSettings s;
  s.rounds = 1;
  s.epsilon = 1e-2;
  s.raysPerLink = 4;
  s.stopping.maxIterations = 20000;  // the default, 10⁵, would be no faster; 10⁸ used to be it
  HierarchicalResult hr = solveHierarchical(b.scene, s);
  EXPECT_EQ(hr.solve.exit, "predicted_over_budget") << hr.solve.reason;
  EXPECT_FALSE(hr.solve.converged);
  EXPECT_EQ(hr.solve.iterations, 3 * kRateWindowSweeps);
  EXPECT_NEAR(hr.solve.spectralRadius, rho, 1e-9);
  const double analytic = std::log(s.stopping.tolerance / hr.solve.residual) / std::log(rho);
  EXPECT_NEAR(hr.solve.predictedSweeps / analytic, 1.0, 0.01) << hr.solve.predictedSweeps;
  EXPECT_NE(hr.solve.reason.find("--max-iterations 20000 leaves"), std::string::npos)
      << hr.solve.reason;
  EXPECT_EQ(hr.solve.history.back().iteration, hr.solve.iterations);
  for (const Vec3& v : hr.radiosity) EXPECT_TRUE(std::isfinite(v.y) && v.y > 1.0);

  s.order = GatherOrder::GaussSeidel;
  hr = solveHierarchical(b.scene, s);
  EXPECT_EQ(hr.solve.exit, "predicted_over_budget") << hr.solve.reason;
  EXPECT_LT(hr.solve.iterations, 1000);
}

/// An open scene: nothing is normalised, and a row sum far above 1 (a coarse ε between nearby
/// clusters) is capped so the solve still converges at ρ = 0.99.
TEST(Hierarchical, OpenSceneNearUnitReflectanceConverges) {
  SceneBuilder b;
  int white = b.material("white", {0.99, 0.99, 0.99}, {});
  int lamp = b.material("lamp", {0, 0, 0}, {10, 10, 10});
  b.rectangle("floor", white, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 8, 8);
  b.rectangle("wall", white, {0, 1, 0}, {1, 0, 0}, {0, 0, 1}, 8, 8);
  b.rectangle("lamp", lamp, {0.4, 0.4, 0.8}, {0, 0.2, 0}, {0.2, 0, 0}, 1, 1);
  HierarchicalSettings s;
  s.epsilon = 1e-2;
  HierarchicalResult hr = solveHierarchical(b.scene, s);
  EXPECT_TRUE(hr.solve.converged) << hr.solve.reason;
  EXPECT_EQ(hr.system->normalisedLeaves(), 0);
  for (const Vec3& v : hr.radiosity) EXPECT_TRUE(std::isfinite(v.x) && v.x >= 0);
}

/// Howell C-11 through cluster links: a 1×1 emitter split into 16×16 faces (a cluster) five
/// units from a 1×1 receiver kept whole. The receiver's irradiance per unit emitter radiosity
/// is F_12 = 2/(πXY){...} at X = Y = 0.2 (Howell's catalogue, C-11); each link gathered may err
/// by τ/(ρ A) in irradiance (the oracle's promise), and the error falls with ε.
TEST(Hierarchical, ViewFactorThroughClusterLinksWithinTheLinkBound) {
  SceneBuilder b;
  int lamp = b.material("lamp", {0, 0, 0}, {1, 1, 1});
  int target = b.material("target", {0.5, 0.5, 0.5}, {});
  b.rectangle("emitter", lamp, {0, 0, 5}, {0, 1, 0}, {1, 0, 0}, 16, 16);
  b.rectangle("receiver", target, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 1, 1);
  const double exact = test::c11ParallelRectangles(0.2, 0.2);
  std::vector<double> errors;
  for (double eps : {1e-2, 1e-3, 1e-5}) {
    HierarchicalSettings s;
    s.epsilon = eps;
    s.minArea = 0.5;  // the receiver stays one element
    HierarchicalResult hr = solveHierarchical(b.scene, s);
    ASSERT_EQ(hr.leaves.surfaceBegin[2] - hr.leaves.surfaceBegin[1], 1);
    const int leaf = hr.leaves.surfaceBegin[1];
    const int node = hr.leafNodes[leaf];
    int clusterLinks = 0;
    for (const HLink& l : hr.system->links())
      clusterLinks += l.receiver == node && !(*hr.hierarchy)[l.source].element;
    if (eps == 1e-2) {
      EXPECT_GT(clusterLinks, 0) << "the emitter should be reached through clusters";
    }
    const double bound = hr.system->linkCount(node) * hr.threshold / 0.5;  // receiver area 1
    EXPECT_NEAR(hr.irradiance[leaf].x, exact, bound) << "epsilon " << eps;
    errors.push_back(std::fabs(hr.irradiance[leaf].x - exact) / exact);
  }
  EXPECT_LT(errors[2], errors[0]);
  EXPECT_LT(errors[2], 1e-3);
}

/// Partly blocked links, few rays: the visible share is estimated from K = 4 rays per link, and
/// which links are kept or dropped depends on rays too. Kept values come from rays independent
/// of those choices, blocked links are dropped by Russian roulette, and the visible share is a
/// control-variate estimate, so the power reaching a partly shadowed receiver is unbiased: over
/// 16 seeds its mean agrees with a Monte Carlo reference (10⁷ cosine rays from the emitter)
/// within 4 standard errors of the difference. (Dropping every link whose rays were all
/// blocked gave 1.8 % too little light here, 6 % when earlier rounds kept them.)
TEST(Hierarchical, ShadowedPowerIsUnbiasedWithFewRays) {
  SceneBuilder b;
  int lamp = b.material("lamp", {0, 0, 0}, {1, 1, 1});
  int grey = b.material("grey", {0.5, 0.5, 0.5}, {});
  int black = b.material("black", {0, 0, 0}, {});
  b.rectangle("emitter", lamp, {0, 0, 1}, {0, 1, 0}, {1, 0, 0}, 4, 4);
  b.rectangle("receiver", grey, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 4, 4);
  b.rectangle("blocker", black, {0.15, 0.2, 0.45}, {0, 0.45, 0}, {0.5, 0, 0}, 2, 2);

  // Reference: the share of the emitter's power whose first hit is the receiver's front.
  PatchMesh base = subdivide(b.scene, {});
  RayScene rays(base);
  Rng rng(7, 0, 0);
  const long N = 10000000;
  long hits = 0;
  Frame down({0, 0, -1});
  for (long k = 0; k < N; ++k) {
    Vec3 x{rng.uniform(), rng.uniform(), 1.0};
    Vec3 d = down.toWorld(sampleCosineHemisphere(rng.uniform(), rng.uniform()));
    std::optional<RayHit> hit = rays.closestHit(x, d, 1e-6);  // past the emitter itself
    hits += hit && base.patches[hit->patch].surface == 1 && d.z < 0;
  }
  const double p = double(hits) / N, reference = p, referenceSe = std::sqrt(p * (1 - p) / N);

  std::vector<double> power;
  for (std::uint64_t seed = 1; seed <= 16; ++seed) {
    HierarchicalSettings s;
    s.epsilon = 1e-3;
    s.raysPerLink = 4;
    s.seed = seed;
    HierarchicalResult hr = solveHierarchical(b.scene, s);
    double sum = 0;
    for (int i = hr.leaves.surfaceBegin[1]; i < hr.leaves.surfaceBegin[2]; ++i)
      sum += hr.leaves.patches[i].area * hr.irradiance[i].x;
    power.push_back(sum);  // emitter power is 1 (unit area, E = 1)
  }
  double mean = 0, var = 0;
  for (double v : power) mean += v / power.size();
  for (double v : power) var += (v - mean) * (v - mean) / (power.size() - 1);
  const double se = std::sqrt(var / power.size() + referenceSe * referenceSe);
  std::printf(
      "receiver's share of the emitted power: hierarchy %.5f (16 seeds, sd %.5f), reference %.5f "
      "+- %.5f\n",
      mean, std::sqrt(var), reference, referenceSe);
  EXPECT_GT(reference, 0.1);
  EXPECT_LT(reference, 0.19) << "the blocker should shadow part of the receiver";
  EXPECT_NEAR(mean, reference, 4 * se);
}

TEST(Hierarchical, SameSeedSameBitsForAnyThreadCount) {
  SceneBuilder b;
  int walls = b.material("walls", {0.7, 0.6, 0.5}, {});
  int lamp = b.material("lamp", {0.2, 0.2, 0.2}, {5, 5, 5});
  b.cube(5, walls, lamp);
  b.rectangle("blocker", walls, {0.3, 0.3, 0.5}, {0.4, 0, 0}, {0, 0.4, 0}, 3, 3);
  HierarchicalSettings s;
  s.epsilon = 1e-3;
  s.rounds = 1;  // one set of links, so both orderings solve the same system
  s.stopping.tolerance = 1e-9;
  std::vector<std::vector<Vec3>> answers;
  for (GatherOrder order : {GatherOrder::Jacobi, GatherOrder::GaussSeidel})
    for (int threads : {1, 2}) {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
      s.order = order;
      answers.push_back(solveHierarchical(b.scene, s).radiosity);
    }
  ASSERT_EQ(answers[0].size(), answers[1].size());
  for (std::size_t i = 0; i < answers[0].size(); ++i) {
    EXPECT_EQ(answers[0][i], answers[1][i]) << "Jacobi, leaf " << i;
    EXPECT_EQ(answers[2][i], answers[3][i]) << "Gauss-Seidel, leaf " << i;
  }
  // Both orderings solve the same system.
  ASSERT_EQ(answers[0].size(), answers[2].size());
  EXPECT_LT(maxRelativeDifference(answers[2], answers[0]), 1e-7);
}

TEST(Hierarchical, GaussSeidelNeedsNoMoreSweepsThanJacobi) {
  SceneBuilder b;
  int walls = b.material("walls", {0.8, 0.8, 0.8}, {});
  int lamp = b.material("lamp", {0.2, 0.2, 0.2}, {5, 5, 5});
  b.cube(4, walls, lamp);
  HierarchicalSettings s;
  s.rounds = 1;
  s.epsilon = 1e-3;
  s.stopping.tolerance = 1e-8;
  s.order = GatherOrder::Jacobi;
  long jacobi = solveHierarchical(b.scene, s).solve.iterations;
  s.order = GatherOrder::GaussSeidel;
  long gaussSeidel = solveHierarchical(b.scene, s).solve.iterations;
  EXPECT_LE(gaussSeidel, jacobi);
}

TEST(Hierarchical, BadSettingsNameTheOptionAndTheFix) {
  SceneBuilder b;
  int lamp = b.material("lamp", {0.5, 0.5, 0.5}, {1, 1, 1});
  b.cube(1, lamp, lamp);
  auto message = [&](HierarchicalSettings s) -> std::string {
    try {
      solveHierarchical(b.scene, s);
    } catch (const std::exception& e) {
      return e.what();
    }
    return "";
  };
  HierarchicalSettings s;
  s.epsilon = 0;
  EXPECT_NE(message(s).find("--epsilon"), std::string::npos);
  s.epsilon = NAN;
  EXPECT_NE(message(s).find("--epsilon"), std::string::npos);
  s = {};
  s.minArea = 100;
  EXPECT_NE(message(s).find("--min-area"), std::string::npos);
  s = {};
  s.memoryBudget = 1024;
  std::string m = message(s);
  EXPECT_NE(m.find("--memory-budget"), std::string::npos) << m;
  EXPECT_NE(m.find("--epsilon"), std::string::npos) << m;

  SceneBuilder dark;
  int grey = dark.material("grey", {0.5, 0.5, 0.5}, {});
  dark.cube(1, grey, grey);
  try {
    solveHierarchical(dark.scene, HierarchicalSettings{});
    ADD_FAILURE() << "a scene without light must be refused";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("emission"), std::string::npos);
  }
}

}  // namespace

/// A closed curved mesh (an icosphere of 1 280 triangles, faces in every direction) inside a
/// closed cube, all ρ = 0.9 and E = 1: the furnace B = E/(1 − ρ) = 10 on every leaf of both.
/// Cluster links between the sphere's clusters and the walls deliver light from every side;
/// summing it as one irradiance vector per cluster cancelled it (closed models lost half their
/// light or the solve diverged).
TEST(Hierarchical, FurnaceAroundAClosedCurvedMesh) {
  SceneBuilder b;
  int glow = b.material("glow", {0.9, 0.9, 0.9}, {1, 1, 1});
  b.cube(4, glow, glow);
  Surface sphere;
  sphere.name = "sphere", sphere.material = glow, sphere.source = "test: sphere";
  std::vector<Vec3> v;
  std::vector<std::array<int, 3>> f;
  test::unitIcosphere(3, v, f);
  for (const Vec3& p : v) sphere.vertices.push_back(Vec3{0.5, 0.5, 0.5} + p * 0.25);
  for (auto t : f) sphere.faces.push_back({{t[0], t[1], t[2]}});  // counter-clockwise outside
  ASSERT_EQ(sphere.faces.size(), 1280u);
  b.scene.surfaces.push_back(sphere);
  HierarchicalSettings s;
  s.epsilon = 1e-3;
  s.stopping.tolerance = 1e-10;
  HierarchicalResult hr = solveHierarchical(b.scene, s);
  ASSERT_TRUE(hr.solve.converged) << hr.solve.reason;
  EXPECT_GT(hr.linksByKind[static_cast<int>(LinkKind::ClusterCluster)], 0);
  for (int i = 0; i < hr.leaves.size(); ++i)
    EXPECT_NEAR(hr.radiosity[i].y, 10.0, 10.0 * 1e-6)
        << "leaf " << i << " of " << b.scene.surfaces[hr.leaves.patches[i].surface].name;
}

/// Spot (Keenan Crane's cow, CC0, data/models) in a closed room under a lamp, the defaults,
/// against a photon tally of the same scene that nobody's links took part in:
/// `radkit photons data/models/spot-room.json --no-radiosity --photons 8000000 --seed 7`
/// (standard errors 0.03-0.14 % of each value). Before cluster links were resolved into facing
/// nodes this run diverged. The bound is the method's target (3 % per surface and channel,
/// docs/hierarchical.md); the photon noise is 20 times smaller.
TEST(Hierarchical, RealModelInAClosedRoomMatchesPhotons) {
  Scene scene = loadScene(test::dataPath("models/spot-room.json"));
  HierarchicalResult hr = solveHierarchical(scene, HierarchicalSettings{});
  ASSERT_TRUE(hr.solve.converged) << hr.solve.reason;
  const std::map<std::string, Vec3> photons{
      {"floor", {0.15368015722, 0.13454332207, 0.10030417133}},
      {"ceiling", {0.10951081217, 0.10373236786, 0.06809505550}},
      {"red wall", {0.19567682808, 0.04211540493, 0.03508567941}},
      {"green wall", {0.04334421795, 0.19003716188, 0.03510759886}},
      {"back wall", {0.18947352310, 0.18398990977, 0.14856657475}},
      {"front wall", {0.19071779085, 0.18519352651, 0.14975771089}},
      {"model", {0.17050463499, 0.16407412295, 0.13335733244}}};
  int checked = 0;
  for (const SurfaceResult& r : hr.surfaces) {
    auto it = photons.find(r.name);
    if (it == photons.end()) continue;
    ++checked;
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(r.radiosity[c] / it->second[c], 1.0, 0.03) << r.name << " channel " << c;
  }
  EXPECT_EQ(checked, 7);
  EXPECT_LT(hr.energy.relativeImbalance, 0.005);
}

}  // namespace radkit
