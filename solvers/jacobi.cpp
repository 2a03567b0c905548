// Jacobi iteration (Cohen & Wallace 1993, §5.3.1): B^{k+1} = E + ρ F B^k, every patch gathering
// from the previous iterate. Started from B = E it is the bounce series: term k is the light
// after k bounces. Converges since ‖ρF‖∞ <= max ρ < 1.
//
// Each step streams F once for the three channels and, in the same pass, gathers
// G = E + ρ F B^k, so r(B^k) = G − B^k is exact and free, and the next step just takes B = G.
#include <utility>

#include "solvers/solver.h"

namespace radkit {

namespace {

class JacobiSolver final : public Solver {
 public:
  std::string name() const override { return "jacobi"; }
  std::string describe() const override {
    return "Jacobi iteration B <- E + rho F B, three channels per pass over F";
  }

  void start(const RadiositySystem& system, const SolverSettings& settings) override {
    system.validate();
    m_system = &system;
    m_norm = settings.norm;
    m_b = system.emission;
    m_gathered = makeChannels(system.size());
    m_r = makeChannels(system.size());
    m_iterations = 0;
    gather();
  }

  void step() override {
    std::swap(m_b, m_gathered);  // B^{k+1} = E + ρ F B^k, gathered by the previous pass
    ++m_iterations;
    gather();
  }

  const Channels& radiosity() const override { return m_b; }
  double residual() const override { return m_residual; }
  double unshotPower() const override { return m_power; }
  double sweeps() const override { return static_cast<double>(m_iterations); }

 private:
  /// G = E + ρ F B and r = G − B in one pass over F, parallel over rows.
  void gather() {
    const RadiositySystem& s = *m_system;
    const int n = s.size();
    std::visit(
        [&](const auto& m) {
          const auto bp = channelPointers(m_b);
          forRowBlocks(n, storedEntries(m), [&](int begin, int end) {
            rangeDots<3>(m, begin, end, 0, n, bp, [&](int i, const std::array<double, 3>& fb) {
              for (int c = 0; c < 3; ++c) {
                const double g = s.emission[c][i] + s.reflectance[c][i] * fb[c];
                m_gathered[c][i] = g;
                m_r[c][i] = g - m_b[c][i];
              }
            });
          });
        },
        s.matrix());
    m_residual = residualMeasure(s, m_r, m_b, m_norm);
    m_power = residualPower(s, m_r);
  }

  const RadiositySystem* m_system = nullptr;
  ResidualNorm m_norm = ResidualNorm::Relative;
  Channels m_b, m_gathered, m_r;
  double m_residual = 0.0, m_power = 0.0;
  long m_iterations = 0;
};

}  // namespace

std::unique_ptr<Solver> makeJacobiSolver(Params&) { return std::make_unique<JacobiSolver>(); }

}  // namespace radkit
