// The worked examples of docs/extending.md build and work: the damped-Jacobi solver against a
// closed form, the centroid form factor against Howell's C-11, Schlick's phase function against
// its normalisation and mean cosine. (The BSDF example is bsdf/oren_nayar.cpp, registered and
// tested in tests/bsdf/.)
#include <gtest/gtest.h>

#include <cmath>

#include "geometry/ray_scene.h"
#include "geometry/scene_loader.h"
#include "geometry/subdivision.h"
#include "integrators/integrator.h"
#include "phase/phase_function.h"
#include "radiosity/form_factor_method.h"
#include "solvers/solver.h"
#include "tests/common/test_util.h"
#include "tests/solvers/analytic_systems.h"
#include "util/registry.h"
#include "util/sampling.h"

namespace radkit {

std::unique_ptr<Solver> makeDampedJacobiSolver(Params& params);
std::unique_ptr<FormFactorMethod> createCentroid(Params& params, const PatchMesh&,
                                                 const Visibility&, const FormFactorSettings&);
std::unique_ptr<PhaseFunction> createSchlickPhase(Params& params);
std::unique_ptr<Integrator> createAmbientOcclusion(Params& params);

namespace {

TEST(ExtendingExamples, ExactDampedJacobiSolvesTheSphereInterior) {
  // Inside a sphere F_ij = A_j/A, so with uniform ρ and E every patch has B = E/(1 − ρ)
  // (Cohen & Wallace 1993; docs/oracles.md, closed-form systems).
  const std::vector<double> area{1, 2, 3, 4};
  test::Problem p = test::makeProblem(test::sphereFormFactors(area), area,
                                      test::grey({0.6, 0.6, 0.6, 0.6}), test::grey({1, 1, 1, 1}));
  Params params({{"omega", 0.7}});
  std::unique_ptr<Solver> solver = makeDampedJacobiSolver(params);
  params.rejectUnused("damped-jacobi");
  SolverSettings settings;
  settings.tolerance = 1e-13;
  solve(*solver, p.system, settings);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(solver->radiosity()[0][i], 1 / (1 - 0.6), 1e-11);
  Params bad({{"omega", 1.5}});
  EXPECT_THROW(makeDampedJacobiSolver(bad), std::invalid_argument);
}

TEST(ExtendingExamples, ExactCentroidFormFactorConvergesToHowellC11) {
  // Unit squares one apart: F = 0.19982489569838746 (Howell C-11, X = Y = 1). The centroid
  // rule integrates over patch i with one point per patch: its error falls as patches shrink.
  const Scene scene = loadScene(test::dataPath("parallel-squares.json"));
  double previous = 1;
  for (int patches : {8, 32, 128}) {
    const PatchMesh mesh = subdivide(scene, {0, patches});
    const RayScene rays(mesh);
    Params none;
    const std::unique_ptr<FormFactorMethod> method = createCentroid(none, mesh, rays, {});
    double f = 0, area = 0;
    RowResult row;
    for (int i = mesh.surfaceBegin[0]; i < mesh.surfaceBegin[1]; ++i) {
      method->computeRow(i, row);
      for (const RowEntry& e : row.entries) f += mesh.patches[i].area * e.value;
      area += mesh.patches[i].area;
    }
    const double error = std::abs(f / area - 0.19982489569838746);
    EXPECT_LT(error, previous) << patches << " patches";
    previous = error;
  }
  EXPECT_LT(previous, 2e-3);
}

TEST(ExtendingExamples, ExactCentroidParameterSwitchesTheOccluderOff) {
  // The squares of Howell C-11 with an opaque plate between them, larger than both: every
  // centroid ray is blocked, so F = 0; visibility=0 gives the unoccluded F, which converges to
  // C-11's 0.19982 as above. The parameter is read as the registry reads it: other keys and
  // values outside {0, 1} are refused.
  test::TempDir dir;
  const std::string path = dir.file("blocked.json", R"({"units": "m",
      "materials": {"grey": {"reflectance": [0.5, 0.5, 0.5]}},
      "surfaces": [
        {"name": "lower", "material": "grey", "polygon": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]]},
        {"name": "upper", "material": "grey", "polygon": [[0,0,1],[0,1,1],[1,1,1],[1,0,1]]},
        {"name": "plate", "material": "grey",
         "polygon": [[-1,-1,0.5],[2,-1,0.5],[2,2,0.5],[-1,2,0.5]]}]})");
  const Scene scene = loadScene(path);
  const PatchMesh mesh = subdivide(scene, {0, 200});
  const RayScene rays(mesh);
  auto lowerToUpper = [&](const std::string& parameters) {
    Params params = Params::parse(parameters);
    const std::unique_ptr<FormFactorMethod> method = createCentroid(params, mesh, rays, {});
    params.rejectUnused("centroid");
    double f = 0, area = 0;
    RowResult row;
    for (int i = mesh.surfaceBegin[0]; i < mesh.surfaceBegin[1]; ++i) {
      method->computeRow(i, row);
      for (const RowEntry& e : row.entries)
        if (mesh.patches[e.column].surface == 1) f += mesh.patches[i].area * e.value;
      area += mesh.patches[i].area;
    }
    return f / area;
  };
  EXPECT_EQ(lowerToUpper(""), 0.0);
  EXPECT_EQ(lowerToUpper("visibility=1"), 0.0);
  EXPECT_NEAR(lowerToUpper("visibility=0"), 0.19982489569838746, 5e-3);
  EXPECT_THROW(lowerToUpper("visibility=2"), ParamError);
  EXPECT_THROW(lowerToUpper("visible=0"), ParamError);
}

