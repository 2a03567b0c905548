// The BSDF models: construction from the registry, exact values (Lambert, mirror, glass),
// reciprocity, albedo <= 1, and χ² tests of every sampler against the pdf it claims. The
// statistical tests run over every registered non-delta BSDF (its example parameters), so a
// new BSDF is tested without a line here.
#include "bsdf/bsdf.h"

#include <gtest/gtest.h>

#include <cmath>

#include "bsdf/specular.h"
#include "tests/common/statistics.h"
#include "util/sampling.h"

namespace radkit {
namespace {

/// The non-delta models the statistical tests run over, with a name for messages.
struct NamedBsdf {
  std::string name;
  std::unique_ptr<Bsdf> bsdf;
};

std::vector<NamedBsdf> glossyModels() {
  std::vector<NamedBsdf> out;
  for (const auto& info : bsdfRegistry().entries()) {
    std::unique_ptr<Bsdf> bsdf = makeBsdf(info.name, Params::parse(info.example));
    if (!bsdf->isDelta()) out.push_back({info.name, std::move(bsdf)});
  }
  out.push_back({"phong", makePhongBsdf({0.3, 0.3, 0.3}, {0.6, 0.6, 0.6}, 20)});
  out.push_back({"phong-sharp", makePhongBsdf({0.1, 0.1, 0.1}, {0.85, 0.85, 0.85}, 200)});
  BsdfSettings s;
  for (MaskingShadowing g : {MaskingShadowing::HeightCorrelated, MaskingShadowing::Separable,
                             MaskingShadowing::SchlickGgx, MaskingShadowing::CookTorrance}) {
    s.masking = g;
    out.push_back({std::string("ct-") + maskingShadowingName(g),
                   makeCookTorranceBsdf({0.7, 0.4, 0.2}, 0, 0.6, {0.04, 0.04, 0.04}, s)});
  }
  s.masking = MaskingShadowing::HeightCorrelated;
  s.compensated = true;
  out.push_back({"ct-metal-compensated",
                 makeCookTorranceBsdf({0.9, 0.6, 0.3}, 1, 0.8, {0.04, 0.04, 0.04}, s)});
  return out;
}

TEST(Bsdf, Construct) {
  EXPECT_NE(makeBsdf("lambert", {})->describe().find("lambert"), std::string::npos);
  EXPECT_NE(makeBsdf("phong", Params::parse("ks=0.2, shininess=10"))->describe().find("phong"),
            std::string::npos);
  auto ct = makeBsdf("cook-torrance", Params::parse("metallic=0.25"),
                     {MaskingShadowing::SchlickGgx, true, 16});
  EXPECT_NE(ct->describe().find("schlick"), std::string::npos);
  EXPECT_NE(ct->describe().find("Kulla-Conty"), std::string::npos);
  // The Lambertian part is what radiosity sees: (1 − metallic) · base colour.
  EXPECT_EQ(ct->diffuseAlbedo(), (Vec3{0.375, 0.375, 0.375}));
  EXPECT_TRUE(makeBsdf("mirror", {})->isDelta());
  EXPECT_TRUE(makeBsdf("glass", {})->isDelta());
  EXPECT_TRUE(makeBsdf("glass", {})->transmits());
  EXPECT_FALSE(makeBsdf("lambert", {})->isDelta());
}

TEST(Bsdf, ExactLambertMirrorGlass) {
  auto lambert = makeLambertBsdf({0.5, 0.25, 0.1});
  EXPECT_NEAR(lambert->eval(localDirection(0.3, 1), localDirection(0.9, 2)).x, 0.5 / M_PI, 1e-15);
  EXPECT_EQ(lambert->eval(localDirection(-0.3, 1), localDirection(0.9, 2)).x, 0);  // one-sided
  EXPECT_NEAR(lambert->pdf(localDirection(0.3, 1), localDirection(0.9, 2)), 0.9 / M_PI, 1e-15);

  auto mirror = makeMirrorBsdf({0.9, 0.8, 0.7});
  const Vec3 wo = localDirection(0.6, 0.4);
  auto s = mirror->sample(wo, 0.5, 0.5, 0.5);
  ASSERT_TRUE(s);
  EXPECT_TRUE(s->delta);
  EXPECT_NEAR(length(s->wi - reflect(wo, {0, 0, 1})), 0, 1e-15);
  EXPECT_EQ(s->weight, (Vec3{0.9, 0.8, 0.7}));
  EXPECT_EQ(maxComponent(mirror->eval(wo, s->wi)), 0);

  // Glass: reflection below u0 < F, else refraction by Snell with radiance scaled by 1/η².
  auto glass = makeGlassBsdf(1.5);
  const double f = fresnelDielectric(wo.z, 1.5);
  auto r = glass->sample(wo, f * 0.99, 0.5, 0.5);
  ASSERT_TRUE(r);
  EXPECT_GT(r->wi.z, 0);
  auto t = glass->sample(wo, f + (1 - f) * 0.01, 0.5, 0.5);
  ASSERT_TRUE(t);
  EXPECT_LT(t->wi.z, 0);
  EXPECT_NEAR(std::sqrt(1 - wo.z * wo.z), 1.5 * std::sqrt(1 - t->wi.z * t->wi.z), 1e-12);
  EXPECT_NEAR(t->weight.x, 1 / 2.25, 1e-15);
  // From inside, leaving: the 1/η² factor inverts, so a ray through a slab keeps radiance.
  auto back = glass->sample(t->wi, 0.999999, 0.5, 0.5);  // wo inside: pointing into the glass
  ASSERT_TRUE(back);
  EXPECT_NEAR(back->weight.x * t->weight.x, 1, 1e-12);
  EXPECT_NEAR(length(back->wi - wo), 0, 1e-12);
}

TEST(Bsdf, ExactReciprocity) {
  // f(ωo, ωi) = f(ωi, ωo) (Helmholtz) for every non-delta model, on random pairs.
  Rng rng(3, 0, 0);
  for (const NamedBsdf& m : glossyModels())
    for (int k = 0; k < 2000; ++k) {
      const Vec3 a = localDirection(rng.uniform(), 2 * M_PI * rng.uniform());
      const Vec3 b = localDirection(rng.uniform(), 2 * M_PI * rng.uniform());
      const Vec3 fab = m.bsdf->eval(a, b), fba = m.bsdf->eval(b, a);
      ASSERT_NEAR(fab.x, fba.x, 1e-12 * std::max(1.0, fab.x)) << m.name;
      ASSERT_NEAR(fab.z, fba.z, 1e-12 * std::max(1.0, fab.z)) << m.name;
    }
}

TEST(Bsdf, StatisticalAlbedoAtMostOne) {
  // ∫ f μi dωi <= 1 per channel, estimated with each model's own sampler (mean of the
  // weights): allow 4 standard errors. Phong at kd + ks = 1 and the specular lobe alone at
  // F = 1 (metallic, base colour 1) under each G are the hard cases. (The additive diffuse +
  // specular model with the original Cook-Torrance G and a bright diffuse part does exceed 1
  // at grazing incidence, 1.013 at μ = 0.05 for kd = 0.7: docs/shading.md.)
  std::vector<NamedBsdf> models;
  for (NamedBsdf& m : glossyModels())
    if (m.name != "ct-cook-torrance") models.push_back(std::move(m));
  models.push_back({"phong-white", makePhongBsdf({0.2, 0.2, 0.2}, {0.8, 0.8, 0.8}, 5)});
  BsdfSettings s;
  for (MaskingShadowing g : {MaskingShadowing::HeightCorrelated, MaskingShadowing::Separable,
                             MaskingShadowing::SchlickGgx, MaskingShadowing::CookTorrance})
    for (double roughness : {0.3, 1.0}) {
      s.masking = g;
      models.push_back({std::string("ct-f1-") + maskingShadowingName(g),
                        makeCookTorranceBsdf({1, 1, 1}, 1, roughness, {}, s)});
    }
  s.masking = MaskingShadowing::HeightCorrelated;
  s.compensated = true;
  models.push_back({"ct-white-compensated",
                    makeCookTorranceBsdf({0.99, 0.99, 0.99}, 1, 1.0, {0.04, 0.04, 0.04}, s)});
  for (const NamedBsdf& m : models)
    for (double mu : {0.05, 0.4, 1.0}) {
      Rng rng(11, 0, int(mu * 100));
      const int n = 50000;
      double sum = 0, sumSq = 0;
      for (int k = 0; k < n; ++k) {
        const double u0 = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
        if (auto b = m.bsdf->sample(localDirection(mu, 0.3), u0, u1, u2)) {
          const double w = maxComponent(b->weight);
          sum += w, sumSq += w * w;
        }
      }
      const double mean = sum / n, se = std::sqrt(std::max(0.0, sumSq / n - mean * mean) / n);
      EXPECT_LE(mean, 1 + 4 * se) << m.name << " at mu " << mu;
    }
}

TEST(Bsdf, StatisticalSamplersMatchPdf) {
  // χ² of sample() against pdf() over 20 × 40 (cos θi, φi) cells plus a cell for lost
  // samples (below the horizon), for each model at three incidences; Šidák-corrected.
  std::vector<NamedBsdf> models = glossyModels();
  const int cases = int(models.size()) * 3;
  const double alpha = test::sidakAlpha(0.01, cases);
  const int nt = 20, np = 40, sub = 16;
  const long long n = 100000;
  for (const NamedBsdf& m : models)
    for (double mu : {0.15, 0.6, 0.95}) {
      const Vec3 wo = localDirection(mu, 1.1);
      std::vector<double> observed(nt * np + 1, 0), expected(nt * np + 1, 0);
      Rng rng(5, 1, int(mu * 100));
      for (long long k = 0; k < n; ++k) {
        const double u0 = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
        std::optional<BsdfSample> b = m.bsdf->sample(wo, u0, u1, u2);
        if (!b) {
          observed.back() += 1;
          continue;
        }
        ASSERT_NEAR(b->pdf, m.bsdf->pdf(wo, b->wi), 1e-9 * b->pdf) << m.name;
        const int i = std::clamp(int(b->wi.z * nt), 0, nt - 1);
        double phi = std::atan2(b->wi.y, b->wi.x);
        if (phi < 0) phi += 2 * M_PI;
        observed[i * np + std::clamp(int(phi / (2 * M_PI) * np), 0, np - 1)] += 1;
      }
      double total = 0;
      for (int i = 0; i < nt; ++i)
        for (int j = 0; j < np; ++j) {
          double cell = 0;
          for (int a = 0; a < sub; ++a)
            for (int c = 0; c < sub; ++c)
              cell += m.bsdf->pdf(wo, localDirection((i + (a + 0.5) / sub) / nt,
                                                     2 * M_PI * (j + (c + 0.5) / sub) / np));
          cell *= (1.0 / nt) * (2 * M_PI / np) / (sub * sub);
          expected[i * np + j] = cell * n;
          total += cell;
        }
      EXPECT_LE(total, 1 + 2e-3) << m.name;
      expected.back() = std::max(0.0, 1 - total) * n;
      const std::string name = "bsdf-" + m.name + "-" + std::to_string(int(mu * 100));
      EXPECT_GT(test::chiSquarePValue(observed, expected, name + "-chi2.csv", alpha), alpha)
          << name;
    }
}

}  // namespace
}  // namespace radkit
