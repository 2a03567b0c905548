// The thread count of a run: `--threads N` on every command that computes, and the figure
// report.json gives.
#pragma once

namespace radkit {

/// \brief Caps every parallel loop of the process at n threads (n >= 1) until the process
/// ends or the next call; n = 0 lifts the cap (all cores).
void limitThreads(int n);

/// \brief Threads a parallel loop started here may use: the current arena's concurrency,
/// capped by limitThreads.
int activeThreads();

}  // namespace radkit
