// Line charts written as PNG without a display (PLplot's cairo driver): convergence curves,
// error-versus-cost plots.
#pragma once

#include <string>
#include <vector>

namespace radkit {

struct ChartSeries {
  std::string name;
  std::vector<double> x, y;
};

/// One plot area; several are laid out side by side in one image.
struct ChartPanel {
  std::string title, xLabel, yLabel;
  bool logX = false, logY = false;
  std::vector<ChartSeries> series;
};

/// \brief Writes the panels side by side into a PNG of width × height pixels (atomically).
/// Non-positive values are dropped from logarithmic axes; an empty panel says "no data".
/// The legend sits bottom-left, where decreasing (convergence) curves leave room.
void writeLineChartPng(const std::string& path, const std::vector<ChartPanel>& panels, int width = 1400,
                       int height = 560);

}  // namespace radkit
