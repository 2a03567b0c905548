// The radiosity viewer: `radkit view RUN_DIR` (an interactive window) and its headless
// screenshots. This header is VTK-free: callers (apps/, tests) never see a VTK type.
#pragma once

#include <optional>
#include <string>

#include "geometry/scene.h"
#include "util/errors.h"

namespace radkit::viewer {

struct ViewerOptions {
  std::string runFolder;
  std::string screenshot;  ///< PNG path; empty: open an interactive window
  /// radiosity | false-colour | formfactors-row:ID | matrix | convergence
  std::string mode = "radiosity";
  int width = 1024, height = 768;     ///< window or screenshot size in pixels
  bool smooth = false;                ///< vertex-interpolated shading instead of flat patches
  std::string channel = "luminance";  ///< r | g | b | luminance, for false colour
  /// False colour of luminance in cd/m² (683 lm/W, Rec. 709 weights, L = B/π) instead of W/m².
  bool photometric = false;
  double exposure = 0;           ///< multiplier on L = B/π for true colour; 0: automatic
  std::optional<Camera> camera;  ///< replaces the run's camera (radkit view --camera)
};

/// \brief Opens the viewer on a run folder, or with `screenshot` set renders the chosen mode
/// into a PNG of exactly width × height (written as FILE.tmp, then renamed) and returns.
/// Needs an X display (`xvfb-run -a` on a server).
/// \return 0 on success.
/// \throws radkit::InputError for a missing or malformed run folder, a bad mode, channel,
/// size or patch id, or no display; nothing is written then.
int runViewer(const ViewerOptions& options);

/// \brief Patch id under pixel (x, y) (origin top-left) of the radiosity view of `runFolder`
/// at width × height pixels, -1 for the background (VTK cell picker, the scene's camera).
int pickPatchAt(const std::string& runFolder, int width, int height, int x, int y);

/// \brief Parses "WxH", each side in [minSide, maxSide]. \throws radkit::InputError naming the fix.
void parseSize(const std::string& text, int& width, int& height, int minSide = 16,
               int maxSide = 8192);

}  // namespace radkit::viewer
