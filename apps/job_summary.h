// The console summaries of the main job (job/job.h), one per method.
#pragma once

#include "job/job.h"

namespace radkit::app {

void printDenseSummary(const JobResult& result, bool writeMatrix, bool photometric);
void printHierarchicalSummary(const JobResult& result, double epsilon, bool photometric);

}  // namespace radkit::app
