// The process's peak resident memory, resettable so one stage's peak can be told from another's.
#pragma once

#include <cstddef>

namespace radkit {

/// Linux: writing "5" to /proc/self/clear_refs resets VmHWM to the current resident set.
void resetPeakMemory();
/// VmHWM of /proc/self/status in bytes (0 where it cannot be read).
std::size_t peakMemory();
/// The process's lifetime peak resident memory in bytes (getrusage; unaffected by resets).
std::size_t lifetimePeakMemory();

}  // namespace radkit
