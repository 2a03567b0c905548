// Mouse and keys of the interactive viewer: trackball camera in the scene view, a click
// without a drag picks, and radkit's keys replace VTK's default ones (w, 3, f, ...).
#include <vtkInteractorStyleTrackballCamera.h>
#include <vtkObjectFactory.h>
#include <vtkRenderWindowInteractor.h>

#include <cstdlib>

#include "viewer/viewer_window.h"

namespace radkit::viewer {

namespace {

class ViewerStyle : public vtkInteractorStyleTrackballCamera {
 public:
  static ViewerStyle* New();
  vtkTypeMacro(ViewerStyle, vtkInteractorStyleTrackballCamera)

      void setWindow(ViewerWindow* window) {
    m_window = window;
  }

  void OnChar() override {
    vtkRenderWindowInteractor* rwi = GetInteractor();
    const char* sym = rwi->GetKeySym();
    if (!m_window->onKey(rwi->GetKeyCode(), sym ? sym : "")) rwi->TerminateApp();
  }

  void OnLeftButtonDown() override {
    const int* at = GetInteractor()->GetEventPosition();
    m_down[0] = at[0];
    m_down[1] = at[1];
    FindPokedRenderer(at[0], at[1]);
    // Only the scene rotates; the matrix and chart stay framed.
    if (CurrentRenderer == m_window->sceneRenderer())
      vtkInteractorStyleTrackballCamera::OnLeftButtonDown();
  }

  void OnLeftButtonUp() override {
    const int* at = GetInteractor()->GetEventPosition();
    vtkRenderer* poked = GetInteractor()->FindPokedRenderer(at[0], at[1]);
    vtkInteractorStyleTrackballCamera::OnLeftButtonUp();
    if (std::abs(at[0] - m_down[0]) + std::abs(at[1] - m_down[1]) <= 3)
      m_window->onClick(poked, at[0], at[1]);
  }

  // Zooming and panning the framed matrix or chart makes no sense.
  void OnMouseWheelForward() override {
    if (inScene()) vtkInteractorStyleTrackballCamera::OnMouseWheelForward();
  }
  void OnMouseWheelBackward() override {
    if (inScene()) vtkInteractorStyleTrackballCamera::OnMouseWheelBackward();
  }

 private:
  bool inScene() {
    const int* at = GetInteractor()->GetEventPosition();
    return GetInteractor()->FindPokedRenderer(at[0], at[1]) == m_window->sceneRenderer();
  }

  ViewerWindow* m_window = nullptr;
  int m_down[2] = {0, 0};
};

vtkStandardNewMacro(ViewerStyle);

}  // namespace

void ViewerWindow::attach(vtkRenderWindowInteractor* interactor) {
  layoutAll();
  vtkNew<ViewerStyle> style;
  style->setWindow(this);
  interactor->SetInteractorStyle(style);
  interactor->SetRenderWindow(m_window);
  refresh();
  interactor->Initialize();
}

void ViewerWindow::interact() {
  vtkNew<vtkRenderWindowInteractor> interactor;
  attach(interactor);
  interactor->Start();
}

}  // namespace radkit::viewer
