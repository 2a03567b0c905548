// libFuzzer target for the viewer's run-folder readers (fuzz_run_folder, fuzz/CMakeLists.txt):
// readRunFolder with everything it reads (report.json, radiosity.vtp, formfactors.bin or .mtx,
// links.png through stb_image, convergence.csv, surfaces.csv, sky.pfm), then what the views
// compute from the result without a window (exposure, colour range, smooth corners, the
// automatic camera, the binned matrix, a row of F, the sky's texels). Nothing is rendered.
//
// Input format: a run folder as one file. A line "%%file NAME" (at the start of the input or
// after a newline) starts the file NAME, which runs to the newline before the next such line
// or to the end of the input; text before the first marker is ignored, NAME must be one of the
// files above (others are skipped), and a file not named is absent. Binary files (.bin, .png)
// are carried the same way; fuzz/make_seeds.py writes seeds in this form from real runs.
//
// Each input is written into a private temp folder (the readers take paths). InputError is the
// readers' clean refusal and ends the case; anything else that escapes (another exception, a
// sanitizer report, a hang, memory beyond -rss_limit_mb) is a finding.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "fuzz/work_dir.h"
#include "render/camera.h"
#include "render/smooth_radiosity.h"
#include "util/errors.h"
#include "viewer/run_folder.h"
#include "viewer/view_settings.h"

namespace {

namespace fs = std::filesystem;

constexpr const char* kFiles[] = {"report.json",     "radiosity.vtp", "formfactors.bin",
                                  "formfactors.mtx", "links.png",     "convergence.csv",
                                  "surfaces.csv",    "sky.pfm"};

/// What the views compute from a folder that was read, short of rendering it.
void computeViews(const radkit::viewer::RunFolder& run) {
  using namespace radkit::viewer;
  const PatchData& p = run.patches;
  (void)autoExposure(p);
  std::vector<double> lum;
  for (const radkit::Vec3& b : p.radiosity)
    lum.push_back(channelValue(b, Channel::Luminance, true));
  (void)falseColourTop(p, lum);
  (void)radkit::smoothCornerValues(p.points, p.polygons, p.surface, p.radiosity);
  std::vector<radkit::Triangle> triangles;
  for (const std::vector<int>& poly : p.polygons)
    for (std::size_t k = 1; k + 1 < poly.size(); ++k)
      triangles.push_back({p.points[poly[0]], p.points[poly[k]], p.points[poly[k + 1]]});
  (void)radkit::automaticCamera(triangles);
  for (int i = 0; i < p.size(); ++i) (void)run.surfaceName(i);
  if (run.sky)  // the sky's texels, tone mapped as the radiosity view does
    for (const radkit::Vec3& l : run.sky->radiance) (void)trueColour(l * M_PI, 1.0);
  if (run.formFactors) {
    (void)downsampleMatrix(*run.formFactors, 64);
    (void)run.formFactors->row(p.size() - 1);
    (void)run.formFactors->maxValue();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* bytes, std::size_t size) {
  const fs::path& dir = radkit::fuzz::workDir("run-folder");
  for (const char* name : kFiles) fs::remove(dir / name);
  const std::string_view text(reinterpret_cast<const char*>(bytes), size);
  const std::string_view marker = "%%file ";
  std::size_t at = text.rfind(marker, 0) == 0 ? 0 : text.find("\n" + std::string(marker));
  if (at != std::string_view::npos && at > 0) ++at;  // past the newline
  while (at != std::string_view::npos) {
    const std::size_t nameStart = at + marker.size();
    const std::size_t nameEnd = std::min(text.find('\n', nameStart), text.size());
    const std::string name(text.substr(nameStart, nameEnd - nameStart));
    const std::size_t body = std::min(nameEnd + 1, text.size());
    const std::size_t next = text.find("\n" + std::string(marker), nameEnd);
    const std::size_t end = next == std::string_view::npos ? text.size() : next;
    for (const char* known : kFiles)
      if (name == known)
        std::ofstream(dir / name, std::ios::binary | std::ios::trunc)
            .write(text.data() + body, static_cast<std::streamsize>(std::max(end, body) - body));
    at = next == std::string_view::npos ? next : next + 1;
  }
  try {
    computeViews(radkit::viewer::readRunFolder(dir.string()));
  } catch (const radkit::InputError&) {
    // A clean refusal with a message: what a bad run folder must give.
  }
  return 0;
}
