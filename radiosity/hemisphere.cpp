// hemisphere: the ray-traced hemicube. K rays leave patch i from points uniform on it
// (pdf 1/A_i) in cosine-distributed directions (pdf cosθ/π); the fraction whose first hit
// is the front of patch j estimates F_ij, because cosθ_i cosθ_j/(π r²) dA_j is exactly the
// cosine-weighted measure of the directions through dA_j (Cohen & Wallace ch. 4).
// F_ij = hits_j/K, standard error sqrt(F(1−F)/K) (binomial). Each row costs K rays whatever
// the number of patches, and reciprocity cannot halve it (a row comes from one shooter).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "radiosity/form_factor_method.h"
#include "radiosity/patch_pairs.h"
#include "util/params.h"
#include "util/sampling.h"

namespace radkit {

namespace {
class Hemisphere final : public FormFactorMethod {
 public:
  Hemisphere(const PatchMesh& mesh, const Visibility& visibility, const FormFactorSettings& s)
      : m_table(mesh), m_visibility(visibility), m_settings(s) {}

  std::string name() const override { return "hemisphere"; }
  std::string describe() const override {
    std::ostringstream d;
    d << "hemisphere: K=" << m_settings.samples
      << " cosine-distributed rays per patch from Latin-hypercube points, F_ij = hits_j/K, "
      << "seed " << m_settings.seed;
    return d.str();
  }
  RowCoverage coverage() const override { return RowCoverage::FullRow; }
  void computeRow(int i, RowResult& out) const override;

 private:
  PatchTable m_table;
  const Visibility& m_visibility;
  FormFactorSettings m_settings;
};

void Hemisphere::computeRow(int i, RowResult& out) const {
  out.clear();
  auto start = std::chrono::steady_clock::now();
  const PatchInfo& p = m_table[i];
  const int K = m_settings.samples;
  if (p.area <= 0) return;
  Rng rng(m_settings.seed, std::uint64_t(i), std::uint64_t(i));
  std::vector<double> u;
  std::vector<int> scratch, hits;
  latinHypercube(K, 4, rng, u, scratch);
  Frame frame(p.normal);
  const double eps = m_visibility.epsilon();
  for (int k = 0; k < K; ++k) {
    const double* s = &u[std::size_t(k) * 4];
    Vec3 x = samplePatchUniform(p.v, p.count, p.split, s[0], s[1]) + p.normal * eps;
    Vec3 w = frame.toWorld(sampleCosineHemisphere(s[2], s[3]));
    auto hit = m_visibility.closestHit(x, w, 0.0);
    // A hit on a back face carries nothing to that patch (cos⁺ at the receiver).
    if (hit && hit->patch != i && dot(w, m_table[hit->patch].normal) < 0)
      hits.push_back(hit->patch);
  }
  out.raysCast = K;
  std::sort(hits.begin(), hits.end());
  for (std::size_t a = 0; a < hits.size();) {
    std::size_t b = a;
    while (b < hits.size() && hits[b] == hits[a]) ++b;
    double f = double(b - a) / K;
    out.entries.push_back({hits[a], f, std::sqrt(f * (1 - f) / K)});
    a = b;
  }
  out.pairsFacing = static_cast<long long>(out.entries.size());
  out.raySeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}
}  // namespace

std::unique_ptr<FormFactorMethod> createHemisphere(Params&, const PatchMesh& mesh,
                                                   const Visibility& visibility,
                                                   const FormFactorSettings& settings) {
  return std::make_unique<Hemisphere>(mesh, visibility, settings);
}

}  // namespace radkit
