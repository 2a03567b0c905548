#include "experiments/study.h"
#include "util/format.h"
#include "util/output_folder.h"
#include "util/process_memory.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <memory>
#include <sstream>

namespace radkit {

std::vector<std::pair<std::string, std::vector<int>>> studyFormFactorSamples() {
  std::vector<std::pair<std::string, std::vector<int>>> ladders;
  for (const std::string& method : formFactorMethodNames())
    ladders.emplace_back(method, formFactorTraits(method).studySamples);
  return ladders;
}

namespace {

double total(const StageSeconds& s) {
  return s.mesh + s.rayScene + s.formFactors + s.solve + s.results;
}

StudyConfig makeConfig(StudyKnob knob, const PipelineSettings& base, int patches) {
  StudyConfig c;
  c.knob = knob;
  c.settings = base;
  c.settings.mesh = SubdivisionSettings{0, patches};
  return c;
}

/// Form-factor work of a method in its own units (its registry row's cost model).
double formFactorWork(const FormFactorSettings& ff, double n) {
  return formFactorTraits(ff.method).work(n, ff.samples);
}

/// Cost model. Form factors: the largest measured run of the same method, scaled by the work
/// ratio at equal n and by (n/n_m)^p, p fitted to the two largest runs of that method (clamped
/// to [1, 2]; 1.5 from one run: small meshes carry fixed costs); with none, the method's
/// workPerSecond. Solve: (n/n_m)²; the other stages: n/n_m.
double estimateSeconds(const StudyConfig& c, const std::vector<StudyRow>& done) {
  double n = c.knob == StudyKnob::Adaptive ? c.adaptive.maxPatches : c.settings.mesh.targetPatches;
  const FormFactorSettings& ff = c.settings.formFactors;
  std::vector<const StudyRow*> same;  // measured runs of this method, largest last
  for (const StudyRow& r : done)
    if (r.ran && (r.config.knob == StudyKnob::Mesh || r.config.knob == StudyKnob::FormFactors) &&
        r.config.settings.formFactors.method == ff.method)
      same.push_back(&r);
  std::stable_sort(same.begin(), same.end(),
                   [](auto* a, auto* b) { return a->patches < b->patches; });
  double sec = formFactorWork(ff, n) / formFactorTraits(ff.method).workPerSecond;
  if (!same.empty()) {
    const StudyRow& m = *same.back();
    double p = 1.5;
    for (auto it = same.rbegin() + 1; it != same.rend(); ++it)
      if ((*it)->patches < m.patches * 0.7) {  // unit-work seconds at two sizes
        const StudyRow& a = **it;
        double ta = a.seconds.formFactors / formFactorWork(a.config.settings.formFactors, 1);
        double tm = m.seconds.formFactors / formFactorWork(m.config.settings.formFactors, 1);
        p = std::clamp(std::log(tm / ta) / std::log(double(m.patches) / a.patches), 1.0, 2.0);
        break;
      }
    double ratio = n / m.patches;
    sec = m.seconds.formFactors * formFactorWork(ff, m.patches) /
              formFactorWork(m.config.settings.formFactors, m.patches) * std::pow(ratio, p) +
          m.seconds.solve * ratio * ratio +
          (m.seconds.mesh + m.seconds.rayScene + m.seconds.results) * ratio;
  }
  return c.knob == StudyKnob::Adaptive ? 2.5 * sec : sec;  // adaptive: Σ of its rounds
}

/// Runs one pipeline configuration and keeps its solution (not its F).
StudySolution runConfig(const Scene& scene, const StudyConfig& c, StudyRow& row,
                        const PipelineLog& log,
                        const std::function<void(const PipelineResult&)>& alsoWithF) {
  StudySolution s;
  resetPeakMemory();
  if (c.knob == StudyKnob::Adaptive) {
    AdaptiveResult a = solveAdaptive(scene, c.settings, c.adaptive);
    for (const AdaptiveRound& round : a.rounds) {
      row.seconds.mesh += round.seconds.mesh, row.seconds.rayScene += round.seconds.rayScene;
      row.seconds.formFactors += round.seconds.formFactors,
          row.seconds.solve += round.seconds.solve;
      row.seconds.results += round.seconds.results;
    }
    row.formFactorBytes = a.final.formFactors->diagnostics.matrixBytes;
    row.iterations = a.final.solves.front().iterations,
    row.converged = a.final.solves.front().converged;
    row.note = a.stopReason + ", " + std::to_string(a.rounds.size()) + " rounds";
    s = {std::move(a.final.mesh), std::move(a.final.radiosity), std::move(a.final.surfaces)};
  } else {
    PipelineResult r = runPipeline(scene, c.settings, {log.progress, {}});
    row.seconds = r.seconds;
    row.formFactorBytes = r.formFactors->plan.bytes;
    row.iterations = r.solves.front().iterations, row.converged = r.solves.front().converged;
    row.note = r.solves.front().reason;
    if (alsoWithF) alsoWithF(r);
    s = {std::move(r.mesh), std::move(r.radiosity), std::move(r.surfaces)};
  }
  row.ran = true;
  row.patches = s.mesh.size();
  row.totalSeconds = total(row.seconds);
  row.peakBytes = peakMemory();
  return s;
}

/// The solver knob: every solver and tolerance on one already computed system.
void runSolverKnob(const Scene& scene, const StudySettings& st, const PipelineResult& r,
                   const StudyRow& rung, std::vector<StudyRow>& rows,
                   std::vector<StudySolution>& solutions) {
  for (const std::string& name : st.solvers)
    for (double tol : st.tolerances) {
      StudyRow row;
      row.config =
          makeConfig(StudyKnob::Solver, st.baseline, rung.config.settings.mesh.targetPatches);
      row.config.settings.solvers = {SolverChoice{name, ""}};
      row.config.settings.stopping.tolerance = tol;
      SolveResult s =
          runSolver(row.config.settings.solvers.front(), r.system, row.config.settings.stopping);
      auto t = Clock::now();
      std::vector<Vec3> b = toVec3(s.radiosity);
      std::vector<SurfaceResult> surf =
          surfaceResults(scene, r.mesh, b, irradiance(r.formFactors->matrix, s.radiosity));
      row.seconds = rung.seconds;
      row.seconds.solve = s.seconds;
      row.seconds.results = secondsSince(t);
      row.ran = true, row.patches = r.mesh.size(), row.totalSeconds = total(row.seconds);
      row.formFactorBytes = rung.formFactorBytes;
      row.iterations = s.iterations, row.converged = s.converged, row.note = s.reason;
      rows.push_back(row);
      solutions.push_back({r.mesh, std::move(b), std::move(surf)});
    }
}

/// Every configuration but the solver knob's, which rides on the knob mesh's rung.
std::vector<StudyConfig> candidates(const StudySettings& st) {
  std::vector<StudyConfig> out;
  for (int n : st.meshLadder) out.push_back(makeConfig(StudyKnob::Mesh, st.baseline, n));
  for (const auto& [method, ks] : st.formFactorSamples)
    for (int k : ks) {
      StudyConfig c = makeConfig(StudyKnob::FormFactors, st.baseline, st.knobPatches);
      c.settings.formFactors.method = method;
      c.settings.formFactors.samples = k;
      const FormFactorSettings& b = st.baseline.formFactors;
      if (method != b.method || k != b.samples)
        out.push_back(c);  // the baseline is the rung's copy
    }
  for (int budget : st.adaptiveBudgets) {
    StudyConfig c = makeConfig(StudyKnob::Adaptive, st.baseline, st.adaptiveStartPatches);
    c.adaptive.maxPatches = budget;
    out.push_back(c);
  }
  return out;
}

/// Relative difference of the two finest rungs' errors, extrapolated (see study.h).
void estimateReferenceError(const std::vector<StudyRow>& rows,
                            const std::vector<StudySolution>& sols, StudyReference& ref) {
  std::vector<int> rungs;
  for (std::size_t k = 0; k < rows.size(); ++k)
    if (rows[k].ran && rows[k].config.knob == StudyKnob::Mesh) rungs.push_back(int(k));
  std::sort(rungs.begin(), rungs.end(),
            [&](int a, int b) { return rows[a].patches < rows[b].patches; });
  if (rungs.size() < 2) {
    ref.errorMethod = "no estimate: fewer than two mesh rungs ran";
    return;
  }
  StudyRow coarse, fine;  // d1: second-finest against finest; d2: finest against the reference
  measureErrors(sols[rungs[rungs.size() - 2]], sols[rungs.back()], coarse);
  measureErrors(sols[rungs.back()], ref.solution, fine);
  auto extrapolate = [](double d1, double d2, bool& asymptotic) {
    asymptotic = d1 > d2 && d2 > 0;
    return asymptotic ? d2 / (d1 / d2 - 1) : d2;  // e_ref = d2 / (r − 1), r = d1/d2
  };
  bool a1 = false, a2 = false;
  ref.surfaceErrorEstimate = extrapolate(coarse.surfaceError, fine.surfaceError, a1);
  ref.patchErrorEstimate = extrapolate(coarse.patchError, fine.patchError, a2);
  ref.errorMethod =
      "Richardson-style, from the mesh ladder (each rung twice the patches of the one before): d1 "
      "= difference "
      "between the two finest rungs (" +
      std::to_string(rows[rungs[rungs.size() - 2]].patches) + " and " +
      std::to_string(rows[rungs.back()].patches) +
      " patches), d2 = difference between the finest rung and the "
      "reference (" +
      std::to_string(ref.row.patches) +
      "); if the differences shrink geometrically by r = d1/d2 "
      "per doubling, the reference's own error is d2/(r - 1). Surface level: d1 = " +
      formatValue("%.3g", coarse.surfaceError) +
      ", d2 = " + formatValue("%.3g", fine.surfaceError) +
      (a1 ? "" : " (not shrinking: the estimate is d2 itself)") +
      "; patch level: d1 = " + formatValue("%.3g", coarse.patchError) +
      ", d2 = " + formatValue("%.3g", fine.patchError) +
      (a2 ? "" : " (not shrinking: the estimate is d2 itself)") + ".";
}

}  // namespace

namespace {

/// The patch of `onto` (same surface) containing point x of a surface with normal n: a ray from
/// just in front of x back along −n, or the nearest centroid of that surface when it misses.
int mapPoint(const Vec3& x, const Vec3& n, int surface, const PatchMesh& onto,
             const Visibility& rays) {
  double lift = 10 * rays.epsilon();
  auto hit = rays.closestHit(x + n * lift, -n, 0.0, 2 * lift);
  if (hit && onto.patches[hit->patch].surface == surface) return hit->patch;
  int best = -1;
  double bestD = std::numeric_limits<double>::infinity();
  for (int j = onto.surfaceBegin[surface]; j < onto.surfaceBegin[surface + 1]; ++j) {
    Vec3 d = onto.patches[j].centroid - x;
    if (dot(d, d) < bestD) bestD = dot(d, d), best = j;
  }
  return best;
}

/// Splits a patch into m² pieces (a bilinear grid of a quad, similar triangles of a triangle)
/// and calls fn(centre, area) for each: the quadrature points of the error integrals.
template <typename Fn>
void forEachPiece(const PatchMesh& mesh, const Patch& p, int m, Fn&& fn) {
  Vec3 v0 = mesh.vertex(p, 0), v1 = mesh.vertex(p, 1), v2 = mesh.vertex(p, 2);
  if (p.isQuad()) {
    Vec3 v3 = mesh.vertex(p, 3);
    auto at = [&](double s, double t) {
      return (v0 * (1 - s) + v1 * s) * (1 - t) + (v3 * (1 - s) + v2 * s) * t;
    };
    for (int a = 0; a < m; ++a)
      for (int b = 0; b < m; ++b) {
        double s0 = double(a) / m, s1 = double(a + 1) / m, t0 = double(b) / m,
               t1 = double(b + 1) / m;
        Vec3 c00 = at(s0, t0), c11 = at(s1, t1), c10 = at(s1, t0), c01 = at(s0, t1);
        fn((c00 + c10 + c11 + c01) * 0.25, 0.5 * length(cross(c11 - c00, c01 - c10)));
      }
    return;
  }
  double piece = p.area / (m * m);  // m² similar triangles: barycentric lattice centroids
  for (int i = 0; i < m; ++i)
    for (int j = 0; i + j < m; ++j) {
      auto bary = [&](double u, double w) {
        return v0 + (v1 - v0) * (u / m) + (v2 - v0) * (w / m);
      };
      fn(bary(i + 1.0 / 3, j + 1.0 / 3), piece);
      if (i + j < m - 1) fn(bary(i + 2.0 / 3, j + 2.0 / 3), piece);
    }
}

}  // namespace

std::vector<int> mapPatches(const PatchMesh& from, const PatchMesh& onto,
                            const Visibility& ontoRays) {
  std::vector<int> map(from.patches.size(), -1);
  for (int r = 0; r < from.size(); ++r)
    map[r] = mapPoint(from.patches[r].centroid, from.patches[r].normal, from.patches[r].surface,
                      onto, ontoRays);
  return map;
}

void measureErrors(const StudySolution& s, const StudySolution& ref, StudyRow& row) {
  row.surfaceError = 0;
  for (std::size_t k = 0; k < ref.surfaces.size() && k < s.surfaces.size(); ++k)
    for (int c = 0; c < 3; ++c)
      if (ref.surfaces[k].radiosity[c] > 0)
        row.surfaceError = std::max(
            row.surfaceError, std::fabs(s.surfaces[k].radiosity[c] - ref.surfaces[k].radiosity[c]) /
                                  ref.surfaces[k].radiosity[c]);
  // Each reference patch is cut into 4×4 pieces, each mapped onto s's mesh on its own, so a
  // reference patch straddling two of s's patches is shared between them by area.
  RayScene rays(s.mesh);
  std::vector<Vec3> mean(s.mesh.patches.size());  // Σ a B_ref over the pieces in p
  std::vector<double> weight(s.mesh.patches.size(), 0.0);
  double fieldDiff = 0, fieldRef = 0;
  for (int r = 0; r < ref.mesh.size(); ++r) {
    const Patch& rp = ref.mesh.patches[r];
    forEachPiece(ref.mesh, rp, 4, [&](const Vec3& x, double a) {
      int p = mapPoint(x, rp.normal, rp.surface, s.mesh, rays);
      if (p < 0) return;
      mean[p] += ref.radiosity[r] * a;
      weight[p] += a;
      for (int c = 0; c < 3; ++c) {
        fieldDiff += a * std::fabs(s.radiosity[p][c] - ref.radiosity[r][c]);
        fieldRef += a * ref.radiosity[r][c];
      }
    });
  }
  double patchDiff = 0, patchRef = 0;
  for (int p = 0; p < s.mesh.size(); ++p)
    for (int c = 0; c < 3; ++c) {  // W_p |B_p − B̄_p| with B̄_p = mean/W_p
      patchDiff += std::fabs(s.radiosity[p][c] * weight[p] - mean[p][c]);
      patchRef += mean[p][c];
    }
  row.fieldError = fieldRef > 0 ? fieldDiff / fieldRef : 0;
  row.patchError = patchRef > 0 ? patchDiff / patchRef : 0;
}

std::vector<bool> paretoFront(const std::vector<double>& cost, const std::vector<double>& error) {
  std::vector<bool> front(cost.size());
  for (std::size_t a = 0; a < cost.size(); ++a)
    front[a] = std::isfinite(cost[a]) && std::isfinite(error[a]);
  for (std::size_t a = 0; a < cost.size(); ++a)
    for (std::size_t b = 0; b < cost.size() && front[a]; ++b)
      if (b != a && cost[b] <= cost[a] && error[b] <= error[a] &&
          (cost[b] < cost[a] || error[b] < error[a]))
        front[a] = false;
  return front;
}

double fitExponent(const std::vector<double>& x, const std::vector<double>& y) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (std::size_t k = 0; k < x.size() && k < y.size(); ++k) {
    if (!(x[k] > 0) || !(y[k] > 0)) continue;
    double lx = std::log(x[k]), ly = std::log(y[k]);
    sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly, ++n;
  }
  double den = n * sxx - sx * sx;
  return n < 2 || den <= 0 ? std::numeric_limits<double>::quiet_NaN() : (n * sxy - sx * sy) / den;
}

