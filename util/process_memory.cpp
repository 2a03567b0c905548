#include "util/process_memory.h"

#include <sys/resource.h>

#include <fstream>
#include <string>

namespace radkit {

void resetPeakMemory() { std::ofstream("/proc/self/clear_refs") << "5"; }

std::size_t peakMemory() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::size_t(std::stoll(line.substr(6))) * 1024;
  return 0;
}

std::size_t lifetimePeakMemory() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return std::size_t(u.ru_maxrss) * 1024;  // Linux reports KiB
}

}  // namespace radkit
