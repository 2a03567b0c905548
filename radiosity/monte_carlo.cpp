// monte-carlo: the classic area-to-area estimator with K point pairs (x_k, y_k) uniform on
// patches i and j (pdf 1/A_i · 1/A_j), stratified by a Latin hypercube:
//   F_ij = (1/A_i) ∫∫ cosθ_i cosθ_j V/(π r²) dA_j dA_i  ≈  (A_j/K) Σ_k cosθ_i cosθ_j V/(π r²)
// (Cohen & Wallace ch. 4, the double area integral). Standard error from the same samples.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "radiosity/form_factor_method.h"
#include "radiosity/occluder_culling.h"
#include "radiosity/patch_pairs.h"
#include "util/params.h"
#include "util/sampling.h"

namespace radkit {

namespace {
using Clock = std::chrono::steady_clock;

class MonteCarlo final : public FormFactorMethod {
 public:
  MonteCarlo(const PatchMesh& mesh, const Visibility& visibility, const FormFactorSettings& s)
      : m_table(mesh), m_culling(mesh, m_table), m_visibility(visibility), m_settings(s) {}

  std::string name() const override { return "monte-carlo"; }
  std::string describe() const override {
    std::ostringstream d;
    d << "monte-carlo: K=" << m_settings.samples
      << " Latin-hypercube point pairs per patch pair, F_ij = A_j/K sum cos cos V/(pi r^2), "
      << "F_ji by reciprocity, seed " << m_settings.seed;
    return d.str();
  }
  RowCoverage coverage() const override { return RowCoverage::UpperTriangle; }
  void computeRow(int i, RowResult& out) const override;

 private:
  RowEntry estimate(int i, int j, bool mayBeBlocked, RowResult& out, std::vector<double>& u,
                    std::vector<int>& scratch) const;

  PatchTable m_table;
  OccluderCulling m_culling;
  const Visibility& m_visibility;
  FormFactorSettings m_settings;
};

RowEntry MonteCarlo::estimate(int i, int j, bool mayBeBlocked, RowResult& out,
                              std::vector<double>& u, std::vector<int>& scratch) const {
  const PatchInfo& pi = m_table[i];
  const PatchInfo& pj = m_table[j];
  const int K = m_settings.samples;
  Rng rng(m_settings.seed, std::uint64_t(i), std::uint64_t(j));
  latinHypercube(K, 4, rng, u, scratch);
  double sum = 0, sumSquares = 0;
  for (int k = 0; k < K; ++k) {
    const double* s = &u[std::size_t(k) * 4];
    Vec3 x = samplePatchUniform(pi.v, pi.count, pi.split, s[0], s[1]);
    Vec3 y = samplePatchUniform(pj.v, pj.count, pj.split, s[2], s[3]);
    Vec3 d = y - x;
    double r2 = dot(d, d);
    double cosI = dot(pi.normal, d), cosJ = -dot(pj.normal, d);  // both times r
    if (!(cosI > 0 && cosJ > 0 && r2 > 0)) continue;
    // Divide the kernel by the pdf of y (1/A_j); x's pdf 1/A_i cancels F's leading 1/A_i.
    double value = cosI * cosJ / (M_PI * r2 * r2) / patchUniformPdf(pj.area);
    if (mayBeBlocked) {
      ++out.raysCast;
      if (m_visibility.occluded(x, pi.normal, y, pj.normal)) continue;
    } else {
      ++out.raysSaved;
    }
    sum += value;
    sumSquares += value * value;
  }
  double mean = sum / K;
  double variance = K > 1 ? std::max(0.0, (sumSquares - K * mean * mean) / (K - 1)) : mean * mean;
  return {j, mean, std::sqrt(variance / K)};
}

void MonteCarlo::computeRow(int i, RowResult& out) const {
  out.clear();
  Clock::time_point start = Clock::now();
  std::vector<double> u;
  std::vector<int> scratch;
  for (int j = i + 1; j < m_table.size(); ++j) {
    if (!m_table.facing(i, j)) {
      if (m_table.coplanar(i, j) && m_table[i].bounds.overlaps(m_table[j].bounds) &&
          m_table.overlapArea(i, j) > 0 && out.overlappingPairs++ == 0)
        out.firstOverlap[0] = i, out.firstOverlap[1] = j;
      continue;
    }
    ++out.pairsFacing;
    bool blockable = !m_settings.cullUnblockable || m_culling.mayBeBlocked(i, j);
    out.pairsCulled += !blockable;
    RowEntry e = estimate(i, j, blockable, out, u, scratch);
    if (e.value > 0) out.entries.push_back(e);
  }
  out.raySeconds = std::chrono::duration<double>(Clock::now() - start).count();
}
}  // namespace

std::unique_ptr<FormFactorMethod> createMonteCarlo(Params&, const PatchMesh& mesh,
                                                   const Visibility& visibility,
                                                   const FormFactorSettings& settings) {
  return std::make_unique<MonteCarlo>(mesh, visibility, settings);
}

}  // namespace radkit
