// Successive over-relaxation (Cohen & Wallace 1993, §5.3.3): the Gauss-Seidel update scaled by
// ω, B_i <- B_i + ω (gathered_i − B_i). Parameters:
//   omega            ω in (0, 2); 0 (default) estimates it per channel with Young's formula
//                    ω = 2 / (1 + sqrt(1 − ρ_J²)), ρ_J the spectral radius of the Jacobi
//                    iteration matrix ρF, estimated by power iteration;
//   power_iterations at most this many products ρF x for the estimate (default 30).
// Young's formula is optimal for consistently ordered matrices; radiosity matrices are not, so
// the estimate is a heuristic (see docs/solvers.md for what it gives on our test matrices).
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "solvers/sor_sweep.h"

namespace radkit {

namespace {

/// Spectral radius of ρ_c F per channel by power iteration from x = 1 (ρF >= 0, so the
/// Perron root dominates); stops when the estimate changes by less than 1e-4 relative.
Rgb jacobiSpectralRadius(const RadiositySystem& s, int maxIterations) {
  const int n = s.size();
  Channels x = makeChannels(n, 1.0), fx;
  Rgb radius{0.0, 0.0, 0.0};
  for (int k = 0; k < maxIterations; ++k) {
    multiply(s.matrix(), x, fx);
    bool settled = true;
    for (int c = 0; c < 3; ++c) {
      double norm = 0.0, xNorm = 0.0;
      for (int i = 0; i < n; ++i) {
        fx[c][i] *= s.reflectance[c][i];
        norm = std::max(norm, std::fabs(fx[c][i]));
        xNorm = std::max(xNorm, std::fabs(x[c][i]));
      }
      const double estimate = xNorm > 0.0 ? norm / xNorm : 0.0;
      settled = settled && std::fabs(estimate - radius[c]) <= 1e-4 * estimate;
      radius[c] = estimate;
      for (int i = 0; i < n; ++i) x[c][i] = norm > 0.0 ? fx[c][i] / norm : 0.0;
    }
    if (settled) break;
  }
  return radius;
}

class SorSolver final : public SorIterationSolver {
 public:
  SorSolver(double omega, int powerIterations)
      : m_fixedOmega(omega), m_powerIterations(powerIterations) {}

  std::string name() const override { return "sor"; }
  std::string describe() const override {
    std::ostringstream s;
    s << "SOR sweeps, omega = " << m_omega[0] << ", " << m_omega[1] << ", " << m_omega[2]
      << (m_fixedOmega > 0.0 ? " (given)" : " (Young's formula from power iteration)");
    return s.str();
  }
  void start(const RadiositySystem& system, const SolverSettings& settings) override {
    system.validate();
    m_omega = {m_fixedOmega, m_fixedOmega, m_fixedOmega};
    if (m_fixedOmega == 0.0) {
      const Rgb radius = jacobiSpectralRadius(system, m_powerIterations);
      for (int c = 0; c < 3; ++c) {
        const double r = std::min(radius[c], 1.0);
        m_omega[c] = 2.0 / (1.0 + std::sqrt(1.0 - r * r));
      }
    }
    m_iteration.start(system, settings, m_omega);
  }

 private:
  double m_fixedOmega;
  int m_powerIterations;
  Rgb m_omega{1.0, 1.0, 1.0};
};

}  // namespace

std::unique_ptr<Solver> makeSorSolver(Params& params) {
  const double omega =
      params.number("omega", 0.0, 0.0, 2.0, false, true, "use 0 < omega < 2, or 0 to estimate it");
  const long powerIterations = params.integer("power_iterations", 30, 1, 1000000);
  return std::make_unique<SorSolver>(omega, static_cast<int>(powerIterations));
}

}  // namespace radkit
