// Storage planning for the form-factor matrix.
#include "radiosity/form_factor_storage.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <cstdio>

#include "radiosity/patch_pairs.h"

namespace radkit {

std::string formatBytes(double bytes) {
  const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB"};
  int u = 0;
  while (bytes >= 1024 && u < 5) bytes /= 1024, ++u;
  char text[32];
  std::snprintf(text, sizeof text, u == 0 ? "%.0f %s" : "%.2f %s", bytes, units[u]);
  return text;
}

std::string StoragePlan::storageName() const {
  std::string kind = dense ? "dense-" : "csr-";
  return kind + (precision == FormFactorPrecision::Double ? "double" : "float");
}

std::string StoragePlan::describe() const {
  return storageName() + ": " + formatBytes(double(bytes)) + " needed (" +
         std::to_string(patches) + " patches; budget " + formatBytes(double(budget)) + ")";
}

namespace {
long long countFacingPairs(const PatchMesh& mesh) {
  PatchTable table(mesh);
  const int n = table.size();
  return tbb::parallel_reduce(
      tbb::blocked_range<int>(0, n), 0LL,
      [&](const tbb::blocked_range<int>& r, long long count) {
        for (int i = r.begin(); i < r.end(); ++i)
          for (int j = i + 1; j < n; ++j) count += table.facing(i, j);
        return count;
      },
      [](long long a, long long b) { return a + b; });
}

// CSR of 2·pairs entries plus the per-row (column, value) lists it is assembled from.
std::size_t sparseBytes(int n, long long pairs, std::size_t scalar) {
  std::size_t nnz = std::size_t(2 * pairs);
  std::size_t entry = 16;  // std::pair<int, double> per entry while assembling
  return (std::size_t(n) + 1) * sizeof(std::int64_t) + nnz * (sizeof(int) + scalar) +
         nnz * entry + std::size_t(n) * 24;
}
}  // namespace

StoragePlan planStorage(const PatchMesh& mesh, const FormFactorSettings& settings) {
  StoragePlan plan;
  plan.patches = mesh.size();
  plan.precision = settings.precision;
  plan.budget = settings.memoryBudget;
  const int n = plan.patches;
  std::size_t scalar = settings.precision == FormFactorPrecision::Double ? 8 : 4;
  plan.denseBytes = std::size_t(n) * std::size_t(n) * scalar;
  if (plan.denseBytes <= plan.budget) {
    plan.bytes = plan.denseBytes;
    return plan;
  }
  plan.dense = false;
  plan.facingPairs = countFacingPairs(mesh);
  plan.sparseBytes = sparseBytes(n, plan.facingPairs, scalar);
  plan.bytes = plan.sparseBytes;
  if (plan.sparseBytes <= plan.budget) return plan;

  std::string msg = "form factors for " + std::to_string(n) + " patches do not fit the memory " +
                    "budget of " + formatBytes(double(plan.budget)) + ": dense needs " +
                    formatBytes(double(plan.denseBytes)) + ", sparse up to " +
                    formatBytes(double(plan.sparseBytes)) + " (" +
                    std::to_string(plan.facingPairs) + " facing pairs). Raise --memory-budget, " +
                    "use fewer patches (--max-area larger or --patches smaller)";
  if (settings.precision == FormFactorPrecision::Double)
    msg += ", or store F in single precision (--ff-storage float: dense " +
           formatBytes(double(plan.denseBytes / 2)) + ", sparse up to " +
           formatBytes(double(sparseBytes(n, plan.facingPairs, 4))) + ")";
  throw MemoryBudgetError(msg);
}

double formFactorAt(const FormFactorMatrix& f, int i, int j) {
  return std::visit([&](const auto& m) { return double(m(i, j)); }, f);
}

}  // namespace radkit
