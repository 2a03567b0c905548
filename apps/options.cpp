#include "apps/options.h"

#include <cmath>

#include "apps/common.h"
#include "hierarchy/hierarchical.h"
#include "solvers/registry.h"
#include "util/params.h"

namespace radkit::app {

std::size_t parseBytes(const std::string& text) {
  std::size_t used = 0;
  double value = 0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    throw CLI::ValidationError("--memory-budget",
                               "'" + text + "' is not a size (e.g. 8GiB, 512MiB)");
  }
  std::string unit = text.substr(used);
  double scale = unit.empty() || unit == "B" ? 1
                 : unit == "KiB"             ? 1024.0
                 : unit == "MiB"             ? 1024.0 * 1024
                 : unit == "GiB"             ? 1024.0 * 1024 * 1024
                 : unit == "TiB"             ? 1024.0 * 1024 * 1024 * 1024
                                             : -1;
  if (scale < 0 || !(value > 0) || !std::isfinite(value))
    throw CLI::ValidationError("--memory-budget",
                               "'" + text + "' is not a positive size in B, KiB, MiB, GiB or TiB");
  // Converting a double beyond size_t's range is undefined; no machine has 2^60 bytes.
  if (value * scale >= std::ldexp(1.0, 60))
    throw CLI::ValidationError("--memory-budget",
                               "'" + text +
                                   "' is larger than 1048576 TiB. Fix: give the memory "
                                   "F may use, e.g. 8GiB");
  return std::size_t(value * scale);
}

void FormFactorOptions::finish() {
  // --ff NAME:key=value;...: the method's own parameters, read when it is built.
  const PluginChoice choice = splitPluginChoice(settings.method);
  settings.method = choice.name;
  settings.parameters = choice.parameters;
  try {
    formFactorTraits(choice.name);
  } catch (const std::invalid_argument& e) {
    throw CLI::ValidationError("--ff", e.what());
  }
  if (!enforce.empty() && enforce != "reciprocity")
    throw CLI::ValidationError("--ff-enforce", "the only value is 'reciprocity'");
  settings.enforceReciprocity = enforce == "reciprocity";
  settings.precision =
      storage == "float" ? FormFactorPrecision::Float : FormFactorPrecision::Double;
  settings.memoryBudget = parseBytes(memoryBudget);
  try {
    validateFormFactorSettings(settings);
  } catch (const std::invalid_argument& e) {
    throw CLI::ValidationError(e.what());
  }
}

void SolverOptions::finish() {
  stopping.norm = norm == "per-patch" ? ResidualNorm::PerPatch : ResidualNorm::Relative;
  try {
    choices = parseSolverList(solvers);
  } catch (const std::invalid_argument& e) {
    throw CLI::ValidationError("--solvers", e.what());
  }
}

void addFormFactorOptions(CLI::App& c, FormFactorOptions& o) {
  std::string methods;
  for (const std::string& line : formFactorMethodHelp()) methods += "\n  " + line;
  c.add_option("--ff", o.settings.method,
               "Form-factor method, its own parameters after ':' separated by ';' "
               "(point-polygon:pair_levels=2):" +
                   methods)
      ->capture_default_str();
  c.add_option("--ff-samples", o.settings.samples,
               "Rays (or point pairs) per patch pair, K >= 1; hemisphere: rays per "
               "patch. Default: the method's own (see --ff)")
      ->check(CLI::PositiveNumber);
  c.add_option("--seed", o.settings.seed, "Seed of every random stream (same seed, same output)")
      ->check(Unsigned)
      ->capture_default_str();
  c.add_option("--ff-pair-levels", o.settings.quadrature.pairLevels,
               "point-polygon: highest tensor Gauss-Legendre level (1-8) a pair may take when "
               "its error bound allows; 0 integrates every pair by the adaptive contour "
               "cubature (docs/formfactors.md)")
      ->check(CLI::Range(0, 8))
      ->capture_default_str();
  c.add_option("--ff-enforce", o.enforce,
               "'reciprocity': replace A_iF_ij and A_jF_ji by their mean (off by default)");
  c.add_option("--ff-storage", o.storage, "Form-factor storage precision")
      ->check(CLI::IsMember({"double", "float"}))
      ->capture_default_str();
  c.add_option("--memory-budget", o.memoryBudget,
               "Memory F may use (dense when it fits, else sparse). The hierarchical "
               "method's tree and links: 3/4 of this machine's memory unless given")
      ->capture_default_str();
}

void addSolverOptions(CLI::App& c, SolverOptions& o, const std::string& defaultSolvers) {
  o.solvers = defaultSolvers;
  std::string help;
  for (const std::string& line : solverHelp()) help += "\n  " + line;
  c.add_option("--solvers,--solver", o.solvers,
               "Comma-separated solvers, parameters after ':' separated by ';' "
               "(sor:omega=1.2;power_iterations=40):" +
                   help)
      ->capture_default_str();
  c.add_option("--tol", o.stopping.tolerance,
               "Stop at relative residual ||E + rho F B - B|| / ||E|| <= tol")
      ->check(FinitePositive)
      ->capture_default_str();
  c.add_option("--max-iterations", o.stopping.maxIterations,
               "Stop after this many iterations (shots for southwell; default " +
                   std::to_string(SolverSettings{}.maxIterations) + "; hierarchical: sweeps, " +
                   "default " + std::to_string(kDefaultHierarchicalSweeps) + ")")
      ->check(CLI::PositiveNumber);
  c.add_option("--max-seconds", o.stopping.maxSeconds, "Stop a solver after this many seconds")
      ->check(FinitePositive);
  c.add_option("--residual-norm", o.norm,
               "relative: infinity norm over ||E||; per-patch: worst patch relative to its own B")
      ->check(CLI::IsMember({"relative", "per-patch"}))
      ->capture_default_str();
}

}  // namespace radkit::app
