// The table of iterations and seconds to reach 1e-3, 1e-6 and 1e-9 for report.json
// (convergence.csv itself is written by output/run_files.h).
#pragma once

#include <ostream>
#include <vector>

#include "solvers/solver.h"

namespace radkit {

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
