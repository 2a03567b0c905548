// runViewer and pickPatchAt: check every input first, then open the display, then render.
#include "viewer/viewer.h"

#include <X11/Xlib.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <thread>

#include "util/errors.h"
#include "util/output_folder.h"
#include "util/setting_names.h"
#include "viewer/viewer_window.h"

namespace radkit::viewer {

namespace {

/// The X connection the render window uses. Opened here rather than by VTK, which aborts the
/// process when X refuses; held open for the window's lifetime, because Xvfb resets (and
/// briefly refuses everyone) each time its last client leaves.
class DisplayConnection {
 public:
  DisplayConnection() {
    const char* name = std::getenv("DISPLAY");
    for (int attempt = 0; attempt < 20 && name && *name && !m_display; ++attempt) {
      if (attempt > 0)
        std::this_thread::sleep_for(std::chrono::milliseconds(50));  // a reset passes
      m_display = XOpenDisplay(nullptr);
    }
    if (!m_display)
      throw InputError(
          std::string("no X display") +
          (name && *name ? " (cannot open DISPLAY=" + std::string(name) + ")" : "") +
          ": the viewer renders through X; on a server run it as `xvfb-run -a radkit view ...`");
  }
  ~DisplayConnection() { XCloseDisplay(m_display); }
  DisplayConnection(const DisplayConnection&) = delete;
  DisplayConnection& operator=(const DisplayConnection&) = delete;
  void* id() const { return m_display; }

 private:
  Display* m_display = nullptr;
};

ViewSettings settingsFor(const ViewerOptions& o, const ModeChoice& mode) {
  ViewSettings s;
  s.mode = mode.mode;
  s.picked = mode.row;
  s.channel = parseChannel(o.channel);
  s.smooth = o.smooth;
  s.photometric = o.photometric;
  s.exposure = o.exposure;
  if (s.photometric && s.channel != Channel::Luminance)
    throw InputError(setting("photometric") + " shows luminance in cd/m²; drop " +
                     setting("channel") + " " + o.channel + " or use " + setting("channel") +
                     " luminance");
  if (!(o.exposure >= 0))
    throw InputError(setting("exposure") + " must be >= 0 (0 picks one automatically)");
  if (o.width < 16 || o.height < 16 || o.width > 8192 || o.height > 8192)
    throw InputError(setting("size") + " " + std::to_string(o.width) + "x" +
                     std::to_string(o.height) + ": width and height must be 16..8192 pixels");
  return s;
}

/// What a screenshot of `mode` needs from the run folder.
void requireInputs(const RunFolder& run, const ModeChoice& mode) {
  const bool linksOnly = mode.mode == ViewMode::Matrix && !run.linksImage.empty();
  if ((mode.mode == ViewMode::Matrix || mode.mode == ViewMode::FormFactorRow) && !run.formFactors &&
      !linksOnly)
    throw InputError(run.path + ": " + run.formFactorsMissing);
  if (mode.mode == ViewMode::FormFactorRow && mode.row >= run.patches.size())
    throw InputError(setting("mode") + " formfactors-row:" + std::to_string(mode.row) +
                     ": no such patch; ids are 0.." + std::to_string(run.patches.size() - 1) +
                     " (the id column of patches.csv)");
  if (mode.mode == ViewMode::Convergence && run.convergence.empty())
    throw InputError(
        run.path + ": " +
        (run.convergenceMissing.empty() ? "convergence.csv has no rows" : run.convergenceMissing));
}

}  // namespace

void parseSize(const std::string& text, int& width, int& height, int minSide, int maxSide) {
  const auto x = text.find_first_of("xX");
  auto number = [&](const std::string& part) {
    if (part.empty() || part.size() > 5 ||
        part.find_first_not_of("0123456789") != std::string::npos)
      return -1;
    return std::stoi(part);
  };
  const int w = x == std::string::npos ? -1 : number(text.substr(0, x));
  const int h = x == std::string::npos ? -1 : number(text.substr(x + 1));
  if (w < minSide || h < minSide || w > maxSide || h > maxSide)
    throw InputError(setting("size") + " " + text + ": expected WIDTHxHEIGHT in pixels, each " +
                     std::to_string(minSide) + ".." + std::to_string(maxSide) + " (e.g. 1024x768)");
  width = w;
  height = h;
}

int runViewer(const ViewerOptions& o) {
  const ModeChoice mode = parseMode(o.mode);
  const ViewSettings settings = settingsFor(o, mode);
  if (!o.screenshot.empty()) {
    const auto folder = std::filesystem::path(o.screenshot).parent_path();
    if (!folder.empty() && !std::filesystem::is_directory(folder))
      throw InputError(setting("screenshot") + " " + o.screenshot + ": folder " + folder.string() +
                       " does not exist; create it first");
  }
  RunFolder run = readRunFolder(o.runFolder);
  if (o.camera) run.report.camera = o.camera;
  requireInputs(run, mode);
  const DisplayConnection display;
  ViewerWindow window(run, settings, display.id(), o.width, o.height, !o.screenshot.empty());
  if (o.screenshot.empty()) {
    window.interact();
    return 0;
  }
  window.layoutSingle(mode.mode);
  window.writePng(o.screenshot);
  // A screenshot saved into a run folder is radkit's own: the next run may replace it.
  registerOutputFile(o.screenshot);
  return 0;
}

int pickPatchAt(const std::string& runFolder, int width, int height, int x, int y) {
  if (x < 0 || y < 0 || x >= width || y >= height) return -1;
  const RunFolder run = readRunFolder(runFolder);
  const DisplayConnection display;
  ViewSettings settings;
  ViewerWindow window(run, settings, display.id(), width, height, true);
  window.layoutSingle(ViewMode::Radiosity);
  window.refresh();
  // Pixel centres; VTK's display y runs upwards.
  return window.pickScene(x + 0.5, height - y - 0.5);
}

}  // namespace radkit::viewer