const char* studyKnobName(StudyKnob knob) {
  switch (knob) {
    case StudyKnob::Mesh:
      return "mesh";
    case StudyKnob::FormFactors:
      return "formfactors";
    case StudyKnob::Solver:
      return "solver";
    case StudyKnob::Adaptive:
      return "adaptive";
    case StudyKnob::Hierarchical:
      return "hierarchical";
  }
  return "?";
}

std::string StudyConfig::label() const {
  switch (knob) {
    case StudyKnob::Mesh:
      return "N=" + std::to_string(settings.mesh.targetPatches);
    case StudyKnob::FormFactors:
      return settings.formFactors.method + " K=" + std::to_string(settings.formFactors.samples);
    case StudyKnob::Solver:
      return settings.solvers.front().name +
             " tol=" + formatValue("%.0e", settings.stopping.tolerance);
    case StudyKnob::Adaptive:
      return "adaptive " + std::to_string(settings.mesh.targetPatches) +
             " to <=" + std::to_string(adaptive.maxPatches);
    case StudyKnob::Hierarchical:
      return "eps=" + formatValue("%.0e", epsilon);
  }
  return "?";
}

double estimateReferenceSeconds(const StudySettings& st) {
  StudyConfig c = makeConfig(StudyKnob::Mesh, st.baseline, 2 * st.knobPatches);
  c.settings.stopping.tolerance = st.referenceTolerance;
  return estimateSeconds(c, {});
}

