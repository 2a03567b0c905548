#include "job/study_job.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <sstream>

#include "hierarchy/hierarchical.h"
#include "job/job.h"
#include "output/run_files.h"
#include "util/errors.h"
#include "util/format.h"
#include "util/line_chart.h"
#include "util/output_folder.h"
#include "util/process_memory.h"
#include "util/setting_names.h"

namespace radkit {

namespace {

/// Seconds kept for writing study.csv, study.md and the charts (about 0.3 s on the Cornell box).
constexpr double kWriteReserveSeconds = 1.0;

/// The hierarchical method's ε ladder, coarse to fine, against the study's reference: each
/// rung runs while its estimate fits what is left of the whole budget (counted from the
/// command's start, so loading and the sweeps' overruns are paid for here, not on top).
void addHierarchicalRows(const Scene& scene, const StudyJobSettings& cmd, StudyResult& r,
                         const PipelineLog& log, Clock::time_point begin) {
  double last = 0, growth = 3;  // a rung costs about 3× the last (ε steps of ~3)
  for (double eps : cmd.epsilons) {
    StudyRow row;
    row.config.knob = StudyKnob::Hierarchical;
    row.config.settings = cmd.settings.baseline;
    row.config.epsilon = eps;
    // The first rung (coarsest ε) has no measurement: it is a small fraction of a dense run.
    row.estimatedSeconds = growth * last;
    row.neededSeconds = row.estimatedSeconds;
    row.secondsLeft = cmd.settings.maxSeconds - kWriteReserveSeconds - secondsSince(begin);
    const double left = row.secondsLeft;
    if (row.neededSeconds > left || left <= 0) {
      row.note = "skipped: estimated " + formatValue("%.0f s", row.estimatedSeconds) + ", " +
                 formatValue("%.0f s", left) + " left";
      r.rows.push_back(row);
      continue;
    }
    HierarchicalSettings hs;
    hs.epsilon = eps;
    hs.seed = cmd.settings.baseline.formFactors.seed;
    if (log.message) log.message("hierarchical " + row.config.label());
    resetPeakMemory();
    const auto rungStart = Clock::now();
    HierarchicalResult h = solveHierarchical(scene, hs);
    const double took = secondsSince(rungStart);
    if (last > 0) growth = std::max(2.0, took / last);  // the ladder's own measured growth
    last = took;
    row.ran = true;
    row.patches = h.leaves.size();
    row.seconds = {h.seconds.inputFaces + h.seconds.hierarchy, h.seconds.rayScene, h.seconds.refine,
                   h.seconds.solve, h.seconds.results};
    row.totalSeconds = last;
    row.peakBytes = peakMemory();
    row.iterations = h.solve.iterations;
    row.converged = h.solve.converged;
    row.note = h.solve.reason;
    measureErrors(StudySolution{h.leaves, h.radiosity, h.surfaces}, r.reference.solution, row);
    r.rows.push_back(row);
  }
  r.seconds = secondsSince(begin);
  // Both Pareto fronts again, over every configuration that ran.
  std::vector<StudyRow*> ran;
  std::vector<double> cost, surface, patch;
  for (StudyRow& w : r.rows)
    if (w.ran)
      ran.push_back(&w), cost.push_back(w.totalSeconds), surface.push_back(w.surfaceError),
          patch.push_back(w.patchError);
  std::vector<bool> fs = paretoFront(cost, surface), fp = paretoFront(cost, patch);
  for (std::size_t k = 0; k < ran.size(); ++k)
    ran[k]->paretoSurface = fs[k], ran[k]->paretoPatch = fp[k];
}

std::string mib(std::size_t bytes) { return formatValue("%.1f", bytes / 1048576.0); }

using Pick = double (*)(const StudyRow&);
double totalS(const StudyRow& w) { return w.totalSeconds; }
double solveS(const StudyRow& w) { return w.seconds.solve; }
double patchesOf(const StudyRow& w) { return w.patches; }
double surfaceE(const StudyRow& w) { return w.surfaceError; }
double patchE(const StudyRow& w) { return w.patchError; }

/// One series per group (method, solver), points sorted by x, plus the panel's Pareto front.
ChartPanel panel(const std::vector<const StudyRow*>& rows, Pick x, Pick y,
                 std::string (*group)(const StudyRow&), const std::string& title,
                 const std::string& xLabel, const std::string& yLabel) {
  ChartPanel p{title, xLabel, yLabel, true, true, {}};
  std::map<std::string, std::vector<std::pair<double, double>>> groups;
  std::vector<double> xs, ys;
  for (const StudyRow* w : rows) {
    groups[group(*w)].push_back({x(*w), y(*w)});
    xs.push_back(x(*w)), ys.push_back(y(*w));
  }
  auto add = [&](const std::string& name, std::vector<std::pair<double, double>> pts) {
    std::sort(pts.begin(), pts.end());
    ChartSeries s{name, {}, {}};
    for (auto [a, b] : pts) s.x.push_back(a), s.y.push_back(b);
    p.series.push_back(s);
  };
  for (auto& [name, pts] : groups) add(name, pts);
  std::vector<bool> front = paretoFront(xs, ys);
  std::vector<std::pair<double, double>> fp;
  for (std::size_t k = 0; k < xs.size(); ++k)
    if (front[k]) fp.push_back({xs[k], ys[k]});
  if (!groups.empty()) add("Pareto front", fp);
  return p;
}

std::string byMethod(const StudyRow& w) { return w.config.settings.formFactors.method; }
std::string bySolver(const StudyRow& w) { return w.config.settings.solvers.front().name; }
std::string byKnob(const StudyRow& w) {
  return w.config.knob == StudyKnob::Mesh ? "uniform mesh" : studyKnobName(w.config.knob);
}

std::vector<const StudyRow*> rowsOf(const StudyResult& r, std::initializer_list<StudyKnob> knobs) {
  std::vector<const StudyRow*> out;
  for (const StudyRow& w : r.rows)
    if (w.ran && std::find(knobs.begin(), knobs.end(), w.config.knob) != knobs.end())
      out.push_back(&w);
  return out;
}

/// A chart with no point in it (a knob the budget left out) is not written.
void writeChart(OutputFolder& folder, const std::string& name,
                const std::vector<ChartPanel>& panels) {
  if (chartPoints(panels) > 0) writeLineChartPng(folder.path(name), panels);
}

void writeCharts(OutputFolder& folder, const StudyResult& r, const std::string& scene) {
  const std::string s = "seconds (all stages)", es = "surface error (max rel.)",
                    ep = "patch error (rel. L1)";
  auto mesh = rowsOf(r, {StudyKnob::Mesh, StudyKnob::Hierarchical});
  writeChart(folder, "study-mesh.png",
             {panel(mesh, totalS, surfaceE, byKnob, scene + ": mesh density", s, es),
              panel(mesh, totalS, patchE, byKnob, scene + ": mesh density", s, ep)});
  auto ff = rowsOf(r, {StudyKnob::FormFactors});
  writeChart(
      folder, "study-formfactors.png",
      {panel(ff, totalS, surfaceE, byMethod, scene + ": form factors (K along each line)", s, es),
       panel(ff, totalS, patchE, byMethod, scene + ": form factors (K along each line)", s, ep)});
  auto sv = rowsOf(r, {StudyKnob::Solver});
  writeChart(
      folder, "study-solver.png",
      {panel(sv, solveS, surfaceE, bySolver, scene + ": solver and tolerance", "solve seconds", es),
       panel(sv, solveS, patchE, bySolver, scene + ": solver and tolerance", "solve seconds", ep)});
  auto ad = rowsOf(r, {StudyKnob::Mesh, StudyKnob::Adaptive});
  writeChart(
      folder, "study-adaptive.png",
      {panel(ad, patchesOf, patchE, byKnob, scene + ": adaptive against uniform", "patches", ep),
       panel(ad, totalS, patchE, byKnob, scene + ": adaptive against uniform", s, ep)});
  auto all = rowsOf(r, {StudyKnob::Mesh, StudyKnob::FormFactors, StudyKnob::Solver,
                        StudyKnob::Adaptive, StudyKnob::Hierarchical});
  writeChart(folder, "study-pareto.png",
             {panel(all, totalS, surfaceE, byKnob, scene + ": every configuration", s, es),
              panel(all, totalS, patchE, byKnob, scene + ": every configuration", s, ep)});
}

void writeMarkdown(const std::string& path, const StudyResult& r, const Scene& scene,
                   double maxSeconds) {
  std::ostringstream o;
  const StudyRow& ref = r.reference.row;
  o << "# Speed-accuracy study: " << scene.name << "\n\n"
    << "Budget " << maxSeconds << " s, study took " << formatValue("%.0f", r.seconds) << " s.\n\n"
    << "**Reference:** " << ref.patches << " patches, " << ref.config.settings.formFactors.method
    << " K = " << ref.config.settings.formFactors.samples << ", "
    << ref.config.settings.solvers.front().name << " to "
    << formatValue("%.0e", ref.config.settings.stopping.tolerance) << " ("
    << formatValue("%.1f", ref.totalSeconds) << " s, F " << mib(ref.formFactorBytes)
    << " MiB, peak " << mib(ref.peakBytes) << " MiB). Its own error, estimated: surface "
    << formatValue("%.2e", r.reference.surfaceErrorEstimate) << ", patch "
    << formatValue("%.2e", r.reference.patchErrorEstimate) << ". " << r.reference.errorMethod
    << "\n\n"
    << "Errors are relative to the reference (experiments/study.h): surface = max over surfaces "
       "and "
       "channels; patch = "
       "area-weighted L1 of patch means; field = area-weighted L1 of the piecewise-constant "
       "picture. P = on the Pareto "
       "front of error against total seconds (s: surface, p: patch).\n\n"
    << "| knob | configuration | patches | mesh s | F s | solve s | total s | F MiB | peak MiB | "
       "iterations | surface "
       "error | patch error | field error | P "
       "|\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const StudyRow& w : r.rows) {
    if (!w.ran) continue;
    o << "| " << studyKnobName(w.config.knob) << " | " << w.config.label() << " | " << w.patches
      << " | " << formatValue("%.2f", w.seconds.mesh) << " | "
      << formatValue("%.2f", w.seconds.formFactors) << " | " << formatValue("%.3f", w.seconds.solve)
      << " | " << formatValue("%.2f", w.totalSeconds) << " | " << mib(w.formFactorBytes) << " | "
      << mib(w.peakBytes) << " | " << w.iterations << " | " << formatValue("%.2e", w.surfaceError)
      << " | " << formatValue("%.2e", w.patchError) << " | " << formatValue("%.2e", w.fieldError)
      << " | " << (w.paretoSurface ? "s" : "") << (w.paretoPatch ? "p" : "") << " |\n";
  }
  o << "\nSkipped (the planner's estimate did not fit the remaining budget):\n\n";
  for (const StudyRow& w : r.rows)
    if (!w.ran)
      o << "- " << studyKnobName(w.config.knob) << " " << w.config.label() << ": " << w.note
        << "\n";
  std::vector<double> n, ff, pe;
  for (const StudyRow* w : rowsOf(r, {StudyKnob::Mesh}))
    n.push_back(w->patches), ff.push_back(w->seconds.formFactors), pe.push_back(w->patchError);
  // A fit needs two rungs with positive values; NaN says it had fewer.
  const auto exponent = [](double e) {
    return std::isnan(e) ? std::string("n/a (fewer than two rungs to fit)")
                         : "N^" + formatValue("%.2f", e);
  };
  o << "\nMesh ladder fits: form-factor seconds ∝ " << exponent(fitExponent(n, ff))
    << ", patch error ∝ " << exponent(fitExponent(n, pe)) << ".\n";
  writeFileAtomically(path, o.str());
}

}  // namespace

