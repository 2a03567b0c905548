// The two halves of runJob, one per method, on settings resolveJobSettings has completed.
#pragma once

#include <chrono>

#include "job/job.h"

namespace radkit {

/// `scene` as loaded (its camera set), `loaded` what loading reported; `start` is the job's
/// and `loadSeconds` the time loading took.
JobResult runDenseJob(Scene scene, const LoadReport& loaded, const JobSettings& settings,
                      const PipelineLog& log, std::chrono::steady_clock::time_point start);
JobResult runHierarchicalJob(Scene scene, const LoadReport& loaded, const JobSettings& settings,
                             const PipelineLog& log, std::chrono::steady_clock::time_point start,
                             double loadSeconds);

}  // namespace radkit
