#include "atmosphere/rayleigh.h"

#include <cmath>
#include <memory>

namespace radkit::atmosphere {

namespace {

// Bodhaine et al. (1999)'s constants.
constexpr double kAvogadro = 6.0221367e23;        // 1/mol
constexpr double kStandardDensity = 2.546899e25;  // N_s, 1/m³ at 288.15 K and 1013.25 hPa (eq. 24)
constexpr double kSeaLevelPressure = 101325;      // Pa
/// Gravity at the mass-weighted column height z_c = 0.73737 z + 5517.56 m of a sea-level column
/// at 45° latitude, by List (1968)'s formula, as Bodhaine et al. evaluate it (m/s²).
double columnGravity() {
  const double zc = 5517.56;   // m
  const double g0 = 980.6160;  // cm/s² at 45°, where cos 2φ = 0
  return (g0 - 3.085462e-4 * zc + 7.254e-11 * zc * zc - 1.517e-17 * zc * zc * zc) * 1e-2;
}

std::unique_ptr<RayleighAir> createBruneton(Params&) {
  return std::make_unique<RayleighAir>(RayleighAir{{5.8e-6, 13.5e-6, 33.1e-6}, 8000});
}

std::unique_ptr<RayleighAir> createBodhaine(Params& params) {
  const double ppm = params.number("co2", 360, 0, 1e4, false, false,
                                   "give the CO2 content in parts per million (today about 420)");
  // The column's scale height N_col/N_s, so that ∫ β dh = σ · (the column of eq. 25) and the
  // optical depth is theirs: P A / (m_a g N_s), 8.45 km (the isothermal height at 288.15 K).
  const double co2 = ppm * 1e-6;
  const double molarMass = (15.0556 * co2 + 28.9595) * 1e-3;  // kg/mol, dry air (their eq. 17)
  const double column = kSeaLevelPressure * kAvogadro / (molarMass * columnGravity());
  RayleighAir air{{0, 0, 0}, column / kStandardDensity};
  for (int c = 0; c < 3; ++c)
    air.scattering[c] = bodhaineAir(kWavelengths[c], co2).crossSection * kStandardDensity;
  return std::make_unique<RayleighAir>(air);
}

}  // namespace

BodhaineAir bodhaineAir(double wavelength, double co2) {
  const double um = wavelength * 1e6, inv2 = 1 / (um * um);
  // Peck and Reeder (1972) for 300 ppm CO2 (eq. 18), and its CO2 correction (eq. 19).
  const double n300 = (8060.51 + 2480990 / (132.274 - inv2) + 17455.7 / (39.32957 - inv2)) * 1e-8;
  const double nm1 = n300 * (1 + 0.54 * (co2 - 0.0003));
  // King factors: N2 and O2 from Bates (1984), Ar 1.00, CO2 1.15 (eqs. 5, 6), weighted by
  // volume with CO2 in percent (eq. 23).
  const double fN2 = 1.034 + 3.17e-4 * inv2;
  const double fO2 = 1.096 + 1.385e-3 * inv2 + 1.448e-4 * inv2 * inv2;
  const double percent = co2 * 100;
  const double king = (78.084 * fN2 + 20.946 * fO2 + 0.934 * 1.00 + percent * 1.15) /
                      (78.084 + 20.946 + 0.934 + percent);
  const double n = 1 + nm1, n2 = n * n;
  const double sigma =
      24 * M_PI * M_PI * M_PI * (n2 - 1) * (n2 - 1) /
      (std::pow(wavelength, 4) * kStandardDensity * kStandardDensity * (n2 + 2) * (n2 + 2)) * king;
  const double molarMass = (15.0556 * co2 + 28.9595) * 1e-3;
  const double tau = sigma * kSeaLevelPressure * kAvogadro / (molarMass * columnGravity());
  return {nm1, king, sigma, tau};
}

const Registry<RayleighAir>& rayleighRegistry() {
  static const Registry<RayleighAir> registry(
      "Rayleigh model",
      {
          {"bruneton", createBruneton,
           "Bruneton and Neyret 2008's Earth: (5.8, 13.5, 33.1)·10⁻⁶ /m, scale height 8 km "
           "(the default)",
           ""},
          {"bodhaine", createBodhaine,
           "dry air from its refractive index and King factor (Bodhaine et al. 1999), scale "
           "height from the standard column; co2 in ppm (360)",
           "co2=420"},
      });
  return registry;
}

RayleighAir rayleighAir(const std::string& choice) {
  const PluginChoice c = splitPluginChoice(choice);
  return *rayleighRegistry().make(c.name, Params::parse(c.parameters));
}

Vec3 rayleighOpticalDepth(const Vec3& groundScattering, double scaleHeight, double shellHeight) {
  return groundScattering * (scaleHeight * (1 - std::exp(-shellHeight / scaleHeight)));
}

}  // namespace radkit::atmosphere
