// Solvers by name: the one table lives in registry.cpp.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "solvers/solver.h"
#include "util/registry.h"

namespace radkit {

/// \brief Every registered solver, in table order: names, help, examples.
const Registry<Solver>& solverRegistry();

/// \brief A new solver; params are read by the solver and unknown keys rejected.
/// \throws ParamError (a std::invalid_argument) for an unknown name (the message lists the
///         known names) or an unknown or out-of-range parameter.
std::unique_ptr<Solver> makeSolver(const std::string& name, Params params = {});

/// \brief Registered names in table order: jacobi, gauss-seidel, sor, southwell, cg.
std::vector<std::string> solverNames();

/// \brief One-line help per solver, in table order, "name: text".
std::vector<std::string> solverHelp();

}  // namespace radkit
