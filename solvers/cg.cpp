// Preconditioned conjugate gradient on the symmetric form of the radiosity system.
// Row i of (I − ρF)B = E times A_i/ρ_i gives M B = b with M = diag(A/ρ) − A F: symmetric when
// F is reciprocal (A_i F_ij = A_j F_ji), and positive definite for ρ < 1 since it is strictly
// diagonally dominant with a positive diagonal. Patches with ρ_i = 0 (per channel) have
// B_i = E_i exactly: they are eliminated, their light moving to the right-hand side,
//   b_i = (A_i/ρ_i) E_i + A_i Σ_{j: ρ_j = 0} F_ij E_j   for ρ_i > 0.
// Jacobi (diagonal) preconditioning D_i = A_i/ρ_i − A_i F_ii makes the method independent of the
// area scale: D^{-1/2} M D^{-1/2} = I − (off-diagonal part), spectrum within [1 − ρ, 1 + ρ], so
// iterations grow like sqrt((1 + ρ)/(1 − ρ)) (Hestenes & Stiefel 1952; Saad 2003, §9.2).
// The true residual is r = (ρ/A) (b − M B) on eliminated-free rows, 0 on the others; every
// `replace_every` steps (default 50) it is recomputed from F to stop the recurrence drifting.
// F must be reciprocal: on a matrix that is only approximately so, CG is run on A F as given and
// can stagnate at about the reciprocity error; the driver's checked residual then shows it.
#include <stdexcept>

#include "solvers/solver.h"

namespace radkit {

namespace {

class ConjugateGradientSolver final : public Solver {
 public:
  explicit ConjugateGradientSolver(int replaceEvery) : m_replaceEvery(replaceEvery) {}

  std::string name() const override { return "cg"; }
  std::string describe() const override {
    return "Jacobi-preconditioned conjugate gradient on diag(A/rho) - A F (needs reciprocity), "
           "rho = 0 patches eliminated, residual replaced every " +
           std::to_string(m_replaceEvery) + " steps";
  }

  void start(const RadiositySystem& system, const SolverSettings& settings) override {
    system.validate();
    m_system = &system;
    m_norm = settings.norm;
    m_iterations = 0;
    const int n = system.size();
    m_b = system.emission;  // exact on ρ = 0 patches, initial guess elsewhere
    m_diagonal = makeChannels(n);
    const FormFactorMatrix& f = system.matrix();
    for (int i = 0; i < n; ++i) {
      const double fii = std::visit([i](const auto& m) { return double(m(i, i)); }, f);
      for (int c = 0; c < 3; ++c) {
        const double rho = system.reflectance[c][i], a = system.area[i];
        m_diagonal[c][i] = rho > 0.0 ? a / rho - a * fii : 0.0;
      }
    }
    m_p = makeChannels(n);
    m_z = makeChannels(n);
    m_q = makeChannels(n);
    m_active = {true, true, true};
    replaceResidual();
    for (int c = 0; c < 3; ++c) m_p[c] = m_z[c];
  }

  void step() override {
    ++m_iterations;
    applyM(m_p, m_q);
    for (int c = 0; c < 3; ++c) {
      if (!m_active[c]) continue;
      const double pq = dot(m_p[c], m_q[c]);
      if (!(pq > 0.0) || m_rz[c] == 0.0) {  // exact solution reached in this channel
        m_active[c] = false;
        continue;
      }
      const double alpha = m_rz[c] / pq;
      for (std::size_t i = 0; i < m_b[c].size(); ++i) {
        m_b[c][i] += alpha * m_p[c][i];
        m_r[c][i] -= alpha * m_q[c][i];
      }
    }
    if (m_replaceEvery > 0 && m_iterations % m_replaceEvery == 0) {
      const Rgb previous = m_rz;
      replaceResidual();
      updateDirections(previous);
    } else {
      const Rgb previous = m_rz;
      precondition();
      updateDirections(previous);
      measure();
    }
  }

  const Channels& radiosity() const override { return m_b; }
  double residual() const override { return m_residual; }
  double unshotPower() const override { return m_power; }
  double sweeps() const override { return static_cast<double>(m_iterations); }

 private:
  /// y = M x = diag(A/ρ) x − A F x on ρ > 0 rows, 0 elsewhere (x is 0 there too).
  void applyM(const Channels& x, Channels& y) {
    multiply(m_system->matrix(), x, y);
    const RadiositySystem& s = *m_system;
    for (int c = 0; c < 3; ++c)
      for (int i = 0; i < s.size(); ++i) {
        const double rho = s.reflectance[c][i], a = s.area[i];
        y[c][i] = rho > 0.0 ? (a / rho) * x[c][i] - a * y[c][i] : 0.0;
      }
  }

  /// r = b − M B = (A/ρ) (E + ρFB − B) from a pass over F, then z and r·z.
  void replaceResidual() {
    const RadiositySystem& s = *m_system;
    m_trueResidual = residualVector(s, m_b);
    m_r = m_trueResidual;
    for (int c = 0; c < 3; ++c)
      for (int i = 0; i < s.size(); ++i) {
        const double rho = s.reflectance[c][i];
        m_r[c][i] = rho > 0.0 ? s.area[i] / rho * m_trueResidual[c][i] : 0.0;
        if (rho == 0.0) m_trueResidual[c][i] = 0.0;  // B = E there: exact by construction
      }
    precondition();
    m_residual = residualMeasure(s, m_trueResidual, m_b, m_norm);
    m_power = residualPower(s, m_trueResidual);
  }

  void precondition() {
    for (int c = 0; c < 3; ++c) {
      for (std::size_t i = 0; i < m_r[c].size(); ++i)
        m_z[c][i] = m_diagonal[c][i] > 0.0 ? m_r[c][i] / m_diagonal[c][i] : 0.0;
      m_rz[c] = dot(m_r[c], m_z[c]);
    }
  }

  /// p = z + β p with β = (r·z)_new / (r·z)_old (Fletcher-Reeves form).
  void updateDirections(const Rgb& previous) {
    for (int c = 0; c < 3; ++c) {
      if (!m_active[c]) continue;
      const double beta = previous[c] > 0.0 ? m_rz[c] / previous[c] : 0.0;
      for (std::size_t i = 0; i < m_p[c].size(); ++i) m_p[c][i] = m_z[c][i] + beta * m_p[c][i];
    }
  }

  /// True residual from the recurrence: E + ρFB − B = (ρ/A) r.
  void measure() {
    const RadiositySystem& s = *m_system;
    for (int c = 0; c < 3; ++c)
      for (int i = 0; i < s.size(); ++i)
        m_trueResidual[c][i] = s.reflectance[c][i] / s.area[i] * m_r[c][i];
    m_residual = residualMeasure(s, m_trueResidual, m_b, m_norm);
    m_power = residualPower(s, m_trueResidual);
  }

  int m_replaceEvery;
  const RadiositySystem* m_system = nullptr;
  ResidualNorm m_norm = ResidualNorm::Relative;
  Channels m_b, m_r, m_z, m_p, m_q, m_diagonal, m_trueResidual;
  Rgb m_rz{0.0, 0.0, 0.0};
  std::array<bool, 3> m_active{true, true, true};
  double m_residual = 0.0, m_power = 0.0;
  long m_iterations = 0;
};

}  // namespace

std::unique_ptr<Solver> makeConjugateGradientSolver(Params& params) {
  // 0: never replace the recursive residual by the true one.
  const long replaceEvery = params.integer("replace_every", 50, 0, 1000000000);
  return std::make_unique<ConjugateGradientSolver>(static_cast<int>(replaceEvery));
}

}  // namespace radkit
