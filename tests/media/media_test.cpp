// Phase functions and Mie theory (media/) against outside oracles: normalisation and mean cosine
// by quadrature, χ² of every sampler against its own density, the Rayleigh limit of Mie theory,
// and Mie numbers checked two ways: this C++ BHMIE-style code (D_n recurrences) and an
// independent NumPy code built on scipy.special.spherical_jn/yn with complex argument, whose
// π_n come from scipy's associated Legendre functions (lpmv), not from recurrences. Numbers
// marked "two ways" agreed to ≥ 6 significant digits between the two.
#include "phase/phase_function.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "phase/mie.h"
#include "tests/common/statistics.h"
#include "util/sampling.h"
#include "util/vec3.h"

namespace radkit::media {
namespace {

/// ∫ f(cos θ)·sin θ dθ·2π for θ in [θ0, θ1], Simpson's rule in θ: the forward peaks of Mie
/// tables (width ~1/x in θ, ~1/x² in cos θ) are resolved in θ where a grid in cos θ misses them.
template <class F>
double integrateTheta(const F& f, double theta0, double theta1, int n = 2000) {
  double sum = 0;
  const double h = (theta1 - theta0) / n;
  for (int i = 0; i <= n; ++i) {
    const double t = theta0 + i * h;
    const double w = (i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2);
    sum += w * f(std::cos(t)) * std::sin(t);
  }
  return 2 * kPi * sum * h / 3;
}

/// The registered functions with their example parameters, plus a few more per parameter.
std::vector<std::pair<std::string, std::string>> phaseCases() {
  std::vector<std::pair<std::string, std::string>> cases;
  for (const std::string& name : phaseFunctionNames())
    cases.emplace_back(name, phaseFunctionExample(name));
  for (const char* g : {"g=-0.7", "g=0", "g=0.3", "g=0.95"})
    cases.emplace_back("henyey-greenstein", g);
  cases.emplace_back("double-henyey-greenstein", "g1=0.9, g2=-0.6, w=0.5");
  cases.emplace_back("double-henyey-greenstein", "g1=0.2, g2=0.7, w=0");
  return cases;
}

TEST(Phase, RegistryHasEveryFunction) {
  const std::vector<std::string> names = phaseFunctionNames();
  for (const char* name :
       {"isotropic", "rayleigh", "henyey-greenstein", "double-henyey-greenstein", "mie-cloud"})
    EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
  for (const std::string& name : names)
    EXPECT_EQ(makePhaseFunction(name, phaseFunctionExample(name))->name(), name);
}

TEST(Phase, IntegratesToOneAndHasItsMeanCosine) {
  for (const auto& [name, params] : phaseCases()) {
    SCOPED_TRACE(name + " " + params);
    const auto phase = makePhaseFunction(name, params);
    const auto f = [&](double mu) { return phase->eval(mu); };
    // The forward half finely: HG(0.95) and Mie peak at θ = 0.
    const double total = integrateTheta(f, 0, 0.2, 20000) + integrateTheta(f, 0.2, kPi, 20000);
    EXPECT_NEAR(total, 1, 1e-6);
    const auto fm = [&](double mu) { return mu * phase->eval(mu); };
    const double mean = integrateTheta(fm, 0, 0.2, 20000) + integrateTheta(fm, 0.2, kPi, 20000);
    EXPECT_NEAR(mean, phase->meanCosine(), 1e-6);
  }
}

TEST(Phase, MeanCosinesAreTheirParameters) {
  EXPECT_DOUBLE_EQ(HenyeyGreensteinPhase(0.63).meanCosine(), 0.63);
  EXPECT_DOUBLE_EQ(DoubleHenyeyGreensteinPhase(0.9, -0.6, 0.7).meanCosine(),
                   0.7 * 0.9 + 0.3 * -0.6);
  // The quadrature of the one before checks these against the densities; here the formulas.
  EXPECT_EQ(RayleighPhase().meanCosine(), 0);
  EXPECT_EQ(IsotropicPhase().meanCosine(), 0);
}

/// χ² of 200 000 samples in 64 bins of cos θ against the density integrated over each bin.
void expectSamplesFollowDensity(const PhaseFunction& phase, const std::string& label,
                                std::uint64_t stream) {
  const int bins = 64, samples = 200000;
  std::vector<double> observed(bins, 0), expected(bins);
  for (int b = 0; b < bins; ++b) {
    const double mu0 = -1 + 2.0 * b / bins, mu1 = -1 + 2.0 * (b + 1) / bins;
    expected[b] = samples * integrateTheta([&](double mu) { return phase.eval(mu); },
                                           std::acos(mu1), std::acos(mu0), 4000);
  }
  Rng rng(7, stream, 0);
  for (int i = 0; i < samples; ++i) {
    double pdf = -1;
    const double mu = phase.sample(rng.uniform(), pdf);
    ASSERT_GE(mu, -1);
    ASSERT_LE(mu, 1);
    ASSERT_NEAR(pdf, phase.eval(mu), 1e-9 * std::max(1.0, pdf)) << label << " at " << mu;
    observed[std::min(bins - 1, int((mu + 1) / 2 * bins))] += 1;
  }
  EXPECT_GT(test::chiSquarePValue(observed, expected, "media_phase_" + label, 1e-3), 1e-3) << label;
}

TEST(Phase, SamplingPassesChiSquare) {
  std::uint64_t stream = 0;
  for (const auto& [name, params] : phaseCases()) {
    SCOPED_TRACE(name + " " + params);
    expectSamplesFollowDensity(*makePhaseFunction(name, params), name, ++stream);
  }
}

TEST(Phase, TabulatedIsExactForLinearDensities) {
  // p ∝ 1 + cos θ is linear in cos θ: the table on any grid represents it exactly.
  std::vector<double> theta = forwardRefinedAngles(7), values;
  for (double t : theta) values.push_back(3 * (1 + std::cos(t)));
  const TabulatedPhase table(theta, values);
  for (double mu : {-1.0, -0.3, 0.0, 0.5, 1.0})
    EXPECT_NEAR(table.eval(mu), (1 + mu) / (4 * kPi), 1e-14);
  EXPECT_NEAR(table.meanCosine(), 1.0 / 3, 1e-14);
  EXPECT_NEAR(table.probability(-1, 0), 0.25, 1e-14);
}

TEST(Phase, RegistryRejectsUnknownNamesKeysAndRanges) {
  const auto message = [](const std::string& name, const std::string& params) {
    try {
      makePhaseFunction(name, params);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no exception");
  };
  EXPECT_NE(message("hg", "").find("henyey-greenstein"), std::string::npos);
  const std::string unknownKey = message("henyey-greenstein", "g=0.5, gg=1");
  EXPECT_NE(unknownKey.find("gg"), std::string::npos) << unknownKey;
  const std::string range = message("henyey-greenstein", "g=1");
  EXPECT_NE(range.find("\"g\""), std::string::npos) << range;
  EXPECT_NE(range.find("(-1, 1)"), std::string::npos) << range;
  EXPECT_NE(message("double-henyey-greenstein", "w=1.5").find("[0, 1]"), std::string::npos);
  EXPECT_NE(message("mie-cloud", "v_eff=0.6").find("v_eff"), std::string::npos);
  EXPECT_NE(message("rayleigh", "g=0.5").find("rayleigh has no parameters"), std::string::npos);
  EXPECT_EQ(range.rfind("phase function \"henyey-greenstein\": ", 0), 0u) << range;
  EXPECT_NE(message("henyey-greenstein", "g=abc").find("finite number"), std::string::npos);
}

TEST(Mie, SmallSpheresScatterAsRayleigh) {
  // x → 0: p → 3(1 + cos²θ)/(16π) and Q_sca → (8/3)x⁴|(m² − 1)/(m² + 2)|² (Bohren and Huffman
  // 1983, section 5.2); the corrections are O(x²) = 1e-4.
  const double x = 0.01;
  const std::complex<double> m(1.33, 0);
  std::vector<double> mus;
  for (int i = 0; i <= 20; ++i) mus.push_back(std::cos(kPi * i / 20));
  const MieSphere s = mieSphere(x, m, mus);
  for (size_t i = 0; i < mus.size(); ++i) {
    const double rayleigh = 3 * (1 + mus[i] * mus[i]) / (16 * kPi);
    EXPECT_NEAR(s.phase(int(i), x) / rayleigh, 1, 1e-3) << "cos θ " << mus[i];
  }
  const double qRayleigh = 8.0 / 3 * std::pow(x, 4) * std::norm((m * m - 1.0) / (m * m + 2.0));
  EXPECT_NEAR(s.qsca / qRayleigh, 1, 1e-3);
  EXPECT_LT(std::fabs(s.g), 1e-3);
}

TEST(Mie, BohrenHuffmanTestCase) {
  // Bohren and Huffman's appendix A example: m = 1.55, r = 0.525 µm, λ = 0.6328 µm,
  // x = 5.21282; Q_ext = Q_sca = 3.10543 as printed there. Q_back, g and the phase function
  // (to 8 digits) as scripts/mie-crosscheck.py computes them from scipy's Bessel functions.
  const double x = 5.21282;
  const std::vector<double> mus = {1 - 1e-9, 0.5, 0, -0.5, -1 + 1e-9};
  const MieSphere s = mieSphere(x, {1.55, 0}, mus);
  EXPECT_NEAR(s.qext, 3.105425, 2e-6);
  EXPECT_NEAR(s.qsca, 3.105425, 2e-6);
  EXPECT_NEAR(s.qback, 2.925339, 2e-6);
  EXPECT_NEAR(s.g, 0.633137, 2e-6);
  const double phase[] = {1.95628559, 0.06292441, 0.02437549, 0.01256854, 0.07496271};
  for (int i = 0; i < 5; ++i) EXPECT_NEAR(s.phase(i, x) / phase[i], 1, 1e-6) << mus[i];
}

TEST(Mie, AbsorbingSphere) {
  // m = 1.5 + 0.1i, x = 10, two ways.
  const std::vector<double> mus = {1 - 1e-9, 0.5, 0, -0.5, -1 + 1e-9};
  const MieSphere s = mieSphere(10, {1.5, 0.1}, mus);
  EXPECT_NEAR(s.qext, 2.459791, 2e-6);
  EXPECT_NEAR(s.qsca, 1.235144, 2e-6);
  EXPECT_NEAR(s.g, 0.922350, 2e-6);
  const double phase[] = {9.77163055, 1.66724993e-02, 4.73044214e-03, 3.00286233e-03,
                          5.97418804e-03};
  for (int i = 0; i < 5; ++i) EXPECT_NEAR(s.phase(i, 10) / phase[i], 1, 1e-6) << mus[i];
}

TEST(Mie, NonAbsorbingSpheresAbsorbNothing) {
  for (double x : {0.1, 1.0, 5.0, 50.0, 300.0}) {
    const MieSphere s = mieSphere(x, {1.333, 0});
    EXPECT_NEAR(s.qabs(), 0, 1e-12 * s.qext) << "x " << x;
  }
}

TEST(Mie, CloudDropletAsymmetry) {
  // Water (m = 1.333, Hale and Querry 1973) droplet of r = 10 µm at 550 nm: x = 114.24. Two
  // ways: Q_ext = 2.028658, g = 0.863044. Cloud droplets' g in the visible is ~0.85–0.87 in the
  // literature (Hansen and Travis 1974's cloud models); the band below allows that much.
  const double x = 2 * kPi * 10e-6 / 550e-9;
  const MieSphere s = mieSphere(x, {1.333, 0});
  EXPECT_NEAR(s.qext, 2.028658, 2e-6);
  EXPECT_NEAR(s.g, 0.863044, 2e-6);
  EXPECT_GT(s.g, 0.84);
  EXPECT_LT(s.g, 0.88);
}

TEST(Mie, ExtinctionParadox) {
  // Q_ext → 2 as x → ∞ (BH section 4.4.3); at x = 1000, two ways: 2.022811.
  const MieSphere s = mieSphere(1000, {1.333, 0});
  EXPECT_NEAR(s.qext / 2, 1, 0.02);
  EXPECT_NEAR(s.qext, 2.022811, 2e-6);
}

TEST(Mie, CloudTable) {
  const MiePhase cloud = mieCloud();
  std::printf(
      "mie cloud (r_eff 10 µm, v_eff 0.1, %zu radii, %zu angles): %.2f s, g %.6f, "
      "<C_sca> %.6g m², albedo %.9f\n",
      cloud.radii.size(), cloud.theta.size(), cloud.seconds, cloud.g, cloud.crossSectionScattering,
      cloud.singleScatteringAlbedo());
  // The table before its own normalisation integrates to 1 (trapezoids in cos θ on its grid):
  // the grid resolves the forward peak.
  double total = 0;
  for (size_t i = 0; i + 1 < cloud.theta.size(); ++i)
    total += 2 * kPi * (std::cos(cloud.theta[i]) - std::cos(cloud.theta[i + 1])) *
             (cloud.phase[i] + cloud.phase[i + 1]) / 2;
  EXPECT_NEAR(total, 1, 2e-3);
  const double gLo = std::min(cloud.radiusG.front(), cloud.radiusG.back());
  const double gHi = std::max(cloud.radiusG.front(), cloud.radiusG.back());
  EXPECT_GT(cloud.g, gLo);
  EXPECT_LT(cloud.g, gHi);
  const TabulatedPhase table = cloud.table();
  EXPECT_NEAR(table.meanCosine(), cloud.g, 1e-3);
  EXPECT_NEAR(cloud.singleScatteringAlbedo(), 1, 1e-12);
  // The quadrature reproduces Hansen and Travis's definitions: r_eff = ⟨r³⟩/⟨r²⟩ and
  // v_eff = ⟨(r − r_eff)² r²⟩/(r_eff² ⟨r²⟩) are the distribution's parameters.
  double m2 = 0, m3 = 0, spread = 0, number = 0;
  for (size_t j = 0; j < cloud.radii.size(); ++j) {
    const double r = cloud.radii[j], w = cloud.weights[j];
    number += w, m2 += w * r * r, m3 += w * r * r * r;
  }
  const double rEff = m3 / m2;
  for (size_t j = 0; j < cloud.radii.size(); ++j)
    spread += cloud.weights[j] * std::pow(cloud.radii[j] - rEff, 2) * std::pow(cloud.radii[j], 2);
  EXPECT_NEAR(rEff, 10e-6, 1e-11);
  EXPECT_NEAR(spread / (rEff * rEff * m2), 0.1, 1e-6);
  // Droplets much larger than λ: ⟨C_ext⟩/(π⟨r²⟩) is near the extinction paradox's 2 (somewhat
  // above it: Q_ext of the smaller droplets, x ~ 5–50, reaches 2.5–4).
  const double qext = cloud.crossSectionExtinction / (kPi * m2 / number);
  EXPECT_GT(qext, 2.0);
  EXPECT_LT(qext, 2.2);
  expectSamplesFollowDensity(table, "mie_cloud_table", 99);
}

}  // namespace
}  // namespace radkit::media
