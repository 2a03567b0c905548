#include "solvers/solver.h"
#include "util/format.h"
#include "util/setting_names.h"

#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace radkit {

namespace {

std::string number(double v) { return formatNumber(v, 3); }

std::string rateText(double rate) {
  return std::isnan(rate) ? std::string() : ", estimated spectral radius " + number(rate);
}

/// Notices steps that change nothing the driver sees: B, the residual and the unshot power
/// exactly as before. Such a solver repeats itself to the iteration limit (a Python step() that
/// never updates B; cg with every channel stopped on a non-reciprocal F) while its residual
/// neither falls to the rounding floor the stagnation rule waits at nor grows. The unshot power
/// counts because B alone can stand still while a solver progresses: Southwell shooting light
/// too faint to change B in the last bit, its ΔB still falling. B is copied only when the
/// residual and the power repeat exactly, so a run that makes progress pays nothing.
class FrozenWatch {
 public:
  /// Whether nothing changed over at least one step and one sweep (or n steps, for a solver
  /// whose sweeps() does not advance); call once per iteration.
  bool update(long iteration, const Solver& solver) {
    const double r = solver.residual(), power = solver.unshotPower();
    if (iteration == 0 || !(r == m_residual && power == m_power)) {
      m_residual = r, m_power = power;
      m_watching = false;
      return false;
    }
    if (!m_watching || solver.radiosity() != m_b) {
      m_b = solver.radiosity();
      m_since = iteration;
      m_sinceSweeps = solver.sweeps();
      m_watching = true;
      return false;
    }
    const long steps = iteration - m_since;
    return steps >= 1 &&
           (solver.sweeps() - m_sinceSweeps >= 1.0 || steps >= static_cast<long>(m_b[0].size()));
  }
  long since() const { return m_since; }

 private:
  double m_residual = 0.0, m_power = 0.0;
  bool m_watching = false;
  Channels m_b;
  long m_since = 0;
  double m_sinceSweeps = 0.0;
};

/// Empty when the run goes on; otherwise why it stops (and result.exit, result.converged).
std::string stopReason(const Solver& solver, const SolverSettings& settings, long iteration,
                       double seconds, double emissionNorm, ConvergenceMonitor& p,
                       const FrozenWatch& frozen, bool isFrozen, SolveResult& result) {
  const double r = solver.residual();
  const std::string tail = " after " + std::to_string(iteration) + " iterations";
  result.converged = false;
  // Iterating B ← E + ρFB diverges when some row of ρF sums above 1 (noisy or
  // non-physical form factors): B grows without bound and turns inf, then NaN.
  // A million-fold growth over the starting residual is divergence too, caught long before
  // B overflows; none of the methods grows its residual that far on a convergent system.
  if (!std::isfinite(r) || !allFinite(solver.radiosity()) || r > 1e6 * p.startResidual) {
    result.exit = "diverged";
    return "diverged: the residual grew to " + number(r) + tail +
           " (rows of rho F sum above 1: check the form factors' row sums, raise " +
           setting("ff_samples") + ")";
  }
  if (r <= settings.tolerance) {
    result.converged = true;
    result.exit = "converged";
    if (emissionNorm == 0.0 && r == 0.0) return "converged: E = 0, so B = 0 is exact";
    return "converged: residual " + number(r) + " <= tolerance " + number(settings.tolerance) +
           tail;
  }
  if (iteration >= settings.maxIterations) {
    result.exit = "max_iterations";
    return "not converged: maximum iterations (" + std::to_string(settings.maxIterations) +
           ") reached with residual " + number(r) + " > tolerance " + number(settings.tolerance) +
           rateText(p.rate);
  }
  if (seconds >= settings.maxSeconds) {
    result.exit = "time_limit";
    return "not converged: time limit " + number(settings.maxSeconds) + " s reached" + tail +
           " with residual " + number(r) + " > tolerance " + number(settings.tolerance) +
           rateText(p.rate);
  }
  // A residual stuck at the rounding floor above the tolerance would run to the iteration
  // limit. Only at the floor: far above it, a residual may rise for a long while and still
  // converge (Gauss-Seidel and Southwell at reflectances near 1).
  const bool longNoLow = solver.sweeps() - p.bestSweeps >= kStagnationSweeps;
  if (isFrozen || longNoLow) {
    const double scale = maxAbs(solver.radiosity()) / std::max(emissionNorm, 1e-300);
    // Above the floor, a step that changed nothing will change nothing again. (At the floor
    // the rule below stops the run, with its own reason.)
    if (isFrozen && r > 1e4 * std::numeric_limits<double>::epsilon() * std::max(1.0, scale)) {
      result.exit = "stagnated";
      return "stagnated: B, the residual " + number(r) +
             " and the unshot power have not changed since iteration " +
             std::to_string(frozen.since()) + ", above tolerance " + number(settings.tolerance) +
             tail +
             ": every further step would repeat the last. Fix: a solver's step() must "
             "update the B its radiosity() returns; cg needs a reciprocal F (A_i F_ij = A_j F_ji)";
    }
    if (longNoLow && p.stagnated(solver.sweeps(), scale)) {
      result.exit = "stagnated";
      return "stagnated: no residual below " + number(p.best) + " for " +
             number(kStagnationSweeps) + " sweeps" + tail + rateText(p.rate) +
             " (rounding error: tolerance " + number(settings.tolerance) +
             " is below what this system reaches; raise " + setting("tol") + ")";
    }
  }
  // Southwell's steps are shots: the iterations left count at the sweeps per step so far.
  const double sweepsPerStep = iteration > 0 ? solver.sweeps() / double(iteration) : 1.0;
  if (p.overBudget(r, settings.tolerance,
                   double(settings.maxIterations - iteration) * sweepsPerStep,
                   settings.maxSeconds - seconds)) {
    result.exit = "predicted_over_budget";
    result.predictedSweeps = p.predicted;
    return p.overBudgetText(r, settings.tolerance, settings, iteration);
  }
  return {};
}

}  // namespace

