// The air's Rayleigh models (atmosphere/rayleigh.h) against Bodhaine, Wood, Dutton and Slusser
// (1999), "On Rayleigh optical depth calculations", J. Atmos. Oceanic Technol. 16, 1854–1861:
// their Table 3 (sea level, 1013.25 hPa, 45° latitude, 360 ppm CO2) and their four-parameter
// fit of it, eq. (30). docs/atmosphere.md lists the values.
#include <gtest/gtest.h>

#include <cmath>

#include "atmosphere/atmosphere.h"
#include "atmosphere/rayleigh.h"

namespace radkit::atmosphere {
namespace {

/// Bodhaine et al. (1999), eq. (30): τ_R(λ) at sea level, λ in µm.
double bodhaineFit(double um) {
  const double l2 = um * um;
  return 0.0021520 * (1.0455996 - 341.29061 / l2 - 0.90230850 * l2) /
         (1 + 0.0027059889 / l2 - 85.968563 * l2);
}

TEST(Rayleigh, BodhaineAirReproducesTheirTable) {
  // Table 3: wavelength (µm), σ (cm²), τ_R, F(air).
  struct Row {
    double um, sigma, tau, king;
  };
  const Row rows[] = {{0.45, 1.0274e-26, 0.22111, 1.05011},
                      {0.50, 6.6614e-27, 0.14336, 1.04935},
                      {0.55, 4.5105e-27, 0.097069, 1.04882},
                      {0.65, 2.2856e-27, 0.049188, 1.04815},
                      {0.70, 1.6926e-27, 0.036424, 1.04793}};
  for (const Row& r : rows) {
    const BodhaineAir air = bodhaineAir(r.um * 1e-6);
    // The table rounds to five digits: 1e-4 relative is its last digit.
    EXPECT_NEAR(air.crossSection * 1e4 / r.sigma, 1, 1e-4) << r.um;
    EXPECT_NEAR(air.opticalDepth / r.tau, 1, 1e-4) << r.um;
    EXPECT_NEAR(air.kingFactor, r.king, 1e-5) << r.um;
  }
  // Dispersion: n − 1 of air falls from 2.81e-4 at 440 nm to 2.76e-4 at 680 nm.
  EXPECT_NEAR(bodhaineAir(440e-9).refractiveIndexMinusOne, 2.81e-4, 0.5e-6);
  EXPECT_NEAR(bodhaineAir(680e-9).refractiveIndexMinusOne, 2.76e-4, 0.5e-6);
}

TEST(Rayleigh, BodhaineModelsOpticalDepthIsTheirsAtTheChannels) {
  // The channels' 680, 550 and 440 nm against eq. (30), through the atmosphere's own optical
  // depth integration from the ground to the top (60 km): within 1 % (the target), and within
  // 0.2 % in fact (the top truncates e^(−60/8.45) = 0.08 % of the column).
  AtmosphereParameters p;
  useRayleigh(p, rayleighAir("bodhaine"));
  p.mieScattering = 0, p.mieExtinction = 0;
  const Atmosphere air(p);
  const Vec3 ground = air.pointAtAltitude(0);
  const Vec3 tau = air.opticalDepth(ground, air.pointAtAltitude(p.topRadius - p.groundRadius));
  const Vec3 shell = rayleighOpticalDepth(p.rayleighScattering, p.rayleighScaleHeight,
                                          p.topRadius - p.groundRadius);
  for (int c = 0; c < 3; ++c) {
    const double expected = bodhaineFit(kWavelengths[c] * 1e6);
    EXPECT_NEAR(tau[c] / expected, 1, 2e-3) << c;
    EXPECT_NEAR(shell[c] / tau[c], 1, 1e-4) << c;
  }
  // The scale height is the isothermal one at 288.15 K: k T / (m_a g), 8.45 km.
  EXPECT_NEAR(p.rayleighScaleHeight, 8450, 10);
  // Bruneton's defaults lie 9–13 % above (n − 1 = 3.0e-4 and a King factor of 1.061).
  const RayleighAir bruneton = rayleighAir("bruneton");
  const Vec3 brunetonTau = rayleighOpticalDepth(bruneton.scattering, bruneton.scaleHeight, 60e3);
  for (int c = 0; c < 3; ++c) {
    const double ratio = brunetonTau[c] / bodhaineFit(kWavelengths[c] * 1e6);
    EXPECT_GT(ratio, 1.08) << c;
    EXPECT_LT(ratio, 1.14) << c;
  }
}

TEST(Rayleigh, ModelsByNameWithTheirParameters) {
  // More CO2 scatters a little more: 1 + 0.54 ΔC in n − 1 and a King factor nudged up.
  const double more = bodhaineAir(550e-9, 1000e-6).opticalDepth;
  EXPECT_GT(more, bodhaineAir(550e-9).opticalDepth);
  EXPECT_NE(rayleighAir("bodhaine:co2=420").scattering.y, rayleighAir("bodhaine").scattering.y);
  EXPECT_THROW(rayleighAir("bodhaine:co2=-5"), ParamError);
  EXPECT_THROW(rayleighAir("bodhaine:temperature=300"), ParamError);
  EXPECT_THROW(rayleighAir("nishita"), UnknownNameError);
  EXPECT_EQ(rayleighAir("bruneton").scattering.z, AtmosphereParameters{}.rayleighScattering.z);
}

}  // namespace
}  // namespace radkit::atmosphere
