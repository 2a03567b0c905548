// The solver interface a lab exercise implements (Nori's integrator.h pattern): one header, one
// .cpp per solver with no header, each listed by name in solvers/registry.cpp. A solver runs
// step by step so the caller sees every iteration; solve() is the driver with the stopping rules.
#pragma once

#include <limits>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "solvers/kernels.h"
#include "solvers/radiosity_system.h"
#include "util/params.h"

namespace radkit {

/// Run-wide stopping rules, shared by every solver of a run.
struct SolverSettings {
  double tolerance = 1e-6;         ///< stop when residual() <= tolerance
  long maxIterations = 100000000;  ///< steps (sweeps, or shots for Southwell)
  double maxSeconds = std::numeric_limits<double>::infinity();  ///< wall clock, start included
  ResidualNorm norm = ResidualNorm::Relative;
};

/// An iterative solver for B = E + ρFB, all three channels at once.
class Solver {
 public:
  virtual ~Solver() = default;
  /// \brief Registry name, e.g. "gauss-seidel".
  virtual std::string name() const = 0;
  /// \brief One line with the method and its parameters, for report.json.
  virtual std::string describe() const = 0;
  /// \brief Validates the system and sets the initial guess B = E (iteration 0, its residual
  ///        known). system must outlive the solver's use.
  virtual void start(const RadiositySystem& system, const SolverSettings& settings) = 0;
  /// \brief One iteration: a sweep (Jacobi, Gauss-Seidel, SOR), a shot (Southwell) or a
  ///        conjugate-gradient step. A step after exact convergence leaves B unchanged.
  virtual void step() = 0;
  /// \brief Current radiosity B per channel, W/m².
  virtual const Channels& radiosity() const = 0;
  /// \brief Residual of radiosity() in settings.norm (exact up to rounding for Jacobi,
  ///        Gauss-Seidel, SOR and CG; for Southwell see southwell.cpp: ‖ΔB‖, an upper bound).
  virtual double residual() const = 0;
  /// \brief Σ_i A_i Σ_c |r_ic| in W: the unshot power ΔB·A for Southwell, the residual's
  ///        power for the others.
  virtual double unshotPower() const = 0;
  /// \brief Work since start() in full passes over F: iterations for the sweeping methods,
  ///        Σ (entries of each shot row) / (entries of F) for Southwell.
  virtual double sweeps() const = 0;
  /// \brief Display-only ambient term per channel (Cohen et al. 1988); zero but for Southwell.
  ///        Never part of radiosity().
  virtual Rgb ambient() const { return {0.0, 0.0, 0.0}; }
};

/// One row of convergence.csv.
struct HistoryRow {
  long iteration = 0;
  double seconds = 0.0;
  double residual = 0.0;
  double unshotPower = 0.0;
  double sweeps = 0.0;  ///< sweep-equivalents (see Solver::sweeps)
};

/// What solve() returns.
struct SolveResult {
  std::string solver;       ///< registry name
  std::string description;  ///< describe()
  bool converged = false;
  std::string reason;  ///< why it stopped, one sentence for the console
  long iterations = 0;
  double seconds = 0.0;
  double residual = 0.0;         ///< solver's residual() at the end
  double checkedResidual = 0.0;  ///< recomputed from F by the driver, same norm
  Channels radiosity;
  Rgb ambient{};
  /// Why it stopped, for report.json: "converged", "max_iterations", "time_limit",
  /// "stagnated" (at the rounding floor, no new lowest residual for kStagnationSweeps sweeps),
  /// "predicted_over_budget" (the estimated spectral radius predicts more sweeps to the
  /// tolerance than the limits leave, see ConvergenceMonitor::overBudget) or "diverged".
  std::string exit;
  /// Sweeps still needed to reach the tolerance, predicted from the spectral-radius estimate
  /// when the run stopped as "predicted_over_budget"; NaN otherwise.
  double predictedSweeps = std::numeric_limits<double>::quiet_NaN();
  /// Mean factor by which the residual fell per sweep over the last kRateWindowSweeps sweeps
  /// (or since the start): an estimate of the iteration's spectral radius; NaN before a sweep.
  double spectralRadius = std::numeric_limits<double>::quiet_NaN();
  /// Iteration 0 (after start), every step up to iteration 1000, then logarithmically spaced
  /// (900 rows per decade of iterations), plus the first row below each power of ten of the
  /// residual and the last row: its size stays bounded however long a solver runs.
  std::vector<HistoryRow> history;
};

/// Sweeps without a new lowest residual (by a relative 1e-9), at a residual within 1e4
/// rounding errors of zero, after which solve() stops.
constexpr double kStagnationSweeps = 1000;
/// Sweeps over which SolveResult::spectralRadius is measured.
constexpr double kRateWindowSweeps = 50;
/// A run stops as "predicted_over_budget" only when the prediction exceeds this many times the
/// sweeps it can still afford: a rate that later improves must not cost a run that would have
/// converged.
constexpr double kPredictionMargin = 2;
/// Two consecutive windows' rates count as one stable estimate when their convergence speeds
/// (−log rate per sweep) differ by at most this factor.
constexpr double kRateAgreement = 1.25;

/// What solve() tracks across iterations beyond the solver's own state; the hierarchical gather
/// (hierarchy/hierarchical.cpp) uses it too, so both stop, estimate ρ and keep history alike.
struct ConvergenceMonitor {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  double startResidual = 0.0;
  double best = std::numeric_limits<double>::infinity();  ///< lowest residual so far
  double bestSweeps = 0.0;                                ///< sweeps when it was reached
  double windowSweeps = 0.0, windowResidual = 0.0;        ///< start of the rate window
  double windowSeconds = 0.0;                             ///< its wall-clock time
  double rate = kNaN;                                     ///< see SolveResult::spectralRadius
  /// Rates of the last two completed windows (NaN where a window had no starting residual),
  /// the windows completed since the start (or restart()) and the last one's seconds per sweep.
  double windowRate = kNaN, previousRate = kNaN;
  int windows = 0;
  double secondsPerSweep = kNaN;
  /// Whether the last update() completed a window. overBudget() decides only then: the rate
  /// changes no more often, and a cheap step (a Southwell shot) pays nothing for the test.
  bool windowEnded = false;
  /// Set by overBudget(): sweeps still needed, and the sweeps the limits leave (the smaller of
  /// the iteration and the time budget; timeBound says which).
  double predicted = kNaN, affordable = kNaN;
  bool timeBound = false;
  int decade =
      std::numeric_limits<int>::max();  ///< floor(log10) of the last kept residual's decade

