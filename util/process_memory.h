// The process's peak resident memory, resettable so one stage's peak can be told from another's.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace radkit {

/// Linux: writing "5" to /proc/self/clear_refs resets VmHWM to the current resident set.
void resetPeakMemory();
/// VmHWM of /proc/self/status in bytes (0 where it cannot be read).
std::size_t peakMemory();
/// The process's lifetime peak resident memory in bytes (getrusage; unaffected by resets).
std::size_t lifetimePeakMemory();
/// VmRSS of /proc/self/status in bytes: what the process holds now (0 where it cannot be read).
std::size_t residentMemory();
/// Memory this process may use: the machine's installed memory, or the cgroup's limit
/// (memory.max, as in a container or a batch job) when that is lower; 0 where unknown.
std::size_t availableMachineMemory();

/// Memory after one stage of a run: what the process still holds, and the lifetime peak so far
/// (which includes the stage's transient buffers). Read without resetting anything, so a caller
/// measuring a whole run's peak (the study, the benchmarks) is not disturbed.
struct StageMemory {
  std::string stage;
  std::size_t resident = 0, peak = 0;
};
/// Appends `stage` with the memory now to `stages`.
void markStageMemory(std::vector<StageMemory>& stages, const std::string& stage);

}  // namespace radkit
