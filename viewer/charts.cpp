#include "viewer/charts.h"

#include <vtkAxis.h>
#include <vtkBrush.h>
#include <vtkChartLegend.h>
#include <vtkCommand.h>
#include <vtkContextScene.h>
#include <vtkDoubleArray.h>
#include <vtkPen.h>
#include <vtkPlot.h>
#include <vtkTable.h>
#include <vtkTextProperty.h>

#include <algorithm>
#include <cmath>

#include "viewer/colour_maps.h"

namespace radkit::viewer {

namespace {

/// Okabe–Ito colours (distinguishable with colour-blindness), as convergence.png uses.
constexpr unsigned char kCurveColours[][3] = {{0, 114, 178},   {213, 94, 0},  {0, 158, 115},
                                              {204, 121, 167}, {230, 159, 0}, {86, 180, 233}};

vtkSmartPointer<vtkTable> historyTable(const SolverHistory& h, bool seconds) {
  vtkNew<vtkDoubleArray> x, y;
  x->SetName(seconds ? "seconds" : "iteration");
  y->SetName(h.solver.c_str());
  for (std::size_t k = 0; k < h.residual.size(); ++k) {
    const double xv = seconds ? h.seconds[k] : h.iteration[k];
    // Not placeable on a log axis, nor are NaN and infinity (a diverging solve).
    if (!(h.residual[k] > 0) || (seconds && !(xv > 0)) || !std::isfinite(h.residual[k]) ||
        !std::isfinite(xv))
      continue;
    x->InsertNextValue(xv);
    y->InsertNextValue(h.residual[k]);
  }
  auto table = vtkSmartPointer<vtkTable>::New();
  table->AddColumn(x);
  table->AddColumn(y);
  return table;
}

void styleChart(vtkChartXY* chart) {
  chart->SetShowLegend(true);
  chart->GetLegend()->SetHorizontalAlignment(vtkChartLegend::RIGHT);
  chart->GetLegend()->SetVerticalAlignment(vtkChartLegend::TOP);
  chart->GetLegend()->GetBrush()->SetColorF(1, 1, 1, 0.85);
  for (int a : {vtkAxis::LEFT, vtkAxis::BOTTOM}) {
    chart->GetAxis(a)->GetGridPen()->SetColorF(0.88, 0.88, 0.88);
    chart->GetAxis(a)->SetNotation(vtkAxis::PRINTF_NOTATION);
  }
  vtkAxis* y = chart->GetAxis(vtkAxis::LEFT);
  y->SetLogScale(true);
  y->SetTitle("relative residual");
  y->SetLabelFormat("%.0e");
  chart->SetAutoSize(false);
}

}  // namespace

ConvergenceChart::ConvergenceChart(const RunFolder& run) : m_run(run) {
  m_renderer->SetBackground(1, 1, 1);
  m_actor->GetScene()->SetRenderer(m_renderer);
  m_renderer->AddActor(m_actor);
  for (vtkChartXY* chart : {m_byIteration.Get(), m_byTime.Get()}) styleChart(chart);
  m_actor->GetScene()->AddItem(m_byIteration);
  m_actor->GetScene()->AddItem(m_byTime);
  addCurves(m_byIteration, false);
  addCurves(m_byTime, true);
  m_byIteration->GetAxis(vtkAxis::BOTTOM)->SetLabelFormat("%g");
  m_byTime->GetAxis(vtkAxis::BOTTOM)->SetLabelFormat("%.0e");
  m_message->GetPositionCoordinate()->SetCoordinateSystemToNormalizedViewport();
  m_message->SetPosition(0.5, 0.5);
  m_message->SetVisibility(run.convergence.empty());
  m_message->SetInput(run.convergenceMissing.empty() ? "convergence.csv has no rows"
                                                     : run.convergenceMissing.c_str());
  m_renderer->AddActor2D(m_message);
  setFontSize(15);
  setTimeAxis(false);
  m_renderer->AddObserver(vtkCommand::StartEvent, this, &ConvergenceChart::layout);
}

void ConvergenceChart::addCurves(vtkChartXY* chart, bool seconds) {
  for (std::size_t k = 0; k < m_run.convergence.size(); ++k) {
    vtkPlot* line = chart->AddPlot(vtkChart::LINE);
    line->SetInputData(historyTable(m_run.convergence[k], seconds), 0, 1);
    const unsigned char* c = kCurveColours[k % std::size(kCurveColours)];
    line->SetColor(c[0], c[1], c[2], 255);
    line->SetWidth(2.5);
  }
  vtkAxis* x = chart->GetAxis(vtkAxis::BOTTOM);
  x->SetLogScale(seconds);
  x->SetTitle(seconds ? "seconds" : "iteration (one sweep; one shot for southwell)");
  chart->SetTitle("residual against " + std::string(seconds ? "time" : "iteration"));
}

void ConvergenceChart::setSideBySide(bool both) {
  m_sideBySide = both;
  setTimeAxis(m_timeAxis);
}

void ConvergenceChart::setTimeAxis(bool seconds) {
  m_timeAxis = seconds;
  m_byIteration->SetVisible(m_sideBySide || !seconds);
  m_byTime->SetVisible(m_sideBySide || seconds);
}

void ConvergenceChart::layout() {
  const int* size = m_renderer->GetSize();
  const float w = float(size[0]), h = float(size[1]);
  if (m_sideBySide) {
    m_byIteration->SetSize(vtkRectf(0, 0, w / 2, h));
    m_byTime->SetSize(vtkRectf(w / 2, 0, w / 2, h));
  } else {
    m_byIteration->SetSize(vtkRectf(0, 0, w, h));
    m_byTime->SetSize(vtkRectf(0, 0, w, h));
  }
}

void ConvergenceChart::setFontSize(int pixels) {
  auto style = [&](vtkTextProperty* t, int size) {
    t->SetFontSize(size);
    t->SetColor(0.1, 0.1, 0.12);
    t->SetFontFamilyToArial();
    t->BoldOff();
    t->ItalicOff();
  };
  for (vtkChartXY* chart : {m_byIteration.Get(), m_byTime.Get()}) {
    for (int a : {vtkAxis::LEFT, vtkAxis::BOTTOM}) {
      style(chart->GetAxis(a)->GetTitleProperties(), pixels);
      style(chart->GetAxis(a)->GetLabelProperties(), pixels - 2);
    }
    style(chart->GetTitleProperties(), pixels + 1);
    style(chart->GetLegend()->GetLabelProperties(), pixels);
  }
  styleText(m_message->GetTextProperty(), pixels, false);
  m_message->GetTextProperty()->SetColor(0.1, 0.1, 0.12);
  m_message->GetTextProperty()->SetJustificationToCentered();
}

}  // namespace radkit::viewer
