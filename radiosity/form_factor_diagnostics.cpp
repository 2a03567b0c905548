// Row sums, reciprocity errors and the JSON form of the diagnostics.
#include "radiosity/form_factor_diagnostics.h"

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "radiosity/form_factor_storage.h"

namespace radkit {

namespace {
struct ReciprocityError {
  double maxRelative = 0, sumAbs = 0, sumBoth = 0;
};

// Visits each unordered pair once through the stored entries: (i, j) with i < j, and
// (j, i) with F_ij = 0 stored only on one side.
ReciprocityError reciprocity(const FormFactorMatrix& f, const PatchMesh& mesh) {
  ReciprocityError e;
  forEachNonZero(f, [&](int i, int j, double fij) {
    double fji = formFactorAt(f, j, i);
    if (i > j && fji != 0) return;  // counted from (j, i)
    double a = mesh.patches[i].area * fij, b = mesh.patches[j].area * fji;
    double diff = std::fabs(a - b), big = std::max(std::fabs(a), std::fabs(b));
    if (big > 0) e.maxRelative = std::max(e.maxRelative, diff / big);
    e.sumAbs += diff;
    e.sumBoth += std::fabs(a) + std::fabs(b);
  });
  return e;
}
}  // namespace

double maxRelativeReciprocityError(const FormFactorMatrix& f, const PatchMesh& mesh) {
  return reciprocity(f, mesh).maxRelative;
}

void measureFormFactorMatrix(const FormFactorMatrix& f, const PatchMesh& mesh,
                             FormFactorDiagnostics& d) {
  const int n = matrixSize(f);
  std::vector<double> rowSum(n, 0.0);
  std::size_t nonZeros = 0;
  forEachNonZero(f, [&](int i, int, double v) {
    rowSum[i] += v;
    ++nonZeros;
  });
  d.patches = n;
  d.nonZeros = nonZeros;
  d.matrixBytes = matrixBytes(f);
  d.storage = storageName(f);
  if (n > 0) {
    d.rowSumMin = *std::min_element(rowSum.begin(), rowSum.end());
    d.rowSumMax = *std::max_element(rowSum.begin(), rowSum.end());
    double sum = 0, deviation = 0;
    for (double s : rowSum) sum += s, deviation = std::max(deviation, std::fabs(1 - s));
    d.rowSumMean = sum / n;
    d.maxDeviationFromOne = deviation;
  }
  ReciprocityError e = reciprocity(f, mesh);
  d.maxRelativeReciprocityError = e.maxRelative;
  d.meanRelativeReciprocityError = e.sumBoth > 0 ? e.sumAbs / e.sumBoth : 0.0;
}

nlohmann::json toJson(const FormFactorDiagnostics& d) {
  nlohmann::json phases = nlohmann::json::object();
  for (const auto& [name, seconds] : d.phaseSeconds) phases[name] = seconds;
  nlohmann::json j = {
      {"method", d.method},
      {"description", d.description},
      {"storage", d.storage},
      {"patches", d.patches},
      {"non_zeros", d.nonZeros},
      {"matrix_bytes", d.matrixBytes},
      {"row_sum",
       {{"min", d.rowSumMin},
        {"max", d.rowSumMax},
        {"mean", d.rowSumMean},
        {"max_abs_deviation_from_one", d.maxDeviationFromOne}}},
      {"reciprocity",
       {{"max_relative_error", d.maxRelativeReciprocityError},
        {"mean_relative_error", d.meanRelativeReciprocityError},
        {"max_relative_error_before_enforcement", d.maxRelativeReciprocityErrorBeforeEnforcement},
        {"by_construction", d.reciprocityByConstruction},
        {"enforced", d.reciprocityEnforced}}},
      {"pairs",
       {{"facing", d.pairsFacing},
        {"culled_unblockable", d.pairsCulled},
        {"overlapping", d.overlappingPairs}}},
      {"rays",
       {{"cast", d.raysCast},
        {"saved", d.raysSaved},
        {"per_second", d.raysPerSecond},
        {"thread_seconds", d.rayThreadSeconds}}},
      {"quadrature_points", d.quadraturePoints},
      {"kernel_points", d.kernelPoints},
      {"geometry_thread_seconds", d.geometryThreadSeconds},
      {"threads", d.threads},
      {"seconds", phases},
      {"warnings", d.warnings},
  };
  if (!d.pairsByRule.empty()) {
    nlohmann::json rules = {{"adaptive_contour", d.pairsByRule[0]}};
    for (std::size_t n = 1; n < d.pairsByRule.size(); ++n)
      rules["tensor_level_" + std::to_string(n)] = d.pairsByRule[n];
    j["pairs"]["by_rule"] = rules;
  }
  if (d.overlappingPairs > 0)
    j["pairs"]["first_overlap"] = {d.firstOverlap.first, d.firstOverlap.second};
  return j;
}

}  // namespace radkit
