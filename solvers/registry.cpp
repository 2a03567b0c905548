// The one table of solvers (util/registry.h). The CLI's --solvers, its help text, the C++ API,
// the Python module and the tests all read it.
#include "solvers/registry.h"

namespace radkit {

// Defined in the solver's own .cpp (one class per file, no header).
std::unique_ptr<Solver> makeJacobiSolver(Params& params);
std::unique_ptr<Solver> makeGaussSeidelSolver(Params& params);
std::unique_ptr<Solver> makeSorSolver(Params& params);
std::unique_ptr<Solver> makeSouthwellSolver(Params& params);
std::unique_ptr<Solver> makeConjugateGradientSolver(Params& params);

const Registry<Solver>& solverRegistry() {
  static const Registry<Solver> registry(
      "solver",
      {
          {"jacobi", makeJacobiSolver, "Jacobi sweeps (the bounce series); no parameters", ""},
          {"gauss-seidel", makeGaussSeidelSolver, "Gauss-Seidel sweeps; no parameters", ""},
          {"sor", makeSorSolver,
           "successive over-relaxation; omega=W (0 < W < 2; default 0: Young's estimate), "
           "power_iterations=K (30)",
           "omega=1.2, power_iterations=40"},
          {"southwell", makeSouthwellSolver,
           "progressive refinement, one shot per iteration; no parameters", ""},
          {"cg", makeConjugateGradientSolver,
           "preconditioned conjugate gradient, needs reciprocal F; replace_every=K (50)",
           "replace_every=20"},
      });
  return registry;
}

std::unique_ptr<Solver> makeSolver(const std::string& name, Params params) {
  return solverRegistry().make(name, std::move(params));
}

std::vector<std::string> solverNames() { return solverRegistry().names(); }

std::vector<std::string> solverHelp() {
  std::vector<std::string> help;
  for (const auto& entry : solverRegistry().entries())
    help.push_back(std::string(entry.name) + ": " + entry.help);
  return help;
}

}  // namespace radkit
