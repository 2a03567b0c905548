#include "solvers/convergence.h"

#include <iomanip>

namespace radkit {

std::vector<Milestone> milestones(const SolveResult& result, const std::vector<double>& levels) {
  std::vector<Milestone> out;
  for (double level : levels) {
    Milestone m;
    m.level = level;
    for (const HistoryRow& row : result.history)
      if (row.residual <= level) {
        m.reached = true;
        m.iterations = row.iteration;
        m.seconds = row.seconds;
        m.sweeps = row.sweeps;
        break;
      }
    out.push_back(m);
  }
  return out;
}

}  // namespace radkit
