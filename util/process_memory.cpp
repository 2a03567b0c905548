#include "util/process_memory.h"

#include <malloc.h>
#include <sys/resource.h>
#include <unistd.h>

#include <fstream>
#include <string>

namespace radkit {

void resetPeakMemory() { std::ofstream("/proc/self/clear_refs") << "5"; }

namespace {
/// A "Key:   N kB" line of /proc/self/status in bytes.
std::size_t statusBytes(const std::string& key) {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind(key, 0) == 0) return std::size_t(std::stoll(line.substr(key.size()))) * 1024;
  return 0;
}
}  // namespace

std::size_t peakMemory() { return statusBytes("VmHWM:"); }

std::size_t residentMemory() { return statusBytes("VmRSS:"); }

void markStageMemory(std::vector<StageMemory>& stages, const std::string& stage) {
  // Hand freed heap back first, so "resident" is what the process holds, not what the
  // allocator kept from the stage's transients.
  malloc_trim(0);
  stages.push_back({stage, residentMemory(), lifetimePeakMemory()});
}

std::size_t availableMachineMemory() {
  const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGE_SIZE);
  std::size_t bytes = pages > 0 && pageSize > 0 ? std::size_t(pages) * std::size_t(pageSize) : 0;
  // cgroup v2; "max" (no limit) does not parse as a number and is ignored.
  std::ifstream limit("/sys/fs/cgroup/memory.max");
  unsigned long long cgroup = 0;
  if (limit >> cgroup && cgroup > 0 && (bytes == 0 || cgroup < bytes)) bytes = std::size_t(cgroup);
  return bytes;
}

std::size_t lifetimePeakMemory() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return std::size_t(u.ru_maxrss) * 1024;  // Linux reports KiB
}

}  // namespace radkit