StudyResult runStudy(const Scene& scene, const StudySettings& st, const PipelineLog& log) {
  auto start = Clock::now();
  auto say = [&](const std::string& line) {
    if (log.message) log.message(line);
  };
  StudyResult result;
  std::vector<StudySolution> sols;
  std::vector<StudyConfig> pending = candidates(st);
  std::vector<StudyRow> skipped;
  int finestRung = 0;
  auto referenceConfig = [&](int rung) {
    StudyConfig c = makeConfig(StudyKnob::Mesh, st.baseline, 2 * std::max(rung, st.knobPatches));
    c.settings.stopping.tolerance = st.referenceTolerance;
    return c;
  };
  // Estimates scaled by how far the runs so far overran theirs: on a loaded machine every
  // stage is slower than the cost model says, and the budget is the wall clock's.
  double calibration = 1;
  while (!pending.empty()) {
    std::vector<double> est;
    for (const StudyConfig& c : pending) est.push_back(estimateSeconds(c, result.rows));
    std::size_t k = std::min_element(est.begin(), est.end()) - est.begin();
    StudyConfig c = pending[k];
    pending.erase(pending.begin() + k);
    bool rung = c.knob == StudyKnob::Mesh;
    int rungAfter = rung ? c.settings.mesh.targetPatches : finestRung;
    double need = calibration * (est[k] + estimateSeconds(referenceConfig(rungAfter), result.rows));
    double left = st.maxSeconds - secondsSince(start);
    StudyRow row;
    row.config = c;
    row.estimatedSeconds = est[k];
    row.neededSeconds = need, row.secondsLeft = left;
    if (need > left) {
      row.note = "skipped: estimated " + formatValue("%.0f s", est[k]) + " plus the reference " +
                 formatValue("%.0f s", need - est[k]) + ", " +
                 formatValue("%.0f s", std::max(0.0, left)) + " left";
      say(c.label() + ": " + row.note);
      skipped.push_back(row);
      continue;
    }
    say(std::string(studyKnobName(c.knob)) + " " + c.label() + " (estimated " +
        formatValue("%.1f s", est[k]) + ")");
    const auto runStart = Clock::now();
    bool knobRung = rung && c.settings.mesh.targetPatches == st.knobPatches;
    std::vector<StudyRow> solverRows;
    std::vector<StudySolution> solverSols;
    sols.push_back(runConfig(scene, c, row, log, [&](const PipelineResult& r) {
      if (knobRung) runSolverKnob(scene, st, r, row, solverRows, solverSols);
    }));
    result.rows.push_back(row);
    // Short runs are mostly fixed costs the model leaves out, and the knob rung also ran the
    // solver knob, which its estimate does not include.
    const double taken = secondsSince(runStart);
    if (est[k] > 0.3 && !knobRung)
      calibration = std::clamp(std::max(calibration, taken / est[k]), 1.0, 4.0);
    if (rung) finestRung = std::max(finestRung, c.settings.mesh.targetPatches);
    if (knobRung) {  // the baseline as a member of the form-factor knob, at no cost
      StudyRow copy = row;
      copy.neededSeconds = copy.secondsLeft = std::numeric_limits<double>::quiet_NaN();
      copy.config.knob = StudyKnob::FormFactors;
      result.rows.push_back(copy);
      sols.push_back(sols.back());
    }
    for (std::size_t s = 0; s < solverRows.size(); ++s) {
      solverRows[s].peakBytes = row.peakBytes;  // the rung's run, F included
      result.rows.push_back(solverRows[s]);
      sols.push_back(std::move(solverSols[s]));
    }
  }

  StudyConfig refConfig = referenceConfig(finestRung);
  say("reference " + refConfig.label() + " tol " + formatValue("%.0e", st.referenceTolerance));
  StudyReference& ref = result.reference;
  ref.row.config = refConfig;
  ref.row.estimatedSeconds = estimateSeconds(refConfig, result.rows);
  ref.solution = runConfig(scene, refConfig, ref.row, log, {});
  estimateReferenceError(result.rows, sols, ref);
  say("reference error estimate: surface " + formatValue("%.2e", ref.surfaceErrorEstimate) +
      ", patch " + formatValue("%.2e", ref.patchErrorEstimate));

  std::vector<double> cost, surfaceErr, patchErr;
  for (std::size_t k = 0; k < result.rows.size(); ++k) {
    measureErrors(sols[k], ref.solution, result.rows[k]);
    cost.push_back(result.rows[k].totalSeconds);
    surfaceErr.push_back(result.rows[k].surfaceError);
    patchErr.push_back(result.rows[k].patchError);
  }
  std::vector<bool> ps = paretoFront(cost, surfaceErr), pp = paretoFront(cost, patchErr);
  for (std::size_t k = 0; k < result.rows.size(); ++k)
    result.rows[k].paretoSurface = ps[k], result.rows[k].paretoPatch = pp[k];
  result.rows.insert(result.rows.end(), skipped.begin(), skipped.end());
  result.seconds = secondsSince(start);
  return result;
}

