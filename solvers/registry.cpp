// The one table of solvers (pbrt-v4's hand-written name -> constructor chain, not static-init
// registration). The CLI's --solvers, its help text, the C++ API and the tests all read it.
#include "solvers/registry.h"

#include <stdexcept>

namespace radkit {

// Defined in the solver's own .cpp (one class per file, no header).
std::unique_ptr<Solver> makeJacobiSolver(SolverParams& params);
std::unique_ptr<Solver> makeGaussSeidelSolver(SolverParams& params);
std::unique_ptr<Solver> makeSorSolver(SolverParams& params);
std::unique_ptr<Solver> makeSouthwellSolver(SolverParams& params);
std::unique_ptr<Solver> makeConjugateGradientSolver(SolverParams& params);

namespace {

struct SolverEntry {
  const char* name;
  std::unique_ptr<Solver> (*make)(SolverParams&);
  const char* help;
};

constexpr SolverEntry kSolvers[] = {
    {"jacobi", makeJacobiSolver, "Jacobi sweeps (the bounce series); no parameters"},
    {"gauss-seidel", makeGaussSeidelSolver, "Gauss-Seidel sweeps; no parameters"},
    {"sor", makeSorSolver,
     "successive over-relaxation; omega=W (0 < W < 2; default 0: Young's estimate), "
     "power_iterations=K (30)"},
    {"southwell", makeSouthwellSolver,
     "progressive refinement, one shot per iteration; no parameters"},
    {"cg", makeConjugateGradientSolver,
     "preconditioned conjugate gradient, needs reciprocal F; replace_every=K (50)"},
};

}  // namespace

std::unique_ptr<Solver> makeSolver(const std::string& name, SolverParams params) {
  for (const SolverEntry& entry : kSolvers)
    if (name == entry.name) {
      std::unique_ptr<Solver> solver = entry.make(params);
      params.rejectUnused(name);
      return solver;
    }
  std::string known;
  for (const SolverEntry& entry : kSolvers)
    known += (known.empty() ? "" : ", ") + std::string(entry.name);
  throw std::invalid_argument("unknown solver '" + name + "'; known solvers: " + known);
}

std::vector<std::string> solverNames() {
  std::vector<std::string> names;
  for (const SolverEntry& entry : kSolvers) names.emplace_back(entry.name);
  return names;
}

std::vector<std::string> solverHelp() {
  std::vector<std::string> help;
  for (const SolverEntry& entry : kSolvers)
    help.push_back(std::string(entry.name) + ": " + entry.help);
  return help;
}

}  // namespace radkit
