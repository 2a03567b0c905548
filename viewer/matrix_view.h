// MatrixView: the form-factor matrix F as a heat map (log colour scale) in a VTK renderer,
// grouped by surface, with the picked patch's row highlighted.
#pragma once

#include <vtkActor.h>
#include <vtkImageActor.h>
#include <vtkImageData.h>
#include <vtkLookupTable.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkRenderer.h>
#include <vtkScalarBarActor.h>
#include <vtkSmartPointer.h>
#include <vtkTextActor.h>

#include <vector>

#include "viewer/run_folder.h"
#include "viewer/view_settings.h"

namespace radkit::viewer {

class MatrixView {
 public:
  /// \param maxCells cells per side of the image before block averaging starts.
  explicit MatrixView(const RunFolder& run, int maxCells = 512);
  MatrixView(const MatrixView&) = delete;
  MatrixView& operator=(const MatrixView&) = delete;

  vtkRenderer* renderer() { return m_renderer; }
  /// Highlights the cell row holding patch `row` (-1: none).
  void setPickedRow(int row);
  /// \brief The patch row under display point (x, y) (VTK display pixels), -1 outside the map.
  int rowAt(double x, double y);
  void setFontSize(int pixels);
  /// Fits the matrix and its labels to the renderer's current aspect (before each render).
  void fit();

 private:
  void buildImage();
  /// A hierarchical run: its links.png as the matrix (no F to pick rows from).
  void showLinksImage();
  void buildSurfaceLines();
  void buildLabels();

  const RunFolder& m_run;
  MatrixCells m_cells;
  int m_linksWidth = 0, m_linksHeight = 0;  ///< links.png's size when it is shown
  int m_fontSize = 14;
  vtkNew<vtkRenderer> m_renderer;
  vtkNew<vtkImageData> m_image;
  vtkNew<vtkLookupTable> m_lut;
  vtkNew<vtkImageActor> m_imageActor;
  vtkNew<vtkActor> m_surfaceLines;
  vtkNew<vtkPolyData> m_rowBox;
  vtkNew<vtkActor> m_rowActor;
  vtkNew<vtkScalarBarActor> m_scalarBar;
  vtkNew<vtkTextActor> m_title;
  std::vector<vtkSmartPointer<vtkTextActor>> m_labels;
  std::vector<double> m_labelRow;  ///< world y of each label
};

}  // namespace radkit::viewer
