// Gauss-Seidel iteration (Cohen & Wallace 1993, §5.3.2; Cohen & Greenberg 1985): each patch
// gathers from the values already updated in this sweep. Never slower than Jacobi on the
// radiosity matrix, which is diagonally dominant. The sweep itself is in sor_sweep.cpp (ω = 1).
#include "solvers/sor_sweep.h"

namespace radkit {

namespace {

class GaussSeidelSolver final : public SorIterationSolver {
 public:
  std::string name() const override { return "gauss-seidel"; }
  std::string describe() const override {
    return "Gauss-Seidel sweeps in patch order, three channels per pass over F, blocks of " +
           std::to_string(kSorBlockRows) + " rows";
  }
  void start(const RadiositySystem& system, const SolverSettings& settings) override {
    m_iteration.start(system, settings, {1.0, 1.0, 1.0});
  }
};

}  // namespace

std::unique_ptr<Solver> makeGaussSeidelSolver(Params&) {
  return std::make_unique<GaussSeidelSolver>();
}

}  // namespace radkit
