// docs/extending.md, example 4: a phase function. Schlick's rational stand-in for
// Henyey-Greenstein (Blasi, Le Saëc and Schlick 1993), p(μ) = (1 − k²) / (4π (1 − kμ)²), with
// k ∈ (−1, 1) (k ≈ 1.55g − 0.55g³ matches HG's g). Built and tested by tests/extending/.
#include <cmath>
#include <memory>
#include <string>

#include "phase/phase_function.h"
#include "util/params.h"

namespace radkit {

namespace {

class SchlickPhase final : public PhaseFunction {
 public:
  explicit SchlickPhase(double k) : m_k(k) {}

  double eval(double mu) const override {
    const double d = 1 - m_k * mu;
    return (1 - m_k * m_k) / (4 * kPi * d * d);
  }

  // The CDF in μ, (1 − k²)/(2k) (1/(1 − kμ) − 1/(1 + k)), inverted in closed form.
  double sample(double u, double& pdf) const override {
    double mu = 2 * u - 1;
    if (std::fabs(m_k) > 1e-9) {
      const double a = 2 * m_k * u / (1 - m_k * m_k) + 1 / (1 + m_k);
      mu = std::fmin(1.0, std::fmax(-1.0, (1 - 1 / a) / m_k));
    }
    pdf = eval(mu);
    return mu;
  }

  // ⟨μ⟩ = 1/k + (1 − k²)/(2k²) ln((1 − k)/(1 + k)).
  double meanCosine() const override {
    if (std::fabs(m_k) < 1e-6) return 2 * m_k / 3;  // the series' first term
    return 1 / m_k + (1 - m_k * m_k) / (2 * m_k * m_k) * std::log((1 - m_k) / (1 + m_k));
  }

  std::string name() const override { return "schlick"; }

  // The octave model's higher orders: k scaled, as HG scales g.
  double evalAnisotropyScaled(double mu, double scale) const override {
    return SchlickPhase(scale * m_k).eval(mu);
  }

 private:
  double m_k;
};

}  // namespace

// The registry's create function: reads k with its range; the registry rejects unknown keys.
std::unique_ptr<PhaseFunction> createSchlickPhase(Params& params) {
  return std::make_unique<SchlickPhase>(params.number("k", 0.8, -1, 1, true, true));
}

}  // namespace radkit
