// Charts (issue 15, point 8): outliers get a log axis, the legend stays off the curves.
#include <gtest/gtest.h>

#include "tests/common/test_util.h"
#include "util/canvas.h"
#include "util/line_chart.h"

namespace radkit {
namespace {

TEST(LineChart, AnOutlierTurnsALinearAxisLogarithmic) {
  EXPECT_TRUE(needsLogAxis({1, 2, 3, 15084}));  // Southwell's shots beside sweeps
  EXPECT_FALSE(needsLogAxis({1, 2, 3, 50}));
  EXPECT_FALSE(needsLogAxis({0, 1, 15084}));  // zero has no logarithm: stays linear
  EXPECT_FALSE(needsLogAxis({}));
  EXPECT_EQ(chartPoints({ChartPanel{"a", "x", "y", false, false, {}}}), 0u);
  EXPECT_EQ(
      chartPoints({ChartPanel{"a", "x", "y", false, false, {ChartSeries{"s", {1, 2}, {3, 4}}}}}),
      2u);
}

TEST(LineChart, LegendSitsOutsideThePlot) {
  // One point in the middle of the plot: the series' colour (Okabe-Ito blue 0,114,178) right
  // of the plot area can only be the legend's sample.
  test::TempDir dir;
  const std::string png = dir.path("chart.png");
  writeLineChartPng(
      png, {ChartPanel{"t", "x", "y", false, false, {ChartSeries{"series", {0.5}, {0.5}}}}}, 600,
      400);
  const Canvas c = readPng(png);
  int legendPixels = 0;
  for (int y = 0; y < c.height(); ++y)
    for (int x = int(0.78 * c.width()); x < c.width(); ++x) {
      const Rgb8 p = c.at(x, y);
      if (p.r < 40 && p.g > 90 && p.g < 140 && p.b > 150) ++legendPixels;
    }
  EXPECT_GT(legendPixels, 10);
}

}  // namespace
}  // namespace radkit
