// ConvergenceChart: residual against iteration and against seconds, one curve per solver run
// of convergence.csv, as two vtkChartXY drawn by a vtkContextActor inside a renderer's viewport.
#pragma once

#include <vtkChartXY.h>
#include <vtkContextActor.h>
#include <vtkNew.h>
#include <vtkRenderer.h>
#include <vtkTextActor.h>

#include "viewer/run_folder.h"

namespace radkit::viewer {

class ConvergenceChart {
 public:
  /// \brief One line per SolverHistory, log-scale residual; points with residual <= 0 (exact
  /// solves) are left out because a log axis cannot place them.
  explicit ConvergenceChart(const RunFolder& run);
  ConvergenceChart(const ConvergenceChart&) = delete;
  ConvergenceChart& operator=(const ConvergenceChart&) = delete;

  vtkRenderer* renderer() { return m_renderer; }
  /// Both charts side by side (screenshots), or one with `t` switching between them.
  void setSideBySide(bool both);
  /// The single chart's x axis: iteration (false) or wall seconds on a log axis (true).
  void setTimeAxis(bool seconds);
  bool timeAxis() const { return m_timeAxis; }
  void setFontSize(int pixels);

 private:
  void addCurves(vtkChartXY* chart, bool seconds);
  /// Places the charts in the viewport (before each render: the window may have been resized).
  void layout();

  const RunFolder& m_run;
  bool m_timeAxis = false, m_sideBySide = false;
  vtkNew<vtkRenderer> m_renderer;
  vtkNew<vtkContextActor> m_actor;
  vtkNew<vtkChartXY> m_byIteration, m_byTime;
  vtkNew<vtkTextActor> m_message;
};

}  // namespace radkit::viewer
