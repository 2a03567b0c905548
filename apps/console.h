// What the command line prints: progress bars and the energy and surface lines of a summary.
#pragma once

#include <string>
#include <vector>

#include "radiosity/radiosity_pipeline.h"
#include "radiosity/radiosity_solution.h"

namespace radkit::app {

/// Prints the energy balance ("escaped" followed by `escapedNote`) and one line of radiosity
/// per surface (with cd/m² and lux when photometric).
void printEnergyAndSurfaces(const EnergyBalance& e, const std::vector<SurfaceResult>& surfaces,
                            bool photometric, const std::string& escapedNote = "");

/// Shows a stage's progress: a redrawn bar when stderr is a terminal, else a line per 10 %.
class Progress {
 public:
  void operator()(const std::string& stage, double fraction);
  void finish();

 private:
  std::string m_stage;
  int m_lastTenth = -1;
  bool m_open = false;
};

/// A library log for the console: stages draw `progress`, and each line ends the bar and is
/// printed (printLogLine).
PipelineLog consoleLog(Progress& progress);

}  // namespace radkit::app
