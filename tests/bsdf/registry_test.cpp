// The BSDF registry: names, parameter checking, and the Oren-Nayar model that docs/extending.md
// uses as its worked example.
#include <gtest/gtest.h>

#include <cmath>

#include "bsdf/bsdf.h"
#include "geometry/scene.h"
#include "tests/common/statistics.h"
#include "util/sampling.h"

namespace radkit {
namespace {

std::string errorOf(const std::string& name, const std::string& params) {
  try {
    makeBsdf(name, Params::parse(params));
  } catch (const ParamError& e) {
    return e.what();
  }
  return "";
}

TEST(BsdfRegistry, ConstructEveryEntryFromItsExample) {
  const auto& table = bsdfRegistry().entries();
  ASSERT_GE(table.size(), 6u);
  for (const auto& info : table) {
    std::unique_ptr<Bsdf> bsdf = makeBsdf(info.name, Params::parse(info.example));
    ASSERT_TRUE(bsdf) << info.name;
    // Radiosity needs a diffuse albedo in [0, 1) from every model.
    for (int c = 0; c < 3; ++c) {
      EXPECT_GE(bsdf->diffuseAlbedo()[c], 0) << info.name;
      EXPECT_LT(bsdf->diffuseAlbedo()[c], 1) << info.name;
    }
    EXPECT_FALSE(bsdf->describe().empty());
  }
}

TEST(BsdfRegistry, BadInputNamesTheProblemAndTheFix) {
  EXPECT_NE(errorOf("velvet", "").find("lambert, phong"), std::string::npos);
  // A key of another model is rejected with the keys this one reads.
  const std::string typo = errorOf("lambert", "shininess=3");
  EXPECT_NE(typo.find("\"shininess\""), std::string::npos) << typo;
  EXPECT_NE(typo.find("reads reflectance"), std::string::npos) << typo;
  EXPECT_NE(errorOf("lambert", "reflectance=1").find("outside [0, 1)"), std::string::npos);
  EXPECT_NE(errorOf("phong", "kd=0.6, ks=0.5").find("kd + ks"), std::string::npos);
  EXPECT_NE(errorOf("phong", "kd=0.5, reflectance=0.5").find("both"), std::string::npos);
  EXPECT_NE(errorOf("cook-torrance", "roughness=0").find("Fix:"), std::string::npos);
  EXPECT_NE(errorOf("cook-torrance", "f0=0.04, ior=1.5").find("both"), std::string::npos);
  EXPECT_NE(errorOf("glass", "ior=1").find("outside (1, 10)"), std::string::npos);
  EXPECT_NE(errorOf("oren-nayar", "sigma=-1").find("sigma"), std::string::npos);
  EXPECT_NE(errorOf("lambert", "reflectance=0.1 0.2").find("RGB"), std::string::npos);
}

TEST(BsdfRegistry, ExactMaterialsCacheTheDiffuseAlbedo) {
  EXPECT_EQ(makeMaterial("m", "cook-torrance", "base_color=0.8, metallic=0.5").diffuseAlbedo(),
            (Vec3{0.4, 0.4, 0.4}));
  EXPECT_EQ(makeMaterial("m", "mirror", "").diffuseAlbedo(), (Vec3{0, 0, 0}));
  EXPECT_TRUE(makeMaterial("m", "glass", "").isSpecular());
  // Schlick's F0 from the index of refraction: ((1.5 − 1)/(1.5 + 1))² = 0.04.
  const std::string ct = makeMaterial("m", "cook-torrance", "ior=1.5").description;
  EXPECT_NE(ct.find("F0=[0.04, 0.04, 0.04]"), std::string::npos) << ct;
}

TEST(OrenNayar, ExactLimits) {
  // Oren & Nayar 1994, eq. 30: σ = 0 gives A = 1, B = 0, the Lambertian R/π; seen from the
  // normal (θo = 0, so β = 0 and tan β = 0) any σ gives A R/π, A = 1 − σ²/(2(σ² + 0.33)).
  auto smooth = makeBsdf("oren-nayar", Params::parse("reflectance=0.6, sigma=0"));
  auto lambert = makeLambertBsdf({0.6, 0.6, 0.6});
  Rng rng(1, 2, 3);
  for (int k = 0; k < 100; ++k) {
    const Vec3 a = localDirection(rng.uniform(), 7 * rng.uniform()),
               b = localDirection(rng.uniform(), 7 * rng.uniform());
    EXPECT_NEAR(smooth->eval(a, b).x, lambert->eval(a, b).x, 1e-15);
  }
  EXPECT_NEAR(smooth->diffuseAlbedo().x, 0.6, 1e-12);
  const double s2 = std::pow(30 * M_PI / 180, 2), A = 1 - s2 / (2 * (s2 + 0.33));
  auto rough = makeBsdf("oren-nayar", Params::parse("reflectance=0.6, sigma=30"));
  EXPECT_NEAR(rough->eval({0, 0, 1}, localDirection(0.3, 1.0)).x, 0.6 * A / M_PI, 1e-15);
}

TEST(OrenNayar, StatisticalAlbedoMatchesMonteCarlo) {
  // The albedo radiosity sees is ρ_bh = (1/π) ∫∫ f cos θi cos θo dωi dωo (quadrature in
  // oren_nayar.cpp); estimate it with cosine-distributed pairs: ρ_bh = E[π f].
  for (double sigma : {20.0, 60.0}) {
    auto f =
        makeBsdf("oren-nayar", Params::parse("reflectance=0.7, sigma=" + std::to_string(sigma)));
    Rng rng(9, int(sigma), 0);
    const int n = 400000;
    double sum = 0, sumSq = 0;
    for (int k = 0; k < n; ++k) {
      const Vec3 wo = sampleCosineHemisphere(rng.uniform(), rng.uniform());
      const Vec3 wi = sampleCosineHemisphere(rng.uniform(), rng.uniform());
      const double v = M_PI * f->eval(wo, wi).x;
      sum += v, sumSq += v * v;
    }
    const double mean = sum / n, se = std::sqrt((sumSq / n - mean * mean) / n);
    EXPECT_NEAR(f->diffuseAlbedo().x, mean, 4 * se) << "sigma " << sigma << " se " << se;
    EXPECT_LT(f->diffuseAlbedo().x, 0.7);  // rough diffuse reflects less than Lambert's R
  }
}

}  // namespace
}  // namespace radkit
