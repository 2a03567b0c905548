#include "util/threads.h"

#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <memory>

namespace radkit {

namespace {
std::unique_ptr<tbb::global_control>& threadLimit() {
  static std::unique_ptr<tbb::global_control> limit;
  return limit;
}
}  // namespace

void limitThreads(int n) {
  threadLimit().reset();
  if (n > 0)
    threadLimit() = std::make_unique<tbb::global_control>(
        tbb::global_control::max_allowed_parallelism, std::size_t(n));
}

int activeThreads() {
  std::size_t allowed =
      tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
  return int(std::min<std::size_t>(std::size_t(tbb::this_task_arena::max_concurrency()), allowed));
}

}  // namespace radkit
