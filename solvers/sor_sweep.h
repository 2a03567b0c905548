// The successive over-relaxation sweep shared by Gauss-Seidel (ω = 1) and SOR.
#pragma once

#include "solvers/radiosity_system.h"
#include "solvers/solver.h"

namespace radkit {

/// \brief One SOR sweep for three channels (Cohen & Wallace 1993, §5.3.2–5.3.3):
///        B_i^{k+1} = B_i^k + ω (E_i + ρ_i (Σ_{j<i} F_ij B_j^{k+1} + Σ_{j>=i} F_ij B_j^k) − B_i^k),
///        streaming F once. In the same pass it returns the exact residual of B^k,
///        r_i = E_i + ρ_i Σ_j F_ij B_j^k − B_i^k.
///
/// The residual's lower part Σ_{j<i} F_ij B^k_j is the previous sweep's gathering sum, kept in
/// `lower`, so each entry of F is multiplied with three vectors only, as in Jacobi, instead of
/// six (B^{k+1} and B^k left of the diagonal), which had nearly doubled the loads per entry.
///
/// Rows are taken in blocks of kSorBlockRows: the part of each row left of the block only reads
/// finished B^{k+1}, the part right of it only B^k, so both are computed in parallel over the
/// block's rows; only the diagonal block (n·kSorBlockRows entries per sweep) runs sequentially.
/// The arithmetic is the sequential sweep's, and bit-identical for any thread count.
/// \param old   B^k (not modified)
/// \param next  receives B^{k+1}; resized to n
/// \param lower on entry Σ_{j<i} F_ij B^k_j, on return Σ_{j<i} F_ij B^{k+1}_j
/// \param r     receives r(B^k); resized to n
void sorSweep(const RadiositySystem& system, const Rgb& omega, const Channels& old, Channels& next,
              Channels& lower, Channels& r);

/// \brief lower_i = Σ_{j<i} F_ij x_j, the `lower` a first sorSweep from x needs.
void lowerTriangleProduct(const RadiositySystem& system, const Channels& x, Channels& lower);

/// Rows per block of sorSweep.
constexpr int kSorBlockRows = 128;

/// The state both Gauss-Seidel and SOR keep: B^k (reported), B^{k+1} (already swept) and the
/// exact residual of B^k, so each step costs one pass over F and reports an exact residual.
class SorIteration {
 public:
  /// \brief B^0 = E and one sweep (which yields r(B^0) and B^1). ω per channel, in (0, 2).
  void start(const RadiositySystem& system, const SolverSettings& settings, const Rgb& omega);
  /// \brief B^k <- B^{k+1}, then sweep for B^{k+2} and r(B^{k+1}).
  void step();
  const Channels& radiosity() const { return m_b; }
  double residual() const { return m_residual; }
  double unshotPower() const { return m_power; }
  long iterations() const { return m_iterations; }

 private:
  void sweep();

  const RadiositySystem* m_system = nullptr;
  ResidualNorm m_norm = ResidualNorm::Relative;
  Rgb m_omega{1.0, 1.0, 1.0};
  Channels m_b, m_next, m_lower, m_r;  ///< m_lower: Σ_{j<i} F_ij B^k_j, from the last sweep
  double m_residual = 0.0, m_power = 0.0;
  long m_iterations = 0;
};

/// The Solver plumbing Gauss-Seidel and SOR share: both step a SorIteration and differ only
/// in name, description and how they choose ω at start().
class SorIterationSolver : public Solver {
 public:
  void step() override { m_iteration.step(); }
  const Channels& radiosity() const override { return m_iteration.radiosity(); }
  double residual() const override { return m_iteration.residual(); }
  double unshotPower() const override { return m_iteration.unshotPower(); }
  double sweeps() const override { return static_cast<double>(m_iteration.iterations()); }

 protected:
  SorIteration m_iteration;
};

}  // namespace radkit
