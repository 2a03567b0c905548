// Phase functions (phase_function.h) and their registry. The analytic ones wrap closed_form.h's
// formulas and samplers; the tabulated one is exact for its piecewise-linear density.
#include "phase/phase_function.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "phase/closed_form.h"
#include "phase/mie.h"
#include "util/format.h"
#include "util/params.h"
#include "util/registry.h"

namespace radkit {

double IsotropicPhase::eval(double) const { return isotropicPhase(); }

double IsotropicPhase::sample(double u, double& pdf) const {
  pdf = isotropicPhase();
  return std::clamp(2 * u - 1, -1.0, 1.0);
}

double RayleighPhase::eval(double cosTheta) const { return rayleighPhase(cosTheta); }

double RayleighPhase::sample(double u, double& pdf) const {
  const double mu = sampleRayleighCosine(u);
  pdf = eval(mu);
  return mu;
}

HenyeyGreensteinPhase::HenyeyGreensteinPhase(double g) : m_g(g) {
  if (!(std::fabs(g) < 1))
    throw std::invalid_argument("henyey-greenstein: g " + formatNumber(g) + " is outside (-1, 1)");
}

double HenyeyGreensteinPhase::eval(double cosTheta) const {
  return henyeyGreensteinPhase(cosTheta, m_g);
}

double HenyeyGreensteinPhase::sample(double u, double& pdf) const {
  const double mu = sampleHenyeyGreensteinCosine(u, m_g);
  pdf = eval(mu);
  return mu;
}

DoubleHenyeyGreensteinPhase::DoubleHenyeyGreensteinPhase(double g1, double g2, double w)
    : m_g1(g1), m_g2(g2), m_w(w) {
  if (!(std::fabs(g1) < 1) || !(std::fabs(g2) < 1) || !(w >= 0 && w <= 1))
    throw std::invalid_argument(
        "double-henyey-greenstein: needs g1, g2 in (-1, 1) and w in "
        "[0, 1]; got g1 " +
        formatNumber(g1) + ", g2 " + formatNumber(g2) + ", w " + formatNumber(w));
}

double DoubleHenyeyGreensteinPhase::eval(double cosTheta) const {
  return m_w * henyeyGreensteinPhase(cosTheta, m_g1) +
         (1 - m_w) * henyeyGreensteinPhase(cosTheta, m_g2);
}

double DoubleHenyeyGreensteinPhase::sample(double u, double& pdf) const {
  // u < w picks the first lobe; u rescaled to [0, 1) within the chosen lobe stays uniform.
  double mu;
  if (u < m_w)
    mu = sampleHenyeyGreensteinCosine(std::min(u / m_w, 1.0), m_g1);
  else
    mu = sampleHenyeyGreensteinCosine(std::min((u - m_w) / (1 - m_w), 1.0), m_g2);
  pdf = eval(mu);
  return mu;
}

TabulatedPhase::TabulatedPhase(const std::vector<double>& theta, const std::vector<double>& values,
                               std::string name)
    : m_name(std::move(name)) {
  const size_t n = theta.size();
  if (n < 2 || values.size() != n)
    throw std::invalid_argument("tabulated phase: needs at least 2 angles and one value each");
  for (size_t i = 0; i < n; ++i) {
    if (!(values[i] >= 0) || !std::isfinite(values[i]))
      throw std::invalid_argument("tabulated phase: value " + std::to_string(i) + " is " +
                                  formatNumber(values[i]) + "; values must be finite and >= 0");
    if (i > 0 && !(theta[i] > theta[i - 1]))
      throw std::invalid_argument("tabulated phase: angles must increase strictly");
  }
  if (std::fabs(theta.front()) > 1e-12 || std::fabs(theta.back() - kPi) > 1e-9)
    throw std::invalid_argument("tabulated phase: angles must run from 0 to pi");
  // Increasing cos θ, so the CDF runs from backward (−1) to forward (1).
  m_mu.resize(n);
  m_p.resize(n);
  for (size_t i = 0; i < n; ++i) {
    m_mu[i] = i == 0 ? -1.0 : i + 1 == n ? 1.0 : std::cos(theta[n - 1 - i]);
    m_p[i] = values[n - 1 - i];
  }
  m_cdf.assign(n, 0);
  double mean = 0;
  for (size_t i = 0; i + 1 < n; ++i) {
    const double a = m_mu[i], b = m_mu[i + 1], h = b - a;
    m_cdf[i + 1] = m_cdf[i] + 2 * kPi * h * (m_p[i] + m_p[i + 1]) / 2;
    mean += 2 * kPi * h / 6 * (m_p[i] * (2 * a + b) + m_p[i + 1] * (a + 2 * b));
  }
  const double total = m_cdf.back();
  if (!(total > 0)) throw std::invalid_argument("tabulated phase: values are all zero");
  for (size_t i = 0; i < n; ++i) m_p[i] /= total, m_cdf[i] /= total;
  m_mean = mean / total;
}

double HenyeyGreensteinPhase::evalAnisotropyScaled(double cosTheta, double scale) const {
  return henyeyGreensteinPhase(cosTheta, scale * m_g);
}

double DoubleHenyeyGreensteinPhase::evalAnisotropyScaled(double cosTheta, double scale) const {
  return m_w * henyeyGreensteinPhase(cosTheta, scale * m_g1) +
         (1 - m_w) * henyeyGreensteinPhase(cosTheta, scale * m_g2);
}

double TabulatedPhase::evalAnisotropyScaled(double cosTheta, double scale) const {
  return henyeyGreensteinPhase(cosTheta, scale * m_mean);
}

double TabulatedPhase::eval(double cosTheta) const {
  const double mu = std::clamp(cosTheta, -1.0, 1.0);
  const size_t i = std::min<size_t>(std::upper_bound(m_mu.begin(), m_mu.end(), mu) - m_mu.begin(),
                                    m_mu.size() - 1);
  const size_t j = i == 0 ? 0 : i - 1;
  const double t = (mu - m_mu[j]) / (m_mu[j + 1] - m_mu[j]);
  return m_p[j] + t * (m_p[j + 1] - m_p[j]);
}

double TabulatedPhase::cdfAt(double mu) const {
  mu = std::clamp(mu, -1.0, 1.0);
  size_t j = std::upper_bound(m_mu.begin(), m_mu.end(), mu) - m_mu.begin();
  j = std::min(j == 0 ? 0 : j - 1, m_mu.size() - 2);
  const double h = m_mu[j + 1] - m_mu[j], t = mu - m_mu[j];
  const double s = (m_p[j + 1] - m_p[j]) / h;
  return m_cdf[j] + 2 * kPi * (m_p[j] * t + s * t * t / 2);
}

double TabulatedPhase::probability(double a, double b) const { return cdfAt(b) - cdfAt(a); }

double TabulatedPhase::sample(double u, double& pdf) const {
  const size_t n = m_mu.size();
  size_t j = std::upper_bound(m_cdf.begin(), m_cdf.end(), u) - m_cdf.begin();
  j = std::min(j == 0 ? 0 : j - 1, n - 2);
  // Solve 2π(p_j t + s t²/2) = u − F_j for t in [0, h], in the form that does not cancel.
  const double h = m_mu[j + 1] - m_mu[j], s = (m_p[j + 1] - m_p[j]) / h;
  const double c = std::max(0.0, u - m_cdf[j]) / (2 * kPi);
  const double disc = std::max(0.0, m_p[j] * m_p[j] + 2 * s * c);
  const double denom = m_p[j] + std::sqrt(disc);
  const double t = denom > 0 ? std::clamp(2 * c / denom, 0.0, h) : 0.0;
  const double mu = std::min(m_mu[j] + t, 1.0);
  pdf = m_p[j] + s * t;
  return mu;
}

std::vector<double> forwardRefinedAngles(int n) {
  if (n < 3) throw std::invalid_argument("forwardRefinedAngles: needs at least 3 points");
  // θ(t) = π t (t + c)/(1 + c), t = i/(n − 1): dθ/dt is πc/(1+c) at 0 and π(2+c)/(1+c) at 1.
  const double c = 0.05;
  std::vector<double> theta(n);
  for (int i = 0; i < n; ++i) {
    const double t = double(i) / (n - 1);
    theta[i] = kPi * t * (t + c) / (1 + c);
  }
  theta.back() = kPi;
  return theta;
}

namespace {

std::unique_ptr<PhaseFunction> createIsotropic(Params&) {
  return std::make_unique<IsotropicPhase>();
}
std::unique_ptr<PhaseFunction> createRayleigh(Params&) { return std::make_unique<RayleighPhase>(); }
std::unique_ptr<PhaseFunction> createHenyeyGreenstein(Params& p) {
  return std::make_unique<HenyeyGreensteinPhase>(p.number("g", 0.8, -1, 1, true, true));
}
std::unique_ptr<PhaseFunction> createDoubleHenyeyGreenstein(Params& p) {
  const double g1 = p.number("g1", 0.8, -1, 1, true, true);
  const double g2 = p.number("g2", -0.3, -1, 1, true, true);
  const double w = p.number("w", 0.9, 0, 1);
  return std::make_unique<DoubleHenyeyGreensteinPhase>(g1, g2, w);
}
std::unique_ptr<PhaseFunction> createMieCloud(Params& p) {
  MieCloudSettings s;
  s.effectiveRadius = p.number("r_eff", 10, 0, 100, true) * 1e-6;
  s.effectiveVariance = p.number("v_eff", 0.1, 0, 0.5, true, true);
  s.wavelength = p.number("wavelength", 0.55, 0.1, 20) * 1e-6;
  s.refractiveIndex = {p.number("n", 1.333, 0, 10, true), p.number("k", 0, 0, 10)};
  p.rejectUnused("mie-cloud");  // before the table's second of work, not after
  return std::make_unique<TabulatedPhase>(mieCloud(s).table());
}

}  // namespace

const Registry<PhaseFunction>& phaseRegistry() {
  static const Registry<PhaseFunction> registry(
      "phase function",
      {
          {"isotropic", createIsotropic, "1/(4 pi); no parameters", ""},
          {"rayleigh", createRayleigh, "3/(16 pi) (1 + cos^2); no parameters", ""},
          {"henyey-greenstein", createHenyeyGreenstein, "g in (-1, 1) (0.8)", "g=0.8"},
          {"double-henyey-greenstein", createDoubleHenyeyGreenstein,
           "w HG(g1) + (1 - w) HG(g2); g1 (0.8), g2 (-0.3), w (0.9)", "g1=0.85, g2=-0.4, w=0.7"},
          {"mie-cloud", createMieCloud,
           "Lorenz-Mie over a gamma droplet distribution, tabulated; r_eff in um (10), v_eff "
           "(0.1), wavelength in um (0.55), n (1.333), k (0)",
           "r_eff=4, v_eff=0.1"},
      });
  return registry;
}

std::unique_ptr<PhaseFunction> makePhaseFunction(const std::string& name,
                                                 const std::string& params) {
  return phaseRegistry().make(name, Params::parse(params));
}

std::vector<std::string> phaseFunctionNames() { return phaseRegistry().names(); }

std::string phaseFunctionExample(const std::string& name) {
  return phaseRegistry().at(name).example;
}

}  // namespace radkit