  /// Records residual r after `sweeps` sweep-equivalents at `seconds` on the run's clock: the
  /// lowest so far and the rate.
  void update(double r, double sweeps, double seconds);
  /// Starts the rate windows afresh at `sweeps` (the system changed: a new hierarchical round).
  /// The first window after it gives no rate, as it has no starting residual.
  void restart(double sweeps, double seconds);
  /// Sweeps from residual r down to `tolerance` at the estimated rate; NaN until the rate is
  /// stable: two completed windows after the first (whose fast start misleads) that agree
  /// within kRateAgreement, both falling. The faster of the two is used, so the prediction is
  /// never more than either window's.
  double sweepsToTolerance(double r, double tolerance) const;
  /// Whether, at the end of a window, the stable rate predicts more than kPredictionMargin
  /// times the sweeps the run can still afford: `sweepsLeft` under the iteration limit and, when
  /// `secondsLeft` is finite, as many as fit in it at the last window's seconds per sweep. Sets
  /// predicted and affordable.
  bool overBudget(double r, double tolerance, double sweepsLeft, double secondsLeft);
  /// The console sentence after overBudget() returned true, ending in a Fix; `limits` names the
  /// binding limit's value, `iteration` the steps done.
  std::string overBudgetText(double r, double tolerance, const SolverSettings& limits,
                             long iteration) const;
  /// Whether history row `iteration` is kept: every row up to 1000, then 900 per decade of
  /// iterations, and the first row of each new decade of the residual.
  bool keep(long iteration, double r);
  /// No new lowest residual for kStagnationSweeps sweeps, at a residual within 1e4 rounding
  /// errors of zero (`scale`: largest B over ‖E‖, the size the rounding is relative to).
  bool stagnated(double sweeps, double scale) const;
  /// ", estimated spectral radius R", or nothing before the first estimate.
  std::string rateText() const;
};

/// \brief Runs solver from B = E until residual <= tolerance, maxIterations steps, maxSeconds,
///        stagnation, a prediction over the budget or divergence, recording the history. Throws
///        what start() throws.
SolveResult solve(Solver& solver, const RadiositySystem& system, const SolverSettings& settings);

}  // namespace radkit
