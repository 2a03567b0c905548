// Helpers shared by radkit's tests: temporary folders, running the radkit binary, data paths.
#pragma once

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace radkit::test {

inline std::string dataPath(const std::string& name) {
  return std::string(RADKIT_DATA_DIR) + "/" + name;
}

/// A fresh folder under the system temp dir, removed with the object.
class TempDir {
 public:
  TempDir() {
    std::random_device rd;
    m_path = std::filesystem::temp_directory_path() /
             ("radkit-test-" + std::to_string(rd()) + std::to_string(rd()));
    std::filesystem::create_directories(m_path);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(m_path, ec);
  }
  std::string file(const std::string& name, const std::string& text) const {
    std::ofstream(m_path / name, std::ios::binary) << text;
    return (m_path / name).string();
  }
  std::string path(const std::string& name) const { return (m_path / name).string(); }

 private:
  std::filesystem::path m_path;
};

/// The smallest scene that loads a mesh: `name` in `dir`, one surface "m" of a lamp material
/// (ρ 0.5, emission 1) from `mesh` (a file beside it), with `transform` (JSON object text) when
/// given. Returns its path.
inline std::string lampMeshScene(const TempDir& dir, const std::string& mesh,
                                 const std::string& transform = "",
                                 const std::string& name = "s.json") {
  return dir.file(
      name, R"({"materials": {"lamp": {"reflectance": [0.5,0.5,0.5], "emission": [1,1,1]}},
      "surfaces": [{"name": "m", "material": "lamp", "mesh": ")" +
                mesh + "\"" + (transform.empty() ? "" : ", \"transform\": " + transform) + "}]}");
}

struct RunResult {
  int exitCode = -1;
  std::string output;  ///< stdout and stderr together
};

/// Runs the radkit binary with `args` (shell words), capturing output and exit code. With a
/// time limit, a run still going after `seconds` is killed and exits 124 (timeout(1)), so a
/// hang fails its test instead of stalling the suite.
inline RunResult runRadkit(const std::string& args, int seconds = 0) {
  RunResult r;
  const std::string limit = seconds > 0 ? "timeout -k 5 " + std::to_string(seconds) + " " : "";
  std::string cmd = limit + "'" + RADKIT_BINARY + "' " + args + " 2>&1";
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return r;
  char buf[4096];
  std::size_t n;
  while ((n = fread(buf, 1, sizeof buf, pipe)) > 0) r.output.append(buf, n);
  int status = pclose(pipe);
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

inline RunResult runRadkitWithin(int seconds, const std::string& args) {
  return runRadkit(args, seconds);
}

/// Rows of a CSV file without quoted fields, each a map from header name to text.
inline std::vector<std::map<std::string, std::string>> readCsv(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  std::stringstream h(line);
  for (std::string f; std::getline(h, f, ',');) header.push_back(f);
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    std::stringstream r(line);
    std::map<std::string, std::string> row;
    std::size_t k = 0;
    for (std::string f; std::getline(r, f, ',') && k < header.size(); ++k) row[header[k]] = f;
    rows.push_back(row);
  }
  return rows;
}

}  // namespace radkit::test