StudyJobResult runStudyJob(const StudyJobSettings& cmd, const PipelineLog& log) {
  // The reference runs whatever the budget: --knob-patches 4000 with --max-seconds 1 ran an
  // 8000-patch reference for minutes.
  const double reference = estimateReferenceSeconds(cmd.settings);
  if (reference > cmd.settings.maxSeconds)
    throw InputError(setting("max_seconds") + " " + formatValue("%g", cmd.settings.maxSeconds) +
                     " is shorter than the reference of " + setting("knob_patches") + " " +
                     std::to_string(cmd.settings.knobPatches) + " alone (" +
                     std::to_string(2 * cmd.settings.knobPatches) + " patches, estimated " +
                     formatValue("%.0f s", reference) + "). Fix: raise " + setting("max_seconds") +
                     " or lower " + setting("knob_patches"));
  const auto begin = Clock::now();
  Scene scene = loadJobScene(cmd.scene, {}, "", log);
  OutputFolder folder(cmd.out);  // refuses a folder it cannot replace before the study
  // The sweeps get four fifths of what is left after loading (the hierarchical ladder the rest);
  // the charts and tables are written in the reserve.
  StudySettings sweeps = cmd.settings;
  sweeps.maxSeconds = cmd.settings.maxSeconds - kWriteReserveSeconds - secondsSince(begin);
  if (!cmd.epsilons.empty()) sweeps.maxSeconds *= 0.8;
  StudyResult r = runStudy(scene, sweeps, log);
  addHierarchicalRows(scene, cmd, r, log, begin);
  writeStudyCsv(folder.path("study.csv"), r);
  writeMarkdown(folder.path("study.md"), r, scene, cmd.settings.maxSeconds);
  writeCharts(folder, r, scene.name);
  folder.commit();
  return {cmd.out, scene.name, scene.file, std::move(r)};
}

}  // namespace radkit
