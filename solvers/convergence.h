// Convergence output that knows nothing of geometry: convergence.csv rows and the table of
// iterations and seconds to reach 1e-3, 1e-6 and 1e-9 for report.json.
#pragma once

#include <ostream>
#include <vector>

#include "solvers/solver.h"

namespace radkit {

/// \brief Writes the header "solver,iteration,seconds,residual,unshot_power" and a newline.
void writeConvergenceHeader(std::ostream& out);

/// \brief One line per history row of result, 17 significant digits, no header.
void writeConvergenceRows(std::ostream& out, const SolveResult& result);

/// When a run first reached one residual level.
struct Milestone {
  double level = 0.0;
  bool reached = false;
  long iterations = 0;   ///< valid when reached
  double seconds = 0.0;  ///< valid when reached
  double sweeps = 0.0;   ///< sweep-equivalents, valid when reached
};

/// \brief The first history row with residual <= each level, in the order given.
std::vector<Milestone> milestones(const SolveResult& result,
                                  const std::vector<double>& levels = {1e-3, 1e-6, 1e-9});

}  // namespace radkit