void ConvergenceMonitor::update(double r, double sweeps, double seconds) {
  if (r < best * (1 - 1e-9)) {
    best = r;
    bestSweeps = sweeps;
  }
  const double span = sweeps - windowSweeps;
  windowEnded = span >= kRateWindowSweeps;
  if (windowEnded || std::isnan(rate)) {
    const bool measured = span > 0 && windowResidual > 0 && r >= 0;
    if (measured) rate = std::pow(r / windowResidual, 1 / span);
    if (windowEnded) {
      previousRate = windowRate;
      windowRate = measured ? rate : kNaN;
      secondsPerSweep = (seconds - windowSeconds) / span;
      ++windows;
      windowSweeps = sweeps;
      windowResidual = r;
      windowSeconds = seconds;
    }
  }
}

void ConvergenceMonitor::restart(double sweeps, double seconds) {
  windowSweeps = sweeps, windowSeconds = seconds, windowResidual = 0.0;
  windowRate = previousRate = kNaN;
  windows = 0;
  windowEnded = false;
}

double ConvergenceMonitor::sweepsToTolerance(double r, double tolerance) const {
  if (windows < 3 || !(r > tolerance) || !(tolerance > 0)) return kNaN;
  const double a = -std::log(windowRate), b = -std::log(previousRate);
  // NaN rates fail these tests too; a rising or flat window predicts nothing (a residual may
  // rise for a long while and still converge: Gauss-Seidel and Southwell at ρ near 1).
  if (!(a > 0) || !(b > 0) || !(std::max(a, b) <= kRateAgreement * std::min(a, b))) return kNaN;
  return std::log(r / tolerance) / std::max(a, b);
}

