#include "viewer/viewer_window.h"

#include <vtkPNGWriter.h>
#include <vtkRendererCollection.h>
#include <vtkTextProperty.h>
#include <vtkWindowToImageFilter.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "viewer/colour_maps.h"

namespace radkit::viewer {

namespace {

constexpr const char* kKeyList =
    "click  pick a patch (or a matrix row)\n"
    "drag   rotate,  wheel  zoom\n"
    "s      smooth / flat\n"
    "c      colour: true / false / F row\n"
    "r g b l  false-colour channel\n"
    "+ -    exposure x/÷ 1.41 (a: auto)\n"
    "p      photometric (cd/m²)\n"
    "e      patch edges\n"
    "t      chart x: iteration / time\n"
    "v      reset view,  h  hide keys\n"
    "q      quit";

}  // namespace

ViewerWindow::ViewerWindow(const RunFolder& run, const ViewSettings& settings, void* display,
                           int width, int height, bool offscreen)
    : m_run(run), m_settings(settings), m_scene(run), m_matrix(run), m_chart(run) {
  m_window->SetDisplayId(display);
  m_window->SetSize(width, height);
  m_window->SetOffScreenRendering(offscreen);
  m_window->SetMultiSamples(4);
  m_window->SetWindowName(("radkit view: " + run.report.sceneName + " (" + run.path + ")").c_str());
  m_keys->SetInput(kKeyList);
  m_keys->GetPositionCoordinate()->SetCoordinateSystemToNormalizedViewport();
  m_keys->SetPosition(0.012, 0.02);
  setFontSizes(height);
}

void ViewerWindow::setFontSizes(int height) {
  const int pixels = std::clamp(int(std::lround(height / 50.0)), 11, 28);
  m_scene.setFontSize(pixels);
  m_matrix.setFontSize(pixels - 1);
  m_chart.setFontSize(pixels);
  styleText(m_keys->GetTextProperty(), pixels - 2);
  m_keys->GetTextProperty()->SetFontFamilyToCourier();
}

void ViewerWindow::removeRenderers() {
  while (vtkRenderer* r = m_window->GetRenderers()->GetFirstRenderer()) m_window->RemoveRenderer(r);
}

void ViewerWindow::layoutSingle(ViewMode mode) {
  removeRenderers();
  vtkRenderer* r = mode == ViewMode::Matrix        ? m_matrix.renderer()
                   : mode == ViewMode::Convergence ? m_chart.renderer()
                                                   : m_scene.renderer();
  r->SetViewport(0, 0, 1, 1);
  m_window->AddRenderer(r);
  m_chart.setSideBySide(true);
  if (mode != ViewMode::Matrix && mode != ViewMode::Convergence) m_settings.mode = mode;
}

void ViewerWindow::layoutAll() {
  removeRenderers();
  if (m_settings.mode == ViewMode::Matrix || m_settings.mode == ViewMode::Convergence)
    m_settings.mode = ViewMode::Radiosity;  // both are always on screen here
  constexpr double kSplit = 0.6;
  m_scene.renderer()->SetViewport(0, 0, kSplit, 1);
  m_matrix.renderer()->SetViewport(kSplit, 0.45, 1, 1);
  m_chart.renderer()->SetViewport(kSplit, 0, 1, 0.45);
  m_window->AddRenderer(m_scene.renderer());
  m_window->AddRenderer(m_matrix.renderer());
  m_window->AddRenderer(m_chart.renderer());
  m_chart.setSideBySide(false);
  // The key list sits bottom-left, below the picked patch's panel (top-left).
  m_scene.renderer()->AddActor2D(m_keys);
}

void ViewerWindow::refresh() {
  m_scene.show(m_settings);
  m_matrix.setPickedRow(m_settings.picked);
  m_window->Render();
}

void ViewerWindow::writePng(const std::string& path) {
  refresh();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(m_window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->Update();
  const int* want = m_window->GetSize();
  int got[3];
  grab->GetOutput()->GetDimensions(got);
  if (got[0] != want[0] || got[1] != want[1])
    throw std::runtime_error("screenshot: got " + std::to_string(got[0]) + "x" +
                             std::to_string(got[1]) + " pixels instead of " +
                             std::to_string(want[0]) + "x" + std::to_string(want[1]));
  const std::string tmp = path + ".tmp";
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputConnection(grab->GetOutputPort());
  writer->SetFileName(tmp.c_str());
  writer->Write();
  std::error_code ec;
  if (writer->GetErrorCode() != 0 || !std::filesystem::exists(tmp)) {
    std::filesystem::remove(tmp, ec);
    throw std::runtime_error(path + ": could not write the screenshot (is the folder writable?)");
  }
  std::filesystem::rename(tmp, path);
}

bool ViewerWindow::onKey(char code, const std::string& sym) {
  ViewSettings& s = m_settings;
  if (code == 'q' || sym == "Escape") return false;
  if (code == 's') s.smooth = !s.smooth;
  if (code == 'c') cycleColourMode();
  if (code == 'e') s.edges = !s.edges;
  if (code == 'a') s.exposure = 0;
  if (code == 't') m_chart.setTimeAxis(!m_chart.timeAxis());
  if (code == 'v') m_scene.resetCamera();
  if (code == 'h') m_keys->SetVisibility(!m_keys->GetVisibility());
  const Channel channels[] = {Channel::Red, Channel::Green, Channel::Blue, Channel::Luminance};
  const std::string channelKeys = "rgbl";
  if (auto at = channelKeys.find(code); code != 0 && at != std::string::npos) {
    s.channel = channels[at];
    s.photometric = s.photometric && s.channel == Channel::Luminance;
    s.mode = ViewMode::FalseColour;
  }
  if (code == 'p') {
    s.photometric = !s.photometric;
    if (s.photometric) s.channel = Channel::Luminance;
    s.mode = ViewMode::FalseColour;
  }
  const bool up = code == '+' || code == '=' || sym == "KP_Add";
  const bool down = code == '-' || sym == "KP_Subtract";
  if (up || down) {
    const double now = s.exposure > 0 ? s.exposure : m_scene.autoExposureValue();
    s.exposure = now * (up ? std::sqrt(2.0) : 1 / std::sqrt(2.0));
    s.mode = ViewMode::Radiosity;
  }
  refresh();
  return true;
}

void ViewerWindow::cycleColourMode() {
  ViewSettings& s = m_settings;
  if (s.mode == ViewMode::Radiosity)
    s.mode = ViewMode::FalseColour;
  else if (s.mode == ViewMode::FalseColour && m_run.formFactors)
    s.mode = ViewMode::FormFactorRow;
  else
    s.mode = ViewMode::Radiosity;
}

void ViewerWindow::select(int patch) {
  m_settings.picked = patch;
  if (patch >= 0 && m_run.formFactors) m_settings.mode = ViewMode::FormFactorRow;
  if (patch < 0 && m_settings.mode == ViewMode::FormFactorRow)
    m_settings.mode = ViewMode::Radiosity;
  refresh();
}

void ViewerWindow::onClick(vtkRenderer* renderer, int x, int y) {
  if (renderer == m_scene.renderer()) select(m_scene.pick(x, y));
  if (renderer == m_matrix.renderer()) {
    const int row = m_matrix.rowAt(x, y);
    if (row >= 0) select(row);
  }
}

}  // namespace radkit::viewer
