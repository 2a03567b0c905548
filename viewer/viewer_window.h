// ViewerWindow: one render window holding the scene, matrix and convergence views; either all
// three side by side (interactive) or one filling the window (screenshots), plus key handling.
#pragma once

#include <vtkNew.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkTextActor.h>

#include <string>

#include "viewer/charts.h"
#include "viewer/matrix_view.h"
#include "viewer/run_folder.h"
#include "viewer/scene_view.h"
#include "viewer/view_settings.h"

namespace radkit::viewer {

class ViewerWindow {
 public:
  /// \param display the X connection (a Display*) to render through; it must outlive the window.
  /// \param offscreen render into an off-screen buffer (screenshots, picking through the API).
  ViewerWindow(const RunFolder& run, const ViewSettings& settings, void* display, int width,
               int height, bool offscreen);
  ViewerWindow(const ViewerWindow&) = delete;
  ViewerWindow& operator=(const ViewerWindow&) = delete;

  /// One view fills the window: the scene for Radiosity/FalseColour/FormFactorRow.
  void layoutSingle(ViewMode mode);
  /// Scene on the left; matrix (top) and convergence chart (bottom) on the right; key list.
  void layoutAll();
  /// Applies the settings to every view and renders.
  void refresh();
  /// \brief Renders and writes the window as PNG via `path`.tmp and a rename.
  /// \throws std::runtime_error when the image is not exactly the window size or not written.
  void writePng(const std::string& path);
  /// Opens the window and runs the event loop until q, Escape or the window closes.
  void interact();
  /// Lays out all views and connects radkit's mouse and key handling to `interactor`
  /// (interact() without the event loop, so events can also be sent by a program).
  void attach(vtkRenderWindowInteractor* interactor);

  /// \brief Scene patch under display point (x, y), VTK display pixels (origin bottom-left).
  int pickScene(double x, double y) { return m_scene.pick(x, y); }

  // Event handlers for the interactor style (viewer_interaction.cpp).
  /// \return false when the key asks to quit.
  bool onKey(char code, const std::string& sym);
  /// A click (no drag) at display point (x, y) in `renderer`: picks a patch or a matrix row.
  void onClick(vtkRenderer* renderer, int x, int y);
  vtkRenderer* sceneRenderer() { return m_scene.renderer(); }
  const ViewSettings& settings() const { return m_settings; }

 private:
  void setFontSizes(int height);
  void removeRenderers();
  void select(int patch);
  void cycleColourMode();

  const RunFolder& m_run;
  ViewSettings m_settings;
  SceneView m_scene;
  MatrixView m_matrix;
  ConvergenceChart m_chart;
  vtkNew<vtkRenderWindow> m_window;
  vtkNew<vtkTextActor> m_keys;
};

}  // namespace radkit::viewer
