// A fuzz target's private folder for the files its loaders read by path.
#pragma once

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>

namespace radkit::fuzz {

/// temp/radkit-fuzz-NAME-PID, made on the first call and removed at exit. One per process:
/// a target has one name.
inline const std::filesystem::path& workDir(const std::string& name) {
  static const std::filesystem::path dir = [&] {
    std::filesystem::path d = std::filesystem::temp_directory_path() /
                              ("radkit-fuzz-" + name + "-" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(workDir(""), ec);
    });
    return d;
  }();
  return dir;
}

}  // namespace radkit::fuzz
