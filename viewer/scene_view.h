// SceneView: the patches in a VTK renderer, seen through the scene's camera, coloured by
// radiosity (true or false colour) or by one row of form factors, with picking.
#pragma once

#include <vtkActor.h>
#include <vtkImageData.h>
#include <vtkLookupTable.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkRenderer.h>
#include <vtkScalarBarActor.h>
#include <vtkSkybox.h>
#include <vtkTextActor.h>
#include <vtkTexture.h>

#include <string>

#include "viewer/run_folder.h"
#include "viewer/view_settings.h"

namespace radkit::viewer {

class SceneView {
 public:
  /// \brief Builds the pipeline for `run` (which must outlive the view) and sets the camera:
  /// the scene's camera from report.json, or render/'s automaticCamera when it has none.
  explicit SceneView(const RunFolder& run);
  SceneView(const SceneView&) = delete;
  SceneView& operator=(const SceneView&) = delete;

  vtkRenderer* renderer() { return m_renderer; }

  /// \brief Recolours the patches: settings.mode Radiosity (true colour, with the run's sky
  /// behind them at the same exposure), FalseColour, or FormFactorRow (row settings.picked of F,
  /// log scale; falls back to true colour with a note when the run has no matrix or nothing is
  /// picked). Updates title, scalar bar, the picked patch's outline and its info panel.
  void show(const ViewSettings& settings);

  /// \brief The patch under display point (x, y) (VTK display pixels, origin bottom-left),
  /// or -1 for the background. Needs a rendered window.
  int pick(double x, double y);

  /// The exposure the last true-colour show() used (the automatic one when settings say 0).
  double autoExposureValue() const { return m_autoExposure; }

  /// Back to the scene's camera (after the user rotated or zoomed).
  void resetCamera();

  /// Text size in pixels for title, info panel and scalar bar.
  void setFontSize(int pixels);

 private:
  void showTrueColour(const ViewSettings& s);
  void showFalseColour(const ViewSettings& s);
  void showFormFactorRow(const ViewSettings& s);
  void setValues(const std::vector<double>& perPatch, bool smooth);
  void showOutline(int patch);
  /// The run's sky (if it has one) behind the patches at `exposure`; hidden when < 0.
  void showSky(double exposure);
  std::string patchInfo(int patch) const;

  const RunFolder& m_run;
  double m_autoExposure = 1, m_exposureUsed = 1;
  vtkNew<vtkRenderer> m_renderer;
  vtkNew<vtkPolyData> m_surface;
  vtkNew<vtkPolyDataMapper> m_mapper;
  vtkNew<vtkActor> m_actor;
  vtkNew<vtkLookupTable> m_lut;
  vtkNew<vtkScalarBarActor> m_scalarBar;
  vtkNew<vtkTextActor> m_title, m_info;
  vtkNew<vtkPolyData> m_outline;
  vtkNew<vtkPolyDataMapper> m_outlineMapper;
  vtkNew<vtkActor> m_outlineActor;
  // A run under a sky: its panorama, tone mapped like the patches, as a sphere skybox.
  vtkNew<vtkImageData> m_skyImage;
  vtkNew<vtkTexture> m_skyTexture;
  vtkNew<vtkSkybox> m_skybox;
  double m_skyExposure = -1;  ///< the exposure m_skyImage holds
};

}  // namespace radkit::viewer
