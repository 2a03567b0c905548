// radkit study: the speed-accuracy sweep of experiments/study.h and its files: study.csv,
// study.md, one error-versus-seconds chart per knob and the Pareto fronts.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include "apps/common.h"
#include "apps/console.h"
#include "hierarchy/hierarchical.h"
#include "job/study_job.h"

namespace radkit::app {

namespace {

void run(StudyJobSettings& job) {
  if (job.scene.empty()) job.scene = defaultScenePath();
  Progress progress;
  PipelineLog log;
  log.progress = [&](const std::string& stage, double f) { progress(stage, f); };
  log.message = [&](const std::string& line) {
    progress.finish();
    // Loading's warnings read as every other warning; the study's own lines say "study".
    if (line.rfind("warning: ", 0) == 0)
      printLogLine(line);
    else
      std::fprintf(stderr, "study: %s\n", line.c_str());
  };
  const StudyJobResult r = runStudyJob(job, log);
  progress.finish();
  const StudyResult& s = r.study;
  const int ran =
      int(std::count_if(s.rows.begin(), s.rows.end(), [](const StudyRow& w) { return w.ran; }));
  printField("scene", r.sceneName + " (" + r.sceneFile + ")");
  printField("configurations",
             std::to_string(ran) + " run, " + std::to_string(s.rows.size() - ran) + " skipped");
  printField("reference", std::to_string(s.reference.row.patches) +
                              " patches, error estimate surface " +
                              fmt("%.2e", s.reference.surfaceErrorEstimate) + ", patch " +
                              fmt("%.2e", s.reference.patchErrorEstimate));
  printField("seconds", fmt("%.1f", s.seconds));
  printField("wrote", r.out);
}

}  // namespace

void addStudyCommand(CLI::App& app) {
  auto cmd = std::make_shared<StudyJobSettings>();
  CLI::App* sub = app.add_subcommand(
      "study",
      "Speed against accuracy: sweep mesh density, form factors, solvers, adaptive meshes and the "
      "hierarchical "
      "method's epsilon within a time budget; study.csv, study.md and error-versus-seconds charts");
  sub->add_option("scene", cmd->scene, "Scene file (default: the Cornell box)");
  sub->add_option("--max-seconds", cmd->settings.maxSeconds, "Wall-clock budget of the whole study")
      ->check(FinitePositive)
      ->capture_default_str();
  sub->add_option("--knob-patches", cmd->settings.knobPatches,
                  "Mesh of the form-factor and solver sweeps (a rung of the mesh ladder)")
      ->check(CLI::IsMember({250, 500, 1000, 2000, 4000}))
      ->capture_default_str();
  sub->add_option("--seed", cmd->settings.baseline.formFactors.seed, "Seed of every random stream")
      ->check(Unsigned)
      ->capture_default_str();
  sub->add_option("--epsilons", cmd->epsilons,
                  "Hierarchical method's ladder of --epsilon, measured after the other knobs "
                  "(1e-3,3e-4 or 1e-3 3e-4)")
      ->delimiter(',')
      ->check(FiniteRange(kMinEpsilon, 1.0) & CLI::Validator(
                                                  [](std::string& t) {  // 1 itself is no threshold
                                                    return std::strtod(t.c_str(), nullptr) < 1
                                                               ? std::string()
                                                               : "'" + t + "' must be below 1";
                                                  },
                                                  ""))
      ->capture_default_str();
  sub->add_option("--out", cmd->out, "Output folder")->required();
  sub->callback([cmd] { run(*cmd); });
}

}  // namespace radkit::app
