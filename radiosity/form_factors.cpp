// The form-factor driver: plan storage, compute rows in parallel, assemble, measure.
#include "radiosity/form_factors.h"
#include "util/format.h"
#include "util/setting_names.h"
#include "util/threads.h"

#include <tbb/blocked_range.h>
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <memory>
#include <mutex>

namespace radkit {

namespace {

/// Work counters summed over rows.
struct Totals {
  long long raysCast = 0, raysSaved = 0, pairsFacing = 0, pairsCulled = 0, overlapping = 0;
  long long quadraturePoints = 0, kernelPoints = 0;
  long long pairsByRule[kPairRuleCount] = {};
  double raySeconds = 0, geometrySeconds = 0;
  std::pair<int, int> firstOverlap{-1, -1};
  void add(const RowResult& r) {
    Totals t;
    t.raysCast = r.raysCast, t.raysSaved = r.raysSaved, t.pairsFacing = r.pairsFacing;
    t.pairsCulled = r.pairsCulled, t.overlapping = r.overlappingPairs;
    t.quadraturePoints = r.quadraturePoints;
    t.kernelPoints = r.kernelPoints;
    std::copy(std::begin(r.pairsByRule), std::end(r.pairsByRule), t.pairsByRule);
    t.raySeconds = r.raySeconds, t.geometrySeconds = r.geometrySeconds;
    t.firstOverlap = {r.firstOverlap[0], r.firstOverlap[1]};
    merge(t);
  }
  void merge(const Totals& t) {
    raysCast += t.raysCast;
    raysSaved += t.raysSaved;
    pairsFacing += t.pairsFacing;
    pairsCulled += t.pairsCulled;
    if (t.overlapping > 0 && (overlapping == 0 || t.firstOverlap < firstOverlap))
      firstOverlap = t.firstOverlap;
    overlapping += t.overlapping;
    quadraturePoints += t.quadraturePoints;
    kernelPoints += t.kernelPoints;
    for (int k = 0; k < kPairRuleCount; ++k) pairsByRule[k] += t.pairsByRule[k];
    raySeconds += t.raySeconds;
    geometrySeconds += t.geometrySeconds;
  }
};

/// Reports the fraction of pair work done, from whichever thread finishes a row; one
/// report at a time, and only when it has moved by at least 0.5 %.
class RowProgress {
 public:
  RowProgress(const FormFactorProgress& report, int n, bool upper)
      : m_report(report),
        m_n(n),
        m_upper(upper),
        m_total(upper ? double(n) * (n + 1) / 2 : double(n) * n) {}
  void rowDone(int i) {
    if (!m_report) return;
    // Upper-triangle rows shrink with i: weigh each by its length.
    long long w = m_upper ? m_n - i : m_n;
    double f = double(m_done.fetch_add(w) + w) / m_total;
    std::unique_lock<std::mutex> lock(m_mutex, std::try_to_lock);
    if (lock.owns_lock() && f - m_reported >= 0.005) {
      m_reported = f;
      m_report(f);
    }
  }

