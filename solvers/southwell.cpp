// Southwell iteration = progressive refinement (Cohen, Chen, Wallace & Greenberg 1988; shown to
// be Southwell's method by Gortler, Cohen & Slusallek 1993). Each step shoots the patch with the
// largest unshot power A_i Σ_c ΔB_ic (the sum over channels is the patch's power in W):
//   ΔB_j += ρ_j F_ji ΔB_i = ρ_j F_ij (A_i / A_j) ΔB_i,   B_j += the same,   ΔB_i = 0.
// The second form uses reciprocity A_i F_ij = A_j F_ji, so a shot reads row i of F only; on a
// matrix that is not reciprocal the method solves the system with F_ji replaced by
// F_ij A_i/A_j (see docs/solvers.md).
//
// Invariant: B = E + ρF(B − ΔB), so ΔB is the exact residual of B − ΔB and r(B) = ρFΔB, whose
// ∞-norm is at most ‖ρF‖∞ ‖ΔB‖∞ <= ‖ΔB‖∞ in a valid enclosure. residual() reports ‖ΔB‖: an upper
// bound that costs nothing (the exact r(B) would cost a pass over F per shot).
//
// Display-only ambient term (Cohen et al. 1988, eq. 6-7): B_amb = Σ ΔB_i A_i / Σ A_i / (1 − ρ̄),
// ρ̄ the area-weighted mean reflectance, shown as B_i + ρ_i B_amb; never added to B.
#include <cmath>

#include "solvers/solver.h"

namespace radkit {

namespace {

class SouthwellSolver final : public Solver {
 public:
  std::string name() const override { return "southwell"; }
  std::string describe() const override {
    return "Southwell iteration (progressive refinement): shoot the largest unshot power "
           "A_i sum_c dB_ic, one shot per iteration, row i of F by reciprocity";
  }

  void start(const RadiositySystem& system, const SolverSettings& settings) override {
    system.validate();
    m_system = &system;
    m_norm = settings.norm;
    m_b = system.emission;
    m_unshot = system.emission;
    m_sweeps = 0.0;
    m_emissionNorm = system.emissionNorm();
    double areaSum = 0.0;
    Rgb weighted{0.0, 0.0, 0.0};
    for (int i = 0; i < system.size(); ++i) {
      areaSum += system.area[i];
      for (int c = 0; c < 3; ++c) weighted[c] += system.area[i] * system.reflectance[c][i];
    }
    m_areaSum = areaSum;
    for (int c = 0; c < 3; ++c) m_meanReflectance[c] = weighted[c] / areaSum;
    measure();
  }

  void step() override {
    if (m_shooter < 0) return;  // nothing left to shoot: B is exact
    const int i = m_shooter;
    std::visit([&](const auto& m) { shoot(m, i); }, m_system->matrix());
    measure();
  }

  const Channels& radiosity() const override { return m_b; }
  double residual() const override { return m_residual; }
  double unshotPower() const override { return m_power; }
  double sweeps() const override { return m_sweeps; }
  Rgb ambient() const override {
    Rgb a{0.0, 0.0, 0.0};
    for (int c = 0; c < 3; ++c) {
      double unshot = 0.0;
      for (int i = 0; i < m_system->size(); ++i) unshot += m_unshot[c][i] * m_system->area[i];
      a[c] = unshot / m_areaSum / (1.0 - m_meanReflectance[c]);
    }
    return a;
  }

 private:
  template <typename Matrix>
  void shoot(const Matrix& m, int i) {
    const RadiositySystem& s = *m_system;
    const Rgb d{m_unshot[0][i], m_unshot[1][i], m_unshot[2][i]};
    for (int c = 0; c < 3; ++c) m_unshot[c][i] = 0.0;  // before the loop: F_ii may be non-zero
    const double areaI = s.area[i];
    forEachInRow(m, i, [&](int j, double fij) {
      const double transfer = fij * areaI / s.area[j];  // F_ji by reciprocity
      for (int c = 0; c < 3; ++c) {
        const double shot = s.reflectance[c][j] * transfer * d[c];
        m_unshot[c][j] += shot;
        m_b[c][j] += shot;
      }
    });
    m_sweeps += static_cast<double>(rowEntries(m, i)) / static_cast<double>(storedEntries(m));
  }

  /// One pass: next shooter, residual ‖ΔB‖ in the chosen norm, unshot power.
  void measure() {
    const RadiositySystem& s = *m_system;
    double best = 0.0, power = 0.0, largest = 0.0, perPatch = 0.0;
    m_shooter = -1;
    for (int i = 0; i < s.size(); ++i) {
      double sum = 0.0;
      for (int c = 0; c < 3; ++c) {
        const double d = std::fabs(m_unshot[c][i]);
        sum += d;
        largest = std::max(largest, d);
        const double scale = std::max(std::fabs(m_b[c][i]), std::fabs(m_b[c][i] - m_unshot[c][i]));
        if (scale > 0.0) perPatch = std::max(perPatch, d / scale);
      }
      const double patchPower = s.area[i] * sum;
      power += patchPower;
      if (patchPower > best) {
        best = patchPower;
        m_shooter = i;
      }
    }
    m_power = power;
    const double e = m_emissionNorm;
    m_residual = m_norm == ResidualNorm::PerPatch ? perPatch : (e > 0.0 ? largest / e : largest);
  }

  const RadiositySystem* m_system = nullptr;
  ResidualNorm m_norm = ResidualNorm::Relative;
  Channels m_b, m_unshot;
  Rgb m_meanReflectance{0.0, 0.0, 0.0};
  double m_areaSum = 0.0, m_emissionNorm = 0.0, m_residual = 0.0, m_power = 0.0, m_sweeps = 0.0;
  int m_shooter = -1;
};

}  // namespace

std::unique_ptr<Solver> makeSouthwellSolver(Params&) { return std::make_unique<SouthwellSolver>(); }

}  // namespace radkit
