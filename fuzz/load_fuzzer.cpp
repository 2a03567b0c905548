// libFuzzer target for radkit's scene and mesh loaders, built once per format with
// RADKIT_FUZZ_FORMAT set to "json", "obj", "ply", "off" or "stl" (fuzz/CMakeLists.txt).
// The loaders read paths (extensions choose the reader, scenes name their meshes), so each
// input is written to a file in a private temp folder and loaded as radkit loads it:
//  - json: the input is scene.json, loaded with loadScene (parse, meshes, validation);
//  - obj:  the input is an OBJ scene; the text after the first line "#mtl" is its m.mtl;
//  - ply, off, stl: the input is m.EXT, the mesh of a fixed one-surface scene.json.
// InputError is the loaders' clean refusal and ends the case; anything else that escapes
// (another exception, a sanitizer report, a hang, memory beyond -rss_limit_mb) is a finding.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "fuzz/work_dir.h"
#include "geometry/scene_loader.h"

#ifndef RADKIT_FUZZ_FORMAT
#error "RADKIT_FUZZ_FORMAT must name the format this target loads"
#endif

namespace {

namespace fs = std::filesystem;

constexpr std::string_view kFormat = RADKIT_FUZZ_FORMAT;

void writeFile(const fs::path& path, const char* data, std::size_t size) {
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(data, static_cast<std::streamsize>(size));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* bytes, std::size_t size) {
  const fs::path& dir = radkit::fuzz::workDir(std::string(kFormat));
  const char* data = reinterpret_cast<const char*>(bytes);
  fs::path scene;
  if (kFormat == "json") {
    scene = dir / "scene.json";
    writeFile(scene, data, size);
  } else if (kFormat == "obj") {
    const std::string text(data, size);
    const std::string marker = "#mtl\n";
    std::size_t cut = text.find(marker);
    while (cut != std::string::npos && cut != 0 && text[cut - 1] != '\n')
      cut = text.find(marker, cut + 1);
    const std::size_t objSize = cut == std::string::npos ? size : cut;
    scene = dir / "scene.obj";
    writeFile(scene, data, objSize);
    const std::size_t mtlStart = cut == std::string::npos ? size : cut + marker.size();
    writeFile(dir / "m.mtl", data + mtlStart, size - mtlStart);
  } else {
    scene = dir / "scene.json";
    const std::string json =
        R"({"materials": {"lamp": {"reflectance": [0.5, 0.5, 0.5], "emission": [1, 1, 1]}},
      "surfaces": [{"name": "m", "material": "lamp", "mesh": "m.)" +
        std::string(kFormat) + R"("}]})";
    writeFile(scene, json.data(), json.size());
    writeFile(dir / ("m." + std::string(kFormat)), data, size);
  }
  try {
    radkit::LoadReport report;
    radkit::loadScene(scene.string(), &report);
  } catch (const radkit::InputError&) {
    // A clean refusal with a message: what bad input must give.
  }
  return 0;
}