 private:
  const FormFactorProgress& m_report;
  int m_n;
  bool m_upper;
  double m_total;
  std::atomic<long long> m_done{0};
  std::mutex m_mutex;
  double m_reported = 0;
};

/// Runs computeRow for every row in parallel; `sink(i, row)` stores the entries.
template <typename Sink>
Totals computeRows(const FormFactorMethod& method, int n, RowProgress& progress, Sink&& sink) {
  tbb::combinable<Totals> totals;
  tbb::parallel_for(tbb::blocked_range<int>(0, n, 1), [&](const tbb::blocked_range<int>& r) {
    RowResult row;
    for (int i = r.begin(); i < r.end(); ++i) {
      method.computeRow(i, row);
      totals.local().add(row);
      sink(i, row);
      progress.rowDone(i);
    }
  });
  Totals sum;
  totals.combine_each([&](const Totals& t) { sum.merge(t); });
  return sum;
}

template <typename T>
FormFactorMatrix computeDense(const FormFactorMethod& method, const PatchMesh& mesh,
                              RowProgress& progress, Totals& totals) {
  const int n = mesh.size();
  DenseMatrix<T> f = DenseMatrix<T>::uninitialized(n);
  if (method.coverage() == RowCoverage::FullRow) {
    tbb::parallel_for(tbb::blocked_range<int>(0, n, 16), [&](const tbb::blocked_range<int>& r) {
      for (int i = r.begin(); i < r.end(); ++i) std::fill(f.row(i), f.row(i) + n, T(0));
    });
    totals = computeRows(method, n, progress, [&](int i, const RowResult& row) {
      for (const RowEntry& e : row.entries) f(i, e.column) = T(e.value);
    });
    return f;
  }
  // Upper rows: each writes its own part j >= i in order, then the lower part F_ji =
  // F_ij A_i/A_j is filled tile by tile. Writing F_ji as each row finished instead touched
  // one cache line per entry down a column, 0.4 s of a 5 s single-threaded run at 5 400
  // patches.
  totals = computeRows(method, n, progress, [&](int i, const RowResult& row) {
    T* out = f.row(i);
    std::fill(out + i, out + n, T(0));
    for (const RowEntry& e : row.entries) out[e.column] = T(e.value);
  });
  constexpr int kTile = 64;
  tbb::parallel_for(tbb::blocked_range<int>(0, (n + kTile - 1) / kTile, 1),
                    [&](const tbb::blocked_range<int>& r) {
                      for (int tile = r.begin(); tile < r.end(); ++tile) {
                        const int j0 = tile * kTile, j1 = std::min(n, j0 + kTile);  // rows written
                        for (int i0 = 0; i0 < j1; i0 += kTile) {  // columns written
                          const int i1 = std::min(j1, i0 + kTile);
                          for (int j = j0; j < j1; ++j) {
                            const double aj = mesh.patches[j].area;
                            T* out = f.row(j);
                            for (int i = i0; i < std::min(i1, j); ++i) {
                              const double fij = double(f(i, j));
                              out[i] = fij == 0 ? T(0) : T(fij * mesh.patches[i].area / aj);
                            }
                          }
                        }
                      }
                    });
  return f;
}

using SparseRows = std::vector<std::vector<std::pair<int, double>>>;

/// Full rows → upper rows holding the reciprocity mean (A_iF_ij + A_jF_ji)/2 / A_i.
void symmetrizeRows(SparseRows& rows, const PatchMesh& mesh) {
  const int n = static_cast<int>(rows.size());
  SparseRows upper(n);
  for (int i = 0; i < n; ++i)
    for (auto [j, v] : rows[i]) {
      int a = std::min(i, j), b = std::max(i, j);
      upper[a].push_back({b, 0.5 * v * mesh.patches[i].area / mesh.patches[a].area});
    }
  for (auto& r : upper) {  // merge the two halves of each pair
    std::sort(r.begin(), r.end());
    std::size_t w = 0;
    for (std::size_t k = 0; k < r.size(); ++k) {
      if (w > 0 && r[w - 1].first == r[k].first)
        r[w - 1].second += r[k].second;
      else
        r[w++] = r[k];
    }
    r.resize(w);
  }
  rows.swap(upper);
}

/// CSR from upper rows: row r holds its lower part (from rows i < r, ascending) then its own.
template <typename T>
FormFactorMatrix assembleCsr(SparseRows& rows, bool upper, const PatchMesh& mesh) {
  const int n = static_cast<int>(rows.size());
  std::vector<std::int64_t> start(n + 1, 0), lower(n, 0);
  for (int i = 0; i < n; ++i) {
    start[i + 1] += std::int64_t(rows[i].size());
    if (upper)
      for (auto [j, v] : rows[i]) ++lower[j], ++start[j + 1];
  }
  for (int i = 0; i < n; ++i) start[i + 1] += start[i];
  std::vector<int> column(start[n]);
  std::vector<T> value(start[n]);
  std::vector<std::int64_t> cursor(start.begin(), start.end() - 1);
  for (int i = 0; i < n; ++i) {
    std::int64_t own = start[i] + lower[i];
    for (auto [j, v] : rows[i]) {
      column[own] = j, value[own++] = T(v);
      if (upper) {
        column[cursor[j]] = i;
        value[cursor[j]++] = T(v * mesh.patches[i].area / mesh.patches[j].area);
      }
    }
    std::vector<std::pair<int, double>>().swap(rows[i]);
  }
  return CsrMatrix<T>(n, std::move(start), std::move(column), std::move(value));
}

template <typename T>
FormFactorMatrix computeSparse(const FormFactorMethod& method, const PatchMesh& mesh, bool enforce,
                               RowProgress& progress, Totals& totals) {
  SparseRows rows(mesh.size());
  totals = computeRows(method, mesh.size(), progress, [&](int i, const RowResult& row) {
    rows[i].reserve(row.entries.size());
    for (const RowEntry& e : row.entries) rows[i].push_back({e.column, e.value});
  });
  bool upper = method.coverage() == RowCoverage::UpperTriangle;
  if (enforce && !upper) symmetrizeRows(rows, mesh), upper = true;
  return assembleCsr<T>(rows, upper, mesh);
}
}  // namespace

template <typename T>
void enforceReciprocity(DenseMatrix<T>& f, const PatchMesh& mesh) {
  for (int i = 0; i < f.rows(); ++i)
    for (int j = i + 1; j < f.cols(); ++j) {
      double ai = mesh.patches[i].area, aj = mesh.patches[j].area;
      double mean = 0.5 * (ai * double(f(i, j)) + aj * double(f(j, i)));
      f(i, j) = T(mean / ai);
      f(j, i) = T(mean / aj);
    }
}
template void enforceReciprocity(DenseMatrix<double>&, const PatchMesh&);
template void enforceReciprocity(DenseMatrix<float>&, const PatchMesh&);

FormFactorResult computeFormFactors(const PatchMesh& mesh, const Visibility& visibility,
                                    const FormFactorSettings& settings, const FormFactorLog& log,
                                    const FormFactorProgress& report) {
  FormFactorResult result;
  FormFactorDiagnostics& d = result.diagnostics;
  Clock::time_point t = Clock::now();
  std::unique_ptr<FormFactorMethod> method = makeFormFactorMethod(mesh, visibility, settings);
  const double scalar = settings.precision == FormFactorPrecision::Double ? 8 : 4;
  if (log && double(mesh.size()) * mesh.size() * scalar > double(settings.memoryBudget))
    log("form factors: dense F does not fit " + setting("memory_budget") +
        "; sizing sparse storage from the pairs "
        "that face "
        "each other (up to " +
        std::to_string((long long)mesh.size() * (mesh.size() - 1) / 2) + " tests)");
  result.plan = planStorage(mesh, settings);
  if (log) log("form factors: " + result.plan.describe());
  d.phaseSeconds.push_back({"setup", secondsSince(t)});

  t = Clock::now();
  Totals totals;
  const bool dbl = settings.precision == FormFactorPrecision::Double;
  const bool upper = method->coverage() == RowCoverage::UpperTriangle;
  RowProgress progress(report, mesh.size(), upper);
  if (result.plan.dense)
    result.matrix = dbl ? computeDense<double>(*method, mesh, progress, totals)
                        : computeDense<float>(*method, mesh, progress, totals);
  else
    result.matrix =
        dbl ? computeSparse<double>(*method, mesh, settings.enforceReciprocity, progress, totals)
            : computeSparse<float>(*method, mesh, settings.enforceReciprocity, progress, totals);
  if (report) report(1.0);
  d.phaseSeconds.push_back({"compute", secondsSince(t)});

  t = Clock::now();
  if (settings.enforceReciprocity && result.plan.dense) {
    d.maxRelativeReciprocityErrorBeforeEnforcement =
        maxRelativeReciprocityError(result.matrix, mesh);
    std::visit(
        [&](auto& m) {
          using M = std::decay_t<decltype(m)>;
          if constexpr (std::is_same_v<M, DenseMatrix<double>> ||
                        std::is_same_v<M, DenseMatrix<float>>)
            enforceReciprocity(m, mesh);
        },
        result.matrix);
  }
  d.phaseSeconds.push_back({"reciprocity", secondsSince(t)});

  t = Clock::now();
  measureFormFactorMatrix(result.matrix, mesh, d);
  if (!settings.enforceReciprocity)
    d.maxRelativeReciprocityErrorBeforeEnforcement = d.maxRelativeReciprocityError;
  else if (!result.plan.dense)
    d.maxRelativeReciprocityErrorBeforeEnforcement = -1;  // symmetrized during assembly
  d.phaseSeconds.push_back({"diagnostics", secondsSince(t)});

  d.method = method->name();
  d.description = method->describe();
  d.reciprocityByConstruction = upper;
  d.reciprocityEnforced = settings.enforceReciprocity;
  d.pairsFacing = totals.pairsFacing;
  d.pairsCulled = totals.pairsCulled;
  d.overlappingPairs = totals.overlapping;
  d.firstOverlap = totals.firstOverlap;
  d.raysCast = totals.raysCast;
  d.raysSaved = totals.raysSaved;
  d.quadraturePoints = totals.quadraturePoints;
  d.kernelPoints = totals.kernelPoints;
  if (formFactorTraits(method->name()).countsPairRules)
    d.pairsByRule.assign(std::begin(totals.pairsByRule), std::end(totals.pairsByRule));
  d.threads = activeThreads();
  d.rayThreadSeconds = totals.raySeconds;
  d.geometryThreadSeconds = totals.geometrySeconds;
  d.raysPerSecond = totals.raySeconds > 0 ? totals.raysCast / (totals.raySeconds / d.threads) : 0;
  if (totals.overlapping > 0)
    d.warnings.push_back(std::to_string(totals.overlapping) +
                         " pairs of coplanar patches overlap (coincident geometry), e.g. patches " +
                         std::to_string(totals.firstOverlap.first) + " and " +
                         std::to_string(totals.firstOverlap.second) + "; their F is 0");
  return result;
}

}  // namespace radkit
