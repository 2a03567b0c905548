#include "apps/console.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "apps/common.h"

namespace radkit::app {

void printEnergyAndSurfaces(const EnergyBalance& e, const std::vector<SurfaceResult>& surfaces,
                            bool photometric, const std::string& escapedNote) {
  printField("energy balance", "emitted " + fmt("%.4g W", luminance(e.emitted)) + " = absorbed " +
                                   fmt("%.4g", luminance(e.absorbed)) + " + escaped " +
                                   fmt("%.4g", luminance(e.escaped)) + escapedNote +
                                   " (Y), imbalance " + fmt("%.2e", e.relativeImbalance));
  for (const SurfaceResult& s : surfaces) {
    std::string line = fmt("%10.4f", s.radiosity.x) + fmt(" %10.4f", s.radiosity.y) +
                       fmt(" %10.4f W/m²", s.radiosity.z);
    if (photometric || s.daylit)
      line += fmt("  %9.2f cd/m²", s.luminance) + fmt("  %9.1f lux", s.illuminance);
    if (s.daylit) line += fmt("  sky view %.3f", s.skyViewFactor);
    printField(s.name, line);
  }
}

void Progress::operator()(const std::string& stage, double fraction) {
  bool terminal = isatty(STDERR_FILENO);
  if (stage != m_stage) {
    finish();
    m_stage = stage;
    m_lastTenth = -1;
  }
  int tenth = int(fraction * 10 + 1e-9);
  if (terminal) {
    const int filled = int(std::lround(fraction * 30));
    std::fprintf(stderr, "\r%-14s [%s%s] %3d%%", stage.c_str(), std::string(filled, '#').c_str(),
                 std::string(30 - filled, '.').c_str(), int(std::lround(fraction * 100)));
    m_open = true;
  } else if (tenth > m_lastTenth) {
    std::fprintf(stderr, "%s: %d%%\n", stage.c_str(), tenth * 10);
  }
  m_lastTenth = std::max(m_lastTenth, tenth);
  std::fflush(stderr);
}

void Progress::finish() {
  if (m_open) std::fprintf(stderr, "\n");
  m_open = false;
}

PipelineLog consoleLog(Progress& progress) {
  PipelineLog log;
  log.progress = [&progress](const std::string& stage, double f) { progress(stage, f); };
  log.message = [&progress](const std::string& line) {
    progress.finish();
    printLogLine(line);
  };
  return log;
}

}  // namespace radkit::app
