#include "viewer/matrix_view.h"

#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCommand.h>
#include <vtkImageMapper3D.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkTextProperty.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <cmath>

#include "util/errors.h"
#include "viewer/colour_maps.h"

namespace radkit::viewer {

namespace {

constexpr double kMatrixZeroColour[3] = {0.22, 0.22, 0.25};
constexpr double kBoundary[3] = {0.95, 0.33, 0.28};
constexpr double kPicked[3] = {0.2, 0.95, 1.0};
constexpr double kBarPixels = 110;  // room right of the matrix for the colour bar

/// Polyline segments as a mapper-ready actor input.
void addSegment(vtkPoints* points, vtkCellArray* lines, double x0, double y0, double x1,
                double y1) {
  lines->InsertNextCell(2);
  lines->InsertCellPoint(points->InsertNextPoint(x0, y0, 0.01));
  lines->InsertCellPoint(points->InsertNextPoint(x1, y1, 0.01));
}

}  // namespace

MatrixView::MatrixView(const RunFolder& run, int maxCells) : m_run(run) {
  m_renderer->SetBackground(kBackground[0], kBackground[1], kBackground[2]);
  m_renderer->GetActiveCamera()->ParallelProjectionOn();
  m_title->GetPositionCoordinate()->SetCoordinateSystemToNormalizedViewport();
  m_title->SetPosition(0.015, 0.975);
  m_renderer->AddActor2D(m_title);
  if (!run.formFactors && run.links.width > 0) {
    showLinksImage();
    return;
  }
  if (!run.formFactors) {  // say why, centred, one clause a line
    std::string why = "form-factor matrix:\n" + run.formFactorsMissing;
    for (const char* at : {" (", ": "})
      if (auto k = why.find(at, why.find('\n')); k != std::string::npos)
        why[k + (at[0] == ' ' ? 0 : 1)] = '\n';
    m_title->SetInput(why.c_str());
    m_title->SetPosition(0.5, 0.5);
    setFontSize(m_fontSize);
    return;
  }
  m_cells = downsampleMatrix(*run.formFactors, maxCells);
  buildImage();
  buildSurfaceLines();
  buildLabels();
  m_rowActor->SetVisibility(false);
  vtkNew<vtkPolyDataMapper> rowMapper;
  rowMapper->SetInputData(m_rowBox);
  m_rowActor->SetMapper(rowMapper);
  m_rowActor->GetProperty()->SetColor(kPicked[0], kPicked[1], kPicked[2]);
  m_rowActor->GetProperty()->SetLineWidth(2);
  m_renderer->AddActor(m_rowActor);
  m_scalarBar->SetLookupTable(m_lut);
  m_scalarBar->SetNumberOfLabels(4);
  m_scalarBar->SetLabelFormat("%.0e");
  m_scalarBar->DrawBelowRangeSwatchOn();
  m_scalarBar->SetBelowRangeAnnotation("0");
  m_renderer->AddActor2D(m_scalarBar);
  const std::string how = m_cells.block > 1
                              ? ", cell = mean of " + std::to_string(m_cells.block) + "x" +
                                    std::to_string(m_cells.block) + " patch pairs"
                              : "";
  m_title->SetInput(("form factors F_ij (row i to column j): " +
                     std::to_string(run.formFactors->n) + " patches" + how)
                        .c_str());
  setFontSize(m_fontSize);
  m_renderer->AddObserver(vtkCommand::StartEvent, this, &MatrixView::fit);
}

void MatrixView::showLinksImage() {
  // Decoded and checked by readRunFolder (readLinksPng); VTK's PNG reader is not used, as it
  // crashed after libpng's error on a truncated file.
  const LinksImage& links = m_run.links;
  m_linksWidth = links.width, m_linksHeight = links.height;
  m_image->SetDimensions(links.width, links.height, 1);
  vtkNew<vtkUnsignedCharArray> rgb;
  rgb->SetNumberOfComponents(3);
  rgb->SetNumberOfTuples(vtkIdType(links.width) * links.height);
  for (int y = 0; y < links.height; ++y)  // PNG rows run down, VTK's image rows up
    std::copy_n(&links.rgb[std::size_t(y) * links.width * 3], std::size_t(links.width) * 3,
                rgb->GetPointer(vtkIdType(links.height - 1 - y) * links.width * 3));
  m_image->GetPointData()->SetScalars(rgb);
  m_imageActor->GetMapper()->SetInputData(m_image);
  m_imageActor->InterpolateOff();
  m_renderer->AddActor(m_imageActor);
  // links.png carries its own title, labels and colour bar.
  m_title->SetInput(
      "links.png: each link r <- s of the hierarchy is a block over r's rows and s's columns");
  setFontSize(m_fontSize);
  m_renderer->AddObserver(vtkCommand::StartEvent, this, &MatrixView::fit);
}

void MatrixView::buildImage() {
  const int n = m_cells.cells;
  double hi = 0, minPositive = INFINITY;
  for (double v : m_cells.value) {
    hi = std::max(hi, v);
    if (v > 0) minPositive = std::min(minPositive, v);
  }
  if (hi <= 0) hi = minPositive = 1;
  const double top = std::pow(10.0, std::ceil(std::log10(hi) - 1e-12));
  const double lo = std::max(std::pow(10.0, std::floor(std::log10(minPositive))), top * 1e-6);
  fillLookupTable(m_lut, ColourMap::Viridis, lo, top, true, kMatrixZeroColour, kMatrixZeroColour);

  m_image->SetDimensions(n, n, 1);
  m_image->SetOrigin(0.5, 0.5, 0);  // cell (row r, column c) covers [c, c+1] × [n-1-r, n-r]
  m_image->SetSpacing(1, 1, 1);
  vtkNew<vtkUnsignedCharArray> rgb;
  rgb->SetNumberOfComponents(3);
  rgb->SetNumberOfTuples(vtkIdType(n) * n);
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) {
      const double v = m_cells.value[std::size_t(r) * n + c];
      const unsigned char* colour = m_lut->MapValue(v > 0 ? std::max(v, lo) : NAN);
      rgb->SetTypedTuple(vtkIdType(n - 1 - r) * n + c, colour);
    }
  m_image->GetPointData()->SetScalars(rgb);
  m_imageActor->GetMapper()->SetInputData(m_image);
  m_imageActor->InterpolateOff();
  m_renderer->AddActor(m_imageActor);
}

