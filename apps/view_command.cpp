// radkit view: the VTK viewer on a run folder, interactive or as a headless screenshot.
#include <filesystem>
#include <memory>

#include "apps/common.h"
#include "render/camera.h"
#include "util/errors.h"
#include "viewer/viewer.h"

namespace radkit::app {

namespace {

struct ViewCommand {
  viewer::ViewerOptions options;
  std::string size;
  std::string camera;
  std::string out;  ///< where a scene's run goes (default out/<scene name>)
  bool screenshotGiven = false;
};

void runView(ViewCommand& cmd) {
  viewer::ViewerOptions& o = cmd.options;
  if (o.runFolder.empty())
    throw InputError(
        "RUN_DIR is empty. Fix: give a folder written by `radkit run --out DIR`, or a scene file");
  // An empty --screenshot would open the interactive window, which waits for a user.
  if (cmd.screenshotGiven || !o.screenshot.empty()) checkOutputFile("--screenshot", o.screenshot);
  // A scene file instead of a run folder: run the main job first, then view its folder.
  if (!cmd.camera.empty()) o.camera = parseCamera("--camera", cmd.camera);
  if (std::filesystem::is_regular_file(o.runFolder))
    o.runFolder = runDefaultJob(o.runFolder, cmd.out);
  if (!cmd.size.empty())
    viewer::parseSize(cmd.size, o.width, o.height);
  else if (o.screenshot.empty()) {
    o.width = 1440;  // room for the three views side by side
    o.height = 860;
  }
  const int code = viewer::runViewer(o);
  if (code != 0) throw CLI::RuntimeError(code);
}

}  // namespace

void addViewCommand(CLI::App& app) {
  auto cmd = std::make_shared<ViewCommand>();
  viewer::ViewerOptions& o = cmd->options;
  CLI::App* sub = app.add_subcommand(
      "view",
      "Open the VTK viewer on a run folder (radiosity, form-factor matrix, convergence), or save a "
      "screenshot; needs X (on a server: xvfb-run -a radkit view ...)");
  sub->add_option(
         "run_dir", o.runFolder,
         "Run folder written by `radkit run --out DIR`, or a scene file: it is run first (with "
         "`radkit run`'s defaults) and its folder viewed")
      ->required();
  sub->add_option("--out", cmd->out,
                  "With a scene: the run folder to write (default out/<scene name>)");
  sub->add_option("--screenshot", o.screenshot,
                  "Write this PNG of --mode and exit instead of opening a window");
  sub->add_option(
         "--mode", o.mode,
         "radiosity | false-colour | formfactors-row:ID | matrix | convergence (ID: a patch id of "
         "patches.csv)")
      ->capture_default_str();
  sub->add_option("--size", cmd->size,
                  "Image or window size WIDTHxHEIGHT (default 1024x768 for screenshots, 1440x860 "
                  "for the window)");
  addCameraOption(*sub, cmd->camera);
  sub->add_flag("--smooth", o.smooth,
                "Interpolate radiosity between patches instead of flat patches");
  sub->add_option("--channel", o.channel, "False-colour quantity: r | g | b | luminance")
      ->capture_default_str();
  sub->add_flag(
      "--photometric", o.photometric,
      "False colour of luminance in cd/m² (683 lm/W, Rec. 709 weights, L = B/pi) instead of W/m²");
  sub->add_option("--exposure", o.exposure,
                  "Multiplier on radiance L = B/pi for true colour (0: automatic)")
      ->check(FiniteNonNegative)
      ->capture_default_str();
  CLI::Option* screenshot = sub->get_option("--screenshot");
  sub->callback([cmd, screenshot] {
    cmd->screenshotGiven = screenshot->count() > 0;
    runView(*cmd);
  });
}

}  // namespace radkit::app
