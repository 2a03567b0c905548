#include "solvers/convergence.h"

#include <iomanip>

namespace radkit {

void writeConvergenceHeader(std::ostream& out) {
  out << "solver,iteration,seconds,residual,unshot_power\n";
}

void writeConvergenceRows(std::ostream& out, const SolveResult& result) {
  const auto precision = out.precision(17);
  for (const HistoryRow& row : result.history)
    out << result.solver << ',' << row.iteration << ',' << row.seconds << ',' << row.residual << ','
        << row.unshotPower << '\n';
  out.precision(precision);
}

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