bool ConvergenceMonitor::overBudget(double r, double tolerance, double sweepsLeft,
                                    double secondsLeft) {
  if (!windowEnded) return false;
  predicted = sweepsToTolerance(r, tolerance);
  if (std::isnan(predicted)) return false;
  affordable = std::max(sweepsLeft, 0.0);
  timeBound = false;
  if (std::isfinite(secondsLeft) && secondsPerSweep > 0 &&
      std::max(secondsLeft, 0.0) / secondsPerSweep < affordable) {
    affordable = std::max(secondsLeft, 0.0) / secondsPerSweep;
    timeBound = true;
  }
  return predicted > kPredictionMargin * affordable;
}

std::string ConvergenceMonitor::overBudgetText(double r, double tolerance,
                                               const SolverSettings& limits, long iteration) const {
  const std::string budget =
      timeBound
          ? setting("max_seconds") + " " + number(limits.maxSeconds) + " leaves at " +
                number(secondsPerSweep) + " s per sweep"
          : setting("max_iterations") + " " + std::to_string(limits.maxIterations) + " leaves";
  return "predicted over budget: at estimated spectral radius " +
         formatNumber(std::min(windowRate, previousRate), 7) + " the residual " + number(r) +
         " needs about " + number(predicted) + " more sweeps to reach tolerance " +
         number(tolerance) + ", over twice the " +
         std::to_string(static_cast<long long>(affordable)) + " sweeps that " + budget +
         " (stopped after " + std::to_string(iteration) + " iterations). Fix: raise " +
         setting("max_iterations") + " or " + setting("max_seconds") + ", loosen " +
         setting("tol") +
         ", or lower the "
         "reflectance (a closed scene with reflectance near 1 converges slowly)";
}

bool ConvergenceMonitor::keep(long iteration, double r) {
  bool newDecade = false;
  if (r > 0 && std::isfinite(r) && int(std::floor(std::log10(r))) < decade) {
    decade = int(std::floor(std::log10(r)));
    newDecade = true;
  }
  if (iteration < 1000 || newDecade) return true;
  long step = 1;
  for (long i = iteration; i >= 1000; i /= 10) step *= 10;
  return iteration % step == 0;
}

bool ConvergenceMonitor::stagnated(double sweeps, double scale) const {
  return sweeps - bestSweeps >= kStagnationSweeps &&
         best <= 1e4 * std::numeric_limits<double>::epsilon() * std::max(1.0, scale);
}

std::string ConvergenceMonitor::rateText() const { return radkit::rateText(rate); }

SolveResult solve(Solver& solver, const RadiositySystem& system, const SolverSettings& settings) {
  SolveResult result;
  result.solver = solver.name();
  const Clock::time_point t0 = Clock::now();
  solver.start(system, settings);
  result.description = solver.describe();
  const double emissionNorm = system.emissionNorm();
  long iteration = 0;
  ConvergenceMonitor progress;
  FrozenWatch frozen;
  progress.startResidual = std::max(solver.residual(), std::numeric_limits<double>::min());
  progress.windowResidual = solver.residual();
  for (;;) {
    const double seconds = secondsSince(t0);
    const HistoryRow row{iteration, seconds, solver.residual(), solver.unshotPower(),
                         solver.sweeps()};
    progress.update(row.residual, row.sweeps, row.seconds);
    const bool isFrozen = frozen.update(iteration, solver);
    result.reason = stopReason(solver, settings, iteration, seconds, emissionNorm, progress, frozen,
                               isFrozen, result);
    if (progress.keep(iteration, row.residual) || !result.reason.empty())
      result.history.push_back(row);
    if (!result.reason.empty()) break;
    solver.step();
    ++iteration;
  }
  result.iterations = iteration;
  result.seconds = result.history.back().seconds;
  result.residual = solver.residual();
  result.spectralRadius = progress.rate;
  result.radiosity = solver.radiosity();
  result.ambient = solver.ambient();
  const Channels r = residualVector(system, result.radiosity);
  result.checkedResidual = residualMeasure(system, r, result.radiosity, settings.norm);
  return result;
}

}  // namespace radkit