void writeStudyCsv(const std::string& path, const StudyResult& r) {
  std::ostringstream o;
  o << "knob,config,status,patches,ff_method,ff_samples,solver,tolerance,mesh_s,ray_scene_s,"
       "formfactors_s,solve_s,"
       "results_s,total_s,estimated_s,ff_bytes,peak_bytes,iterations,converged,surface_error,patch_"
       "error,field_error,"
       "pareto_surface,pareto_patch,needed_s,left_s\n";
  auto line = [&](const StudyRow& w, const std::string& knob) {
    const PipelineSettings& s = w.config.settings;
    o << knob << ",\"" << w.config.label() << "\"," << (w.ran ? "ran" : "skipped") << ','
      << w.patches << ',' << s.formFactors.method << ',' << s.formFactors.samples << ','
      << s.solvers.front().name << ',' << s.stopping.tolerance << ',' << w.seconds.mesh << ','
      << w.seconds.rayScene << ',' << w.seconds.formFactors << ',' << w.seconds.solve << ','
      << w.seconds.results << ',' << w.totalSeconds << ',' << w.estimatedSeconds << ','
      << w.formFactorBytes << ',' << w.peakBytes << ',' << w.iterations << ',' << w.converged << ','
      << w.surfaceError << ',' << w.patchError << ',' << w.fieldError << ',' << w.paretoSurface
      << ',' << w.paretoPatch << ',';
    if (!std::isnan(w.neededSeconds))
      o << w.neededSeconds << ',' << w.secondsLeft;
    else
      o << ',';
    o << '\n';
  };
  o.precision(6);
  for (const StudyRow& w : r.rows) line(w, studyKnobName(w.config.knob));
  line(r.reference.row, "reference");
  writeFileAtomically(path, o.str());
}

}  // namespace radkit
