// Sky models (sky/registry.cpp): every entry, built from its example, is checked against
// identities any sky must satisfy, so a new model is tested without a new test; then the closed
// forms of the uniform and CIE overcast skies.
#include <gtest/gtest.h>

#include <cmath>

#include "sky/sky_radiance.h"
#include "util/photometry.h"

namespace radkit {
namespace {

constexpr double kDeg = M_PI / 180;

Vec3 localDirection(double elevation, double azimuth) {
  return {std::cos(elevation) * std::sin(azimuth), std::cos(elevation) * std::cos(azimuth),
          std::sin(elevation)};
}

/// ∫ L cos θ dω over the upper hemisphere by the midpoint rule in elevation and azimuth.
Vec3 integrateHorizontal(const SkyRadiance& sky, int n) {
  Vec3 sum{0, 0, 0};
  for (int i = 0; i < n; ++i) {
    const double e = (i + 0.5) / n * (M_PI / 2);
    for (int j = 0; j < 2 * n; ++j)
      sum += sky.radiance(localDirection(e, (j + 0.5) / (2 * n) * 2 * M_PI)) *
             (std::sin(e) * std::cos(e));
  }
  return sum * ((M_PI / 2) / n * (2 * M_PI) / (2 * n));
}

TEST(SkyRegistry, EveryModelsHorizontalIrradianceIsTheIntegralOfItsRadiance) {
  for (const SkyRegistry::Entry& entry : skyRegistry().entries()) {
    SCOPED_TRACE(entry.name);
    std::unique_ptr<SkyRadiance> sky = skyRegistry().make(entry.name, Params::parse(entry.example));
    sky->prepare(true, 30, 120);
    // A different grid from any model's own (the physical sky integrates its table on 512²).
    const Vec3 integral = integrateHorizontal(*sky, 300);
    const Vec3 claimed = sky->horizontalIrradiance();
    for (int c = 0; c < 3; ++c) {
      EXPECT_GT(claimed[c], 0);
      EXPECT_NEAR(claimed[c] / integral[c], 1, 2e-3) << c;
    }
    // Radiance is finite and non-negative everywhere above the horizon.
    for (int i = 0; i <= 90; i += 5)
      for (int j = 0; j < 360; j += 15) {
        const Vec3 l = sky->radiance(localDirection(std::max(i, 1) * kDeg, j * kDeg));
        for (int c = 0; c < 3; ++c) EXPECT_TRUE(std::isfinite(l[c]) && l[c] >= 0) << i << " " << j;
      }
    // A model that makes the sun gives it for a sun above the horizon, and none below.
    if (sky->computesSun()) {
      EXPECT_GT(sky->sunIrradiance().y, 0);
      sky->prepare(true, -10, 120);
      EXPECT_EQ(sky->sunIrradiance().y, 0);
    }
  }
}

TEST(SkyRegistry, ExamplesAreTenThousandLuxWhereBrightnessIsAParameter) {
  // πL (uniform) and 7πL_z/9 (CIE overcast) of the examples' luminances, in lux: 10 000 within
  // the rounding of the luminance to whole cd/m².
  for (const char* name : {"uniform", "cie-overcast"}) {
    const auto& entry = skyRegistry().at(name);
    const auto sky = skyRegistry().make(name, Params::parse(entry.example));
    EXPECT_NEAR(kLumensPerWatt * luminance(sky->horizontalIrradiance()), 1e4, 2) << name;
  }
}

TEST(SkyRegistry, UniformAndCieOvercastFollowTheirClosedForms) {
  const auto uniform = skyRegistry().make("uniform", Params::parse("radiance=1 2 3"));
  EXPECT_EQ(uniform->radiance(localDirection(0.3, 2)).z, 3);
  EXPECT_NEAR(uniform->horizontalIrradiance().y, 2 * M_PI, 1e-12);
  // CIE overcast (Moon and Spencer 1942): L(θ) = L_z (1 + 2 cos θ)/3, a third at the horizon.
  const auto cie = skyRegistry().make("cie-overcast", Params::parse("zenith_luminance=683"));
  EXPECT_NEAR(cie->radiance({0, 0, 1}).x, 1, 1e-12);
  EXPECT_NEAR(cie->radiance(localDirection(1e-9, 1)).x, 1.0 / 3, 1e-9);
  EXPECT_NEAR(cie->radiance(localDirection(30 * kDeg, 1)).x, (1 + 2 * 0.5) / 3, 1e-12);
}

TEST(SkyRegistry, RefusesBadParametersWithTheModelAndKey) {
  auto message = [](const char* name, const char* params) {
    try {
      skyRegistry().make(name, Params::parse(params));
    } catch (const ParamError& e) {
      return std::string(e.what());
    }
    return std::string("(made)");
  };
  EXPECT_NE(message("uniform", "").find("exactly one of \"radiance\""), std::string::npos);
  EXPECT_NE(message("uniform", "radiance=1, luminance=3").find("exactly one"), std::string::npos);
  EXPECT_NE(message("uniform", "radiance=-1").find("negative"), std::string::npos);
  EXPECT_NE(message("uniform", "radiance=1e70").find("outside"), std::string::npos);
  EXPECT_NE(message("cie-overcast", "radiance=1").find("cie-overcast"), std::string::npos);
  EXPECT_NE(message("physical", "altitude=60000").find("\"altitude\""), std::string::npos);
  EXPECT_NE(message("foggy", "").find("uniform, cie-overcast, physical"), std::string::npos);
  EXPECT_EQ(message("physical", "density=2, altitude=1000"), "(made)");
}

}  // namespace
}  // namespace radkit
