// Radiosity systems with analytic form factors (no geometry) and a long-double direct solve:
// the oracles of the solver tests (docs/oracles.md, Closed-form radiosity).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "solvers/radiosity_system.h"
#include "solvers/registry.h"

namespace radkit::test {

/// A system that owns its matrix (heap-held, so the system's pointer survives moves).
struct Problem {
  std::shared_ptr<FormFactorMatrix> f;
  RadiositySystem system;
};

enum class Storage { DenseDouble, DenseFloat, CsrDouble, CsrFloat };
std::string storageLabel(Storage s);
inline const Storage kAllStorages[] = {Storage::DenseDouble, Storage::DenseFloat,
                                       Storage::CsrDouble, Storage::CsrFloat};

/// \brief Problem from a dense F (row-major, n x n), areas, ρ and E per channel, in storage s.
Problem makeProblem(const std::vector<double>& f, std::vector<double> area, Channels rho,
                    Channels e, Storage s = Storage::DenseDouble);

/// The same values, uniform over channels.
Channels grey(const std::vector<double>& v);

/// Sphere interior: F_ij = A_j / A (Σ_j F_ij = 1, reciprocal).
std::vector<double> sphereFormFactors(const std::vector<double>& area);

/// Two infinite parallel plates: F12 = F21 = 1.
std::vector<double> platesFormFactors();

/// Closed unit cube, faces (0,1), (2,3), (4,5) opposite: F_opposite = 0.199824895698387,
/// F_adjacent = 0.200043776075403 (rows sum to 1 up to rounding).
std::vector<double> cubeFormFactors();
constexpr double kCubeOpposite = 0.199824895698387;
constexpr double kCubeAdjacent = 0.200043776075403;

/// Random reciprocal enclosure: S symmetric positive (zero diagonal), A in [0.5, 2],
/// F_ij = c S_ij / A_i with c making the largest row sum 0.98. ρ in [0, 0.9) with about one
/// patch in five at ρ = 0; E in [0, 1) with about half the patches dark.
Problem randomReciprocal(int n, unsigned seed, Storage s = Storage::DenseDouble);

/// \brief Solves (I − ρF) B = E per channel by Gaussian elimination with partial pivoting in
///        long double. F taken from the problem's storage.
Channels directSolve(const RadiositySystem& system);

/// \brief max_i |a_i − b_i| / max_i |b_i| over all channels.
double relativeError(const Channels& a, const Channels& b);

/// \brief solve() with the named registry solver.
inline SolveResult runSolver(const std::string& name, const RadiositySystem& system,
                             double tolerance, ResidualNorm norm = ResidualNorm::Relative,
                             long maxIterations = 10000000, Params params = {}) {
  SolverSettings settings;
  settings.tolerance = tolerance;
  settings.norm = norm;
  settings.maxIterations = maxIterations;
  auto solver = makeSolver(name, std::move(params));
  return solve(*solver, system, settings);
}

/// Cube with uniform ρ and face 0 emitting 1 in every channel.
inline Problem cubeOneEmitter(double rho, Storage s = Storage::DenseDouble) {
  std::vector<double> e(6, 0.0);
  e[0] = 1.0;
  return makeProblem(cubeFormFactors(), std::vector<double>(6, 1.0),
                     grey(std::vector<double>(6, rho)), grey(e), s);
}

/// Ten equal patches of a sphere interior, ρ = 0.7, E = (1, 0, ..., 0).
inline Problem tenPatchSphere(Storage s = Storage::DenseDouble) {
  std::vector<double> area(10, 1.0), e(10, 0.0);
  e[0] = 1.0;
  return makeProblem(sphereFormFactors(area), area, grey(std::vector<double>(10, 0.7)), grey(e), s);
}

}  // namespace radkit::test
