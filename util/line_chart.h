// Line charts written as PNG without a display (PLplot's cairo driver): convergence curves,
// error-versus-cost plots.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace radkit {

constexpr int kMarkersPerSeries = 12;
constexpr double kAutoLogSpan = 100;

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

/// True when values (finite ones) are all positive and max/min exceeds kAutoLogSpan.
bool needsLogAxis(const std::vector<double>& values);

/// Sum of the panels' data points: a chart of none is not worth a file.
std::size_t chartPoints(const std::vector<ChartPanel>& panels);

/// \brief Writes the panels side by side into a PNG of width × height pixels (atomically).
/// Non-positive values are dropped from logarithmic axes; an empty panel says "no data".
/// Each series has its own marker (at most kMarkersPerSeries, so dense curves stay lines);
/// the legend sits outside the plot, on its right, where it hides no curve.
/// A linear axis whose data are all positive and span more than kAutoLogSpan (one outlier
/// would squash the rest to the axis) is drawn logarithmic.
void writeLineChartPng(const std::string& path, const std::vector<ChartPanel>& panels,
                       int width = 1400, int height = 560);

}  // namespace radkit