void MatrixView::buildSurfaceLines() {
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> lines;
  const double n = m_cells.cells;
  const std::vector<int>& surface = m_run.patches.surface;
  for (std::size_t i = 1; i < surface.size(); ++i) {
    if (surface[i] == surface[i - 1]) continue;
    const double at = double(i) / m_cells.block;
    addSegment(points, lines, at, 0, at, n);
    addSegment(points, lines, 0, n - at, n, n - at);
  }
  vtkNew<vtkPolyData> data;
  data->SetPoints(points);
  data->SetLines(lines);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(data);
  m_surfaceLines->SetMapper(mapper);
  m_surfaceLines->GetProperty()->SetColor(kBoundary[0], kBoundary[1], kBoundary[2]);
  m_surfaceLines->GetProperty()->SetOpacity(0.8);
  m_renderer->AddActor(m_surfaceLines);
}

void MatrixView::buildLabels() {
  const std::vector<int>& surface = m_run.patches.surface;
  for (std::size_t begin = 0; begin < surface.size();) {
    std::size_t end = begin;
    while (end < surface.size() && surface[end] == surface[begin]) ++end;
    auto label = vtkSmartPointer<vtkTextActor>::New();
    label->SetInput(m_run.surfaceName(int(begin)).c_str());
    label->GetPositionCoordinate()->SetCoordinateSystemToWorld();
    m_labels.push_back(label);
    m_labelRow.push_back(m_cells.cells - 0.5 * (begin + end) / m_cells.block);
    m_renderer->AddActor2D(label);
    begin = end;
  }
}

void MatrixView::setFontSize(int pixels) {
  m_fontSize = pixels;
  styleText(m_title->GetTextProperty(), pixels, false);
  if (m_cells.cells == 0 && m_linksWidth == 0) {  // the message in the middle
    m_title->GetTextProperty()->SetJustificationToCentered();
    m_title->GetTextProperty()->SetVerticalJustificationToCentered();
  } else {
    m_title->GetTextProperty()->SetVerticalJustificationToTop();
  }
  for (auto& label : m_labels) {
    styleText(label->GetTextProperty(), pixels, false);
    label->GetTextProperty()->SetJustificationToRight();
    label->GetTextProperty()->SetVerticalJustificationToCentered();
  }
  styleScalarBar(m_scalarBar, pixels);
  m_scalarBar->SetTitle("F");
}

