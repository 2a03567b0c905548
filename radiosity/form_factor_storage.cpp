// Storage planning for the form-factor matrix.
#include "radiosity/form_factor_storage.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <cmath>
#include <cstdint>
#include <cstdio>

#include "radiosity/patch_pairs.h"
#include "util/setting_names.h"

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
  return storageName() + ": " + formatBytes(double(bytes)) + " needed (" + std::to_string(patches) +
         " patches; budget " + formatBytes(double(budget)) + ")";
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

/// A lower bound on the facing pairs, from a fixed sample of pairs: the exact count costs n²/2
/// tests (48 s at 100 000 patches), too long to spend before refusing a mesh that cannot fit.
/// The bound is the sample's fraction less five standard errors, so it errs low.
long long facingPairsLowerBound(const PatchMesh& mesh) {
  PatchTable table(mesh);
  const long long n = table.size();
  const long long pairs = n * (n - 1) / 2;
  const int samples = 200000;
  if (pairs <= 4LL * samples) return 0;         // the exact count is as quick
  std::uint64_t state = 0x9E3779B97F4A7C15ULL;  // fixed seed: the same mesh, the same answer
  auto next = [&] {
    state ^= state << 13, state ^= state >> 7, state ^= state << 17;
    return state;
  };
  long long hits = 0;
  for (int k = 0; k < samples; ++k) {
    const int a = int(next() % std::uint64_t(n));
    int b = int(next() % std::uint64_t(n - 1));
    if (b >= a) ++b;
    hits += table.facing(a, b);
  }
  const double p = double(hits) / samples;
  const double low = p - 5 * std::sqrt(p * (1 - p) / samples);
  return low > 0 ? (long long)(low * double(pairs)) : 0;
}

// CSR of 2·pairs entries plus the per-row (column, value) lists it is assembled from.
std::size_t sparseBytes(int n, long long pairs, std::size_t scalar) {
  std::size_t nnz = std::size_t(2 * pairs);
  std::size_t entry = 16;  // std::pair<int, double> per entry while assembling
  return (std::size_t(n) + 1) * sizeof(std::int64_t) + nnz * (sizeof(int) + scalar) + nnz * entry +
         std::size_t(n) * 24;
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
  const long long atLeast = facingPairsLowerBound(mesh);
  const bool estimated = sparseBytes(n, atLeast, scalar) > plan.budget;
  plan.facingPairs = estimated ? atLeast : countFacingPairs(mesh);
  plan.sparseBytes = sparseBytes(n, plan.facingPairs, scalar);
  plan.bytes = plan.sparseBytes;
  if (plan.sparseBytes <= plan.budget) return plan;

  std::string msg = "form factors for " + std::to_string(n) + " patches do not fit the memory " +
                    "budget of " + formatBytes(double(plan.budget)) + ": dense needs " +
                    formatBytes(double(plan.denseBytes)) + ", sparse " +
                    (estimated ? "at least " : "up to ") + formatBytes(double(plan.sparseBytes)) +
                    " (" + (estimated ? "at least " : "") + std::to_string(plan.facingPairs) +
                    " facing pairs" + (estimated ? ", estimated from 200000 sampled pairs" : "") +
                    "). Fix: raise " + setting("memory_budget") + ", " + fewerPatchesFix();
  if (settings.precision == FormFactorPrecision::Double)
    msg += "or store F in single precision (" + setting("ff_storage") + " float: dense " +
           formatBytes(double(plan.denseBytes) / 2) + ", sparse " +
           (estimated ? "at least " : "up to ") +
           formatBytes(double(sparseBytes(n, plan.facingPairs, 4))) + ")";
  if (msg.size() >= 2 && msg.compare(msg.size() - 2, 2, ", ") == 0) msg.resize(msg.size() - 2);
  const std::size_t smallest =
      std::min(std::size_t(n) * std::size_t(n) * 4, sparseBytes(n, plan.facingPairs, 4));
  throw MemoryBudgetError(msg, n, smallest, plan.budget);
}

double formFactorAt(const FormFactorMatrix& f, int i, int j) {
  return std::visit([&](const auto& m) { return double(m(i, j)); }, f);
}

}  // namespace radkit
