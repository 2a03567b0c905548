// GGX microfacet theory against the identities of docs/oracles.md (Microfacet BRDF identities):
// D normalisation, the weak white furnace, the single-evaluation values, directional albedo
// (two independent quadratures), E <= 1, a χ² test of the visible-normal sampler, and the
// white furnace of Kulla-Conty compensation.
#include "bsdf/microfacet.h"

#include <gtest/gtest.h>

#include <cmath>

#include "bsdf/bsdf.h"
#include "bsdf/specular.h"
#include "tests/common/statistics.h"
#include "util/sampling.h"

namespace radkit {
namespace {

const MaskingShadowing kAllG[] = {MaskingShadowing::HeightCorrelated, MaskingShadowing::Separable,
                                  MaskingShadowing::SchlickGgx, MaskingShadowing::CookTorrance};

/// ∫ f(ωo, ωi) μi dωi by the midpoint rule on n × 2n cells of (μi, φi): independent of the
/// visible-normal warp that directionalAlbedo uses.
double albedoByQuadrature(const GgxDistribution& d, MaskingShadowing g, double muO, int n) {
  const Vec3 wo = localDirection(muO, 0);
  double sum = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < 2 * n; ++j) {
      const Vec3 wi =
          localDirection((i + 0.5) / n, M_PI * (j + 0.5) / (2 * n));  // φ in (0, π): symmetric
      const Vec3 h = normalize(wo + wi);
      sum += d.D(h) * d.G(wo, wi, g) / (4 * wo.z);  // f μi with μi cancelled
    }
  return 2 * sum * (1.0 / n) * (M_PI / (2 * n));
}

TEST(Microfacet, Construct) {
  for (MaskingShadowing g : kAllG) EXPECT_EQ(parseMaskingShadowing(maskingShadowingName(g)), g);
  EXPECT_THROW(parseMaskingShadowing("beckmann"), std::invalid_argument);
  EXPECT_GT(GgxDistribution(0).alpha(), 0);  // clamped so that D stays finite
  EXPECT_EQ(GgxDistribution(0.5).D({0, 0, -1}), 0);
  EXPECT_EQ(GgxDistribution(0.5).G1({1, 0, 0}), 0);
}

TEST(Microfacet, ExactSingleEvaluation) {
  // docs/oracles.md: α = 0.5, ωo at θ = 45°, φ = 0, ωi at θ = 30°, φ = 180°, F0 = 0.04.
  const GgxDistribution d(0.5);
  const Vec3 wo = localDirection(std::cos(M_PI / 4), 0),
             wi = localDirection(std::cos(M_PI / 6), M_PI);
  const Vec3 h = normalize(wo + wi);
  EXPECT_NEAR(d.D(h), 1.152425, 5e-7);
  EXPECT_NEAR(d.G(wo, wi, MaskingShadowing::HeightCorrelated), 0.926412, 5e-7);
  EXPECT_NEAR(fresnelSchlick(Vec3{0.04, 0.04, 0.04}, dot(wi, h)).x, 0.040362, 5e-7);
  // The whole BRDF through the factory: base colour 0 leaves only the specular lobe;
  // roughness √0.5 gives α = 0.5.
  auto f = makeCookTorranceBsdf({0, 0, 0}, 0, std::sqrt(0.5), {0.04, 0.04, 0.04}, {});
  EXPECT_NEAR(f->eval(wo, wi).y, 0.017592, 5e-7);
  // Schlick's hemispherical average F0 + (1 − F0)/21: F_avg = 2 ∫ F(μ) μ dμ.
  double avg = 0;
  for (int k = 0; k < 100000; ++k)
    avg += 2 * fresnelSchlick({0.04, 0, 0}, (k + 0.5) / 1e5).x * (k + 0.5) / 1e5 / 1e5;
  EXPECT_NEAR(avg, 0.04 + 0.96 / 21, 1e-9);
}

TEST(Microfacet, ExactDNormalisation) {
  // ∫ D(m)(n·m) dω_m = 2π ∫₀¹ D(μ) μ dμ = π ∫₀¹ D(√t) dt, t = μ²: D is rational in t, so
  // composite Simpson on 20 000 intervals resolves even the α = 0.05 peak (width α² in t).
  for (double alpha : {0.05, 0.2, 0.5, 0.8, 1.0}) {
    const GgxDistribution d(alpha);
    const int n = 20000;
    double sum = 0;
    for (int k = 0; k <= n; ++k) {
      const double t = double(k) / n, w = (k == 0 || k == n) ? 1 : (k % 2 ? 4 : 2);
      const double tt = std::max(t, 1e-300);  // D is 0 at the horizon itself; take the limit
      sum += w * d.D({std::sqrt(1 - tt), 0, std::sqrt(tt)});
    }
    EXPECT_NEAR(M_PI * sum / (3.0 * n), 1.0, 1e-6) << "alpha " << alpha;
  }
}

TEST(Microfacet, ExactWeakWhiteFurnace) {
  // Heitz 2014, eq. 18: ∫ G1(ωo) max(0, ωo·m) D(m) dω_m = cos θo for every θo and α. Midpoint
  // rule on 1600 × 800 cells of (μ_m, φ_m ∈ (0, π), doubled by symmetry); the kink of
  // max(0, ·) bounds the error near 1e-4.
  for (double alpha : {0.2, 0.5, 1.0})
    for (double thetaDeg : {0.0, 30.0, 60.0, 80.0}) {
      const GgxDistribution d(alpha);
      const Vec3 wo = localDirection(std::cos(thetaDeg * M_PI / 180), 0);
      const int nm = 1600, np = 800;
      double sum = 0;
      for (int i = 0; i < nm; ++i)
        for (int j = 0; j < np; ++j) {
          const Vec3 m = localDirection((i + 0.5) / nm, M_PI * (j + 0.5) / np);
          sum += std::max(0.0, dot(wo, m)) * d.D(m);
        }
      const double integral = d.G1(wo) * 2 * sum * (1.0 / nm) * (M_PI / np);
      EXPECT_NEAR(integral, wo.z, 2e-4) << "alpha " << alpha << ", theta " << thetaDeg;
    }
}

TEST(Microfacet, ExactDirectionalAlbedo) {
  // docs/oracles.md: E(μo = 1, α = 1) ≈ 0.307 (height-correlated, F = 1).
  EXPECT_NEAR(directionalAlbedo(GgxDistribution(1), MaskingShadowing::HeightCorrelated, 1.0), 0.307,
              5e-4);
  // Two quadratures that share nothing but f: the visible-normal warp (64² strata) and a
  // 400 × 800 (μi, φi) grid. Both are midpoint rules across the horizon cut-off, so they
  // agree to about 1e-3; E is below 1 everywhere (single scattering loses energy).
  for (MaskingShadowing g : kAllG)
    for (double alpha : {0.3, 0.6, 1.0})
      for (double mu : {0.1, 0.5, 0.9}) {
        const GgxDistribution d(alpha);
        const double e = directionalAlbedo(d, g, mu);
        EXPECT_NEAR(e, albedoByQuadrature(d, g, mu, 400), 2e-3)
            << maskingShadowingName(g) << " " << alpha << " " << mu;
        EXPECT_LE(e, 1.0);
        EXPECT_GT(e, 0.0);
      }
  // Schlick-GGX with k = (r + 1)²/8 is Smith's separable G exactly at r = α = 1 (both
  // G1 = 2μ/(1 + μ)).
  for (double mu : {0.1, 0.5, 0.9})
    EXPECT_NEAR(directionalAlbedo(GgxDistribution(1), MaskingShadowing::SchlickGgx, mu),
                directionalAlbedo(GgxDistribution(1), MaskingShadowing::Separable, mu), 1e-12);
  // Energy loss grows with roughness (at normal incidence, height-correlated).
  double previous = 1;
  for (double alpha : {0.1, 0.4, 0.7, 1.0}) {
    const double e =
        directionalAlbedo(GgxDistribution(alpha), MaskingShadowing::HeightCorrelated, 1.0);
    EXPECT_LT(e, previous);
    previous = e;
  }
}

TEST(Microfacet, ExactAlbedoTable) {
  const GgxDistribution d(0.7);
  const MicrofacetAlbedoTable t(d, MaskingShadowing::HeightCorrelated, 32);
  // Nodes at (k + ½)/32 are reproduced; in between, linear interpolation of a smooth E is
  // within h²/8 · max|E''| (below 1e-3 here).
  EXPECT_NEAR(t.albedo(0.5 / 32), t.nodes()[0], 1e-15);
  for (double mu : {0.11, 0.37, 0.66, 0.93})
    EXPECT_NEAR(t.albedo(mu), directionalAlbedo(d, MaskingShadowing::HeightCorrelated, mu), 1e-3)
        << mu;
  // E_avg = 2 ∫ E μ dμ, checked against a coarser direct sum.
  double sum = 0;
  for (int k = 0; k < 200; ++k) sum += 2 * t.albedo((k + 0.5) / 200) * (k + 0.5) / 200 / 200;
  EXPECT_NEAR(t.average(), sum, 1e-5);
  EXPECT_LT(t.average(), 1);
  // The Kulla-Conty lobe is symmetric (reciprocal) and carries exactly 1 − E(μo).
  EXPECT_DOUBLE_EQ(t.multipleScattering(0.3, 0.8), t.multipleScattering(0.8, 0.3));
  double ms = 0;
  for (int k = 0; k < 4000; ++k)
    ms += 2 * M_PI * t.multipleScattering(0.4, (k + 0.5) / 4000) * (k + 0.5) / 4000 / 4000;
  EXPECT_NEAR(ms, 1 - t.albedo(0.4), 1e-6);
  EXPECT_EQ(multipleScatteringFresnel({1, 1, 1}, 0.6), (Vec3{1, 1, 1}));
}

/// Histogram of directions over (cos θ, φ) cells against the integral of their claimed
/// density over each cell (32 × 32 midpoint sub-samples per cell), with one more cell for
/// samples the sampler loses. Returns the χ² p-value.
template <typename Sample, typename Pdf>
double chiSquareOfDirections(Sample sample, Pdf pdf, long long n, const std::string& name,
                             double alpha, bool lowerHemisphere = false) {
  const int nt = 20, np = 40, sub = 32;
  const double zLo = lowerHemisphere ? -1 : 0;
  std::vector<double> observed(nt * np + 1, 0), expected(nt * np + 1, 0);
  Rng rng(42, 0, 0);
  for (long long k = 0; k < n; ++k) {
    Vec3 w;
    if (!sample(rng, w)) {
      observed.back() += 1;
      continue;
    }
    const int i = std::clamp(int((w.z - zLo) / (1 - zLo) * nt), 0, nt - 1);
    double phi = std::atan2(w.y, w.x);
    if (phi < 0) phi += 2 * M_PI;
    const int j = std::clamp(int(phi / (2 * M_PI) * np), 0, np - 1);
    observed[i * np + j] += 1;
  }
  double total = 0;
  for (int i = 0; i < nt; ++i)
    for (int j = 0; j < np; ++j) {
      double cell = 0;
      for (int a = 0; a < sub; ++a)
        for (int b = 0; b < sub; ++b) {
          const double z = zLo + (1 - zLo) * (i + (a + 0.5) / sub) / nt;
          const double p = pdf(localDirection(z, 2 * M_PI * (j + (b + 0.5) / sub) / np));
          EXPECT_GE(p, 0);
          cell += p;
        }
      // dω = d(cos θ) dφ.
      cell *= ((1 - zLo) / nt) * (2 * M_PI / np) / (sub * sub);
      expected[i * np + j] = cell * n;
      total += cell;
    }
  EXPECT_LE(total, 1 + 1e-3) << name << ": the claimed density integrates above 1";
  expected.back() = std::max(0.0, 1 - total) * n;
  return test::chiSquarePValue(observed, expected, name + "-chi2.csv", alpha);
}

TEST(Microfacet, StatisticalVisibleNormals) {
  // α = 0.01 at 1 − (1 − 0.01)^(1/6) for the six (α, θo) cases.
  const double alpha = test::sidakAlpha(0.01, 6);
  int index = 0;
  for (double a : {0.3, 0.7})
    for (double thetaDeg : {0.0, 45.0, 80.0}) {
      const GgxDistribution d(a);
      const Vec3 wo = localDirection(std::cos(thetaDeg * M_PI / 180), 0.7);
      auto sample = [&](Rng& rng, Vec3& m) {
        const double u0 = rng.uniform(), u1 = rng.uniform();
        m = d.sampleVisibleNormal(wo, u0, u1);
        return true;
      };
      auto pdf = [&](const Vec3& m) { return d.visibleNormalPdf(wo, m); };
      const double p =
          chiSquareOfDirections(sample, pdf, 200000, "vndf-" + std::to_string(index++), alpha);
      EXPECT_GT(p, alpha) << "alpha " << a << ", theta " << thetaDeg;
    }
}

TEST(Microfacet, StatisticalCompensatedWhiteFurnace) {
  // F = 1 (metallic, base colour 1) with Kulla-Conty: ∫ f μi dωi = 1 for every μo. By the
  // BSDF's own sampler (mean of f μi / pdf, 200 000 samples, standard error ~1e-3) and the
  // table-limited exactness: E_true(μo) − E_table(μo) + 1, where the 32-node table and its
  // 64² quadrature are good to ~2e-3 (ExactAlbedoTable, ExactDirectionalAlbedo).
  BsdfSettings s;
  s.compensated = true;
  for (double roughness : {0.5, 0.8, 1.0}) {
    auto f = makeCookTorranceBsdf({1, 1, 1}, 1, roughness, {0.04, 0.04, 0.04}, s);
    auto single = makeCookTorranceBsdf({1, 1, 1}, 1, roughness, {0.04, 0.04, 0.04}, {});
    for (double mu : {0.2, 0.6, 1.0}) {
      const Vec3 wo = localDirection(mu, 0);
      Rng rng(7, int(roughness * 10), int(mu * 10));
      double sum = 0, sumSq = 0, lossy = 0;
      const int n = 200000;
      for (int k = 0; k < n; ++k) {
        const double u0 = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
        if (auto b = f->sample(wo, u0, u1, u2))
          sum += b->weight.y, sumSq += b->weight.y * b->weight.y;
        if (auto b = single->sample(wo, u0, u1, u2)) lossy += b->weight.y;
      }
      const double mean = sum / n, se = std::sqrt((sumSq / n - mean * mean) / n);
      EXPECT_NEAR(mean, 1.0, 2e-3 + 4 * se) << "roughness " << roughness << ", mu " << mu;
      EXPECT_LT(lossy / n, mean - 0.01) << "single scattering should lose energy";
    }
  }
}

}  // namespace
}  // namespace radkit