void MatrixView::fit() {
  const int* size = m_renderer->GetSize();
  const double w = std::max(1, size[0]), h = std::max(1, size[1]);
  if (m_linksWidth > 0) {  // the whole PNG, centred below the title, aspect kept
    const double top = 2.6 * m_fontSize;
    const double scale =
        std::min(w / m_linksWidth, (h - top) / m_linksHeight);  // pixels per image pixel
    vtkCamera* cam = m_renderer->GetActiveCamera();
    const double cx = (m_linksWidth - 1) / 2.0, cy = (m_linksHeight - 1) / 2.0 + top / 2 / scale;
    cam->SetFocalPoint(cx, cy, 0);
    cam->SetPosition(cx, cy, 10.0 * m_linksHeight);
    cam->SetViewUp(0, 1, 0);
    cam->SetParallelScale(h / 2 / scale);
    m_renderer->ResetCameraClippingRange();
    return;
  }
  if (m_cells.cells == 0) return;
  double labelPixels = 0;
  for (auto& label : m_labels)
    labelPixels = std::max(labelPixels, 0.6 * m_fontSize * std::string(label->GetInput()).size());
  const double top = 2.6 * m_fontSize, bottom = 0.8 * m_fontSize;
  double left = labelPixels + 0.8 * m_fontSize;
  const double side = std::max(16.0, std::min(w - left - kBarPixels, h - top - bottom));
  left += std::max(0.0, (w - left - kBarPixels - side) / 2);  // centre what is left over
  const double n = m_cells.cells, perUnit = side / n;
  vtkCamera* cam = m_renderer->GetActiveCamera();
  const double cx = (w / 2 - left) / perUnit, cy = n - (h / 2 - top) / perUnit;
  cam->SetFocalPoint(cx, cy, 0);
  cam->SetPosition(cx, cy, 10 * n);
  cam->SetViewUp(0, 1, 0);
  cam->SetParallelScale(h / 2 / perUnit);
  m_renderer->ResetCameraClippingRange();

  // Labels left of their surface's rows, dropping any that would overlap the one above.
  double lastY = INFINITY;
  for (std::size_t k = 0; k < m_labels.size(); ++k) {
    m_labels[k]->SetPosition(-0.4 * m_fontSize / perUnit, m_labelRow[k]);
    const bool room = (lastY - m_labelRow[k]) * perUnit >= 1.2 * m_fontSize;
    m_labels[k]->SetVisibility(room);
    if (room) lastY = m_labelRow[k];
  }
  m_scalarBar->SetPosition((left + side + 0.8 * m_fontSize) / w, bottom / h + 0.15 * side / h);
  m_scalarBar->SetPosition2((kBarPixels - 0.8 * m_fontSize) / w, 0.7 * side / h);
}

void MatrixView::setPickedRow(int row) {
  m_rowActor->SetVisibility(row >= 0 && m_cells.cells > 0);
  if (row < 0 || m_cells.cells == 0) return;
  const int block = row / m_cells.block;  // the row's cell in the (possibly binned) matrix
  const double n = m_cells.cells, r = block, pad = 0.004 * n;
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> lines;
  addSegment(points, lines, -pad, n - r + pad, n + pad, n - r + pad);
  addSegment(points, lines, n + pad, n - r + pad, n + pad, n - r - 1 - pad);
  addSegment(points, lines, n + pad, n - r - 1 - pad, -pad, n - r - 1 - pad);
  addSegment(points, lines, -pad, n - r - 1 - pad, -pad, n - r + pad);
  m_rowBox->SetPoints(points);
  m_rowBox->SetLines(lines);
  m_rowBox->Modified();
}

int MatrixView::rowAt(double x, double y) {
  if (m_cells.cells == 0) return -1;
  double world[4];
  m_renderer->SetDisplayPoint(x, y, 0);
  m_renderer->DisplayToWorld();
  m_renderer->GetWorldPoint(world);
  const double n = m_cells.cells, wx = world[0] / world[3], wy = world[1] / world[3];
  if (wx < 0 || wx >= n || wy <= 0 || wy > n) return -1;
  return std::min(m_run.formFactors->n - 1, int((n - wy) * m_cells.block));
}

}  // namespace radkit::viewer