TEST(ExtendingExamples, StatisticalSchlickPhaseIsNormalisedAndSampledAsItsDensity) {
  // Registered as a row would register it: the registry reads k and refuses other keys.
  const Registry<PhaseFunction> registry(
      "phase function", {{"schlick", createSchlickPhase, "Schlick 1993; k (0.8)", "k=0.8"}});
  EXPECT_THROW(registry.make("schlick", Params::parse("k=1")), ParamError);
  EXPECT_THROW(registry.make("schlick", Params::parse("g=0.5")), ParamError);
  for (double k : {-0.6, 0.0, 0.5, 0.9}) {
    const auto phase = registry.make("schlick", Params({{"k", k}}));
    // ∫ p dΩ = 2π ∫ p dμ = 1, and ⟨μ⟩ as the closed form says, by 200 000-point midpoint
    // quadrature in μ (error far below 1e-6 for |k| ≤ 0.9).
    const int n = 200000;
    double total = 0, mean = 0;
    for (int i = 0; i < n; ++i) {
      const double mu = -1 + (i + 0.5) * 2.0 / n;
      total += 2 * kPi * phase->eval(mu) * 2.0 / n;
      mean += 2 * kPi * mu * phase->eval(mu) * 2.0 / n;
    }
    EXPECT_NEAR(total, 1.0, 1e-6) << k;
    EXPECT_NEAR(mean, phase->meanCosine(), 1e-6) << k;
    // Samples: each pdf is eval at the sample, and their mean cosine matches ⟨μ⟩ within four
    // of its estimated standard errors.
    Rng rng(7, std::uint64_t(1000 * (k + 1)), 0);
    const int samples = 100000;
    double sum = 0, sum2 = 0;
    for (int i = 0; i < samples; ++i) {
      double pdf = 0;
      const double mu = phase->sample(rng.uniform(), pdf);
      ASSERT_NEAR(pdf, phase->eval(mu), 1e-12 * pdf);
      sum += mu, sum2 += mu * mu;
    }
    const double sampleMean = sum / samples;
    const double standardError =
        std::sqrt((sum2 / samples - sampleMean * sampleMean) / (samples - 1));
    EXPECT_LT(std::fabs(sampleMean - phase->meanCosine()), 4 * standardError) << k;
    EXPECT_EQ(phase->evalAnisotropyScaled(0.3, 1.0), phase->eval(0.3));
  }
}

TEST(ExtendingExamples, StatisticalAmbientOcclusionIsOneMinusThePointFormFactor) {
  // Registered as a row of integrators/registry.cpp would register it.
  const Registry<Integrator> registry(
      "integrator", {{"ambient-occlusion", createAmbientOcclusion,
                      "share of cosine rays that escape; rays (64), distance (0: any)", "rays=8"}});
  EXPECT_THROW(registry.make("ambient-occlusion", Params::parse("ray=8")), ParamError);
  // Between Howell's parallel unit squares one apart, looking straight down at the lower
  // square's centre: the only thing it sees is the upper square, whose form factor from that
  // point is four corner rectangles of Howell B-3 (X = Y = 1/2):
  // F = 4 · (1/2π) · 2 · X/√(1 + X²) · atan(Y/√(1 + X²)) = 0.239459...
  const double x = 0.5, f = 4 / (2 * M_PI) * 2 * x / std::sqrt(1 + x * x) *
                            std::atan(x / std::sqrt(1 + x * x));
  const Scene scene = loadScene(test::dataPath("parallel-squares.json"));
  RenderSettings s;
  s.film.width = s.film.height = 3;
  s.film.seed = 5;
  s.camera.position = {0.5, 0.5, 0.9};
  s.camera.lookAt = {0.5, 0.5, 0};
  s.camera.up = {0, 1, 0};
  s.camera.fovDeg = 1;
  const int n = 40000;
  const RenderResult r =
      registry.make("ambient-occlusion", Params({{"rays", double(n)}}))->render(scene, s);
  const double share = r.image.radiance[4].x;  // the centre pixel
  EXPECT_EQ(r.surfaces[4], 0);
  // A binomial share: its standard error from the estimate itself.
  const double se = std::sqrt(share * (1 - share) / n);
  EXPECT_LT(std::abs(share - (1 - f)), 4 * se) << share << " against " << 1 - f << " ± " << se;
  // Occluders beyond `distance` do not count: the upper square is 1 away.
  const RenderResult near =
      registry.make("ambient-occlusion", Params({{"rays", 64.0}, {"distance", 0.99}}))
          ->render(scene, s);
  EXPECT_EQ(near.image.radiance[4].x, 1.0);
}

}  // namespace
}  // namespace radkit
