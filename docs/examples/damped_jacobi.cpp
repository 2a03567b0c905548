// docs/extending.md, example 1: a solver. Damped Jacobi, B <- B + ω (E + ρFB − B): with
// ω = 1 it is Jacobi; 0 < ω < 1 damps each step. Built and run by tests/extending/.
#include <memory>
#include <stdexcept>
#include <string>

#include "solvers/solver.h"

namespace radkit {

namespace {

class DampedJacobiSolver final : public Solver {
 public:
  explicit DampedJacobiSolver(double omega) : m_omega(omega) {}

  std::string name() const override { return "damped-jacobi"; }
  std::string describe() const override {
    return "damped Jacobi, omega=" + std::to_string(m_omega);
  }

  void start(const RadiositySystem& system, const SolverSettings& settings) override {
    system.validate();
    m_system = &system;
    m_norm = settings.norm;
    m_b = system.emission;
    m_steps = 0;
    update();
  }

  void step() override {
    for (int c = 0; c < 3; ++c)
      for (int i = 0; i < m_system->size(); ++i) m_b[c][i] += m_omega * m_r[c][i];
    ++m_steps;
    update();
  }

  const Channels& radiosity() const override { return m_b; }
  double residual() const override { return m_residual; }
  double unshotPower() const override { return m_power; }
  double sweeps() const override { return double(m_steps); }

 private:
  void update() {  // r = E + ρFB − B, one pass over F
    m_r = residualVector(*m_system, m_b);
    m_residual = residualMeasure(*m_system, m_r, m_b, m_norm);
    m_power = residualPower(*m_system, m_r);
  }

  double m_omega;
  const RadiositySystem* m_system = nullptr;
  ResidualNorm m_norm = ResidualNorm::Relative;
  Channels m_b, m_r;
  double m_residual = 0, m_power = 0;
  long m_steps = 0;
};

}  // namespace

// The registry's factory: reads its parameters (the registry rejects unknown keys after it).
std::unique_ptr<Solver> makeDampedJacobiSolver(Params& params) {
  const double omega = params.number("omega", 0.8, 0.0, 1.0, /*openLo=*/true);
  return std::make_unique<DampedJacobiSolver>(omega);
}

}  // namespace radkit
