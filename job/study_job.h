// `radkit study` as one library call: the speed-accuracy sweep of experiments/study.h plus the
// hierarchical method's epsilon ladder within one time budget, and its files: study.csv,
// study.md, one error-versus-seconds chart per knob and the Pareto fronts.
#pragma once

#include <string>
#include <vector>

#include "experiments/study.h"
#include "radiosity/radiosity_pipeline.h"

namespace radkit {

struct StudyJobSettings {
  std::string scene;
  StudySettings settings;
  /// The hierarchical method's epsilon ladder, coarse to fine, measured after the other knobs;
  /// empty: none.
  std::vector<double> epsilons{1e-3, 3e-4, 1e-4, 3e-5, 1e-5};
  std::string out;
};

struct StudyJobResult {
  std::string out;
  std::string sceneName, sceneFile;
  StudyResult study;
};

/// \brief Runs the study and writes its folder (all or nothing). \throws InputError when the
/// budget is shorter than the reference alone, or for a bad scene.
StudyJobResult runStudyJob(const StudyJobSettings& settings, const PipelineLog& log = {});

}  // namespace radkit
