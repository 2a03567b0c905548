#include "geometry/text_numbers.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "geometry/mesh_structure.h"
#include "geometry/structure_text.h"
#include "util/errors.h"

namespace radkit {

namespace {

namespace fs = std::filesystem;

std::vector<std::string> tokens(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> out;
  for (std::string t; in >> t;) out.push_back(t);
  return out;
}

/// True when the whole token is a finite decimal number (what the readers can represent).
bool isFiniteDecimal(const std::string& token) {
  if (token.find_first_of("xX") != std::string::npos) return false;  // hex floats read as 0
  const char* begin = token.c_str();
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(begin, &end);
  if (end != begin + token.size()) return false;
  if (errno == ERANGE && std::fabs(v) > 1.0) return false;  // overflow; underflow to 0 is fine
  return std::isfinite(v);
}

class Checker {
 public:
  explicit Checker(std::string path) : m_path(std::move(path)) {}

  /// Checks tokens [first, end) of a line.
  void numbers(const std::vector<std::string>& t, std::size_t first, long line) const {
    for (std::size_t k = first; k < t.size(); ++k)
      if (!isFiniteDecimal(t[k]))
        throw InputError(m_path + ": line " + std::to_string(line) + ": '" + t[k] +
                         "' is not a finite number. Fix: write every number as a finite "
                         "decimal (a '.' as the decimal point, no NaN or infinity).");
  }

 private:
  std::string m_path;
};

using structure::uncommented;

void checkObjLike(std::istream& in, const Checker& check, const std::vector<std::string>& keys,
                  std::vector<std::vector<std::string>>* mtllibs) {
  long n = 0;
  for (std::string line; std::getline(in, line);) {
    ++n;
    const auto t = tokens(uncommented(line));
    if (t.empty()) continue;
    if (mtllibs && t[0] == "mtllib") mtllibs->push_back(t);
    if (std::find(keys.begin(), keys.end(), t[0]) != keys.end()) check.numbers(t, 1, n);
  }
}

void checkOff(std::istream& in, const Checker& check) {
  long n = 0;
  bool header = true;
  for (std::string line; std::getline(in, line);) {
    ++n;
    auto t = tokens(uncommented(line));
    if (t.empty()) continue;
    std::size_t first = 0;
    if (header) {  // OFF, COFF, NOFF, STOFF, 4OFF, ... optionally followed by the counts
      header = false;
      const std::string key = structure::lower(t[0]);
      if (key.size() >= 3 && key.compare(key.size() - 3, 3, "off") == 0) {
        if (t.size() > 1 && structure::lower(t[1]) == "binary") return;
        first = 1;
      }
    }
    check.numbers(t, first, n);
  }
}

void checkPly(std::istream& in, const Checker& check) {
  long n = 0;
  bool ascii = false;
  std::string line;
  while (std::getline(in, line)) {
    ++n;
    const auto t = tokens(line);
    if (t.size() >= 2 && t[0] == "format") ascii = t[1] == "ascii";
    if (!t.empty() && t[0] == "end_header") break;
  }
  if (!ascii) return;
  while (std::getline(in, line)) check.numbers(tokens(line), 0, ++n);
}

/// Binary STL: an 80-byte header, a triangle count, 50 bytes per triangle.
bool isBinaryStl(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char header[84];
  if (!in.read(header, sizeof header)) return false;
  std::uint32_t count = 0;
  for (int k = 3; k >= 0; --k) count = count << 8 | static_cast<unsigned char>(header[80 + k]);
  return fs::file_size(path) == 84 + 50 * static_cast<std::uintmax_t>(count);
}

void checkStl(std::istream& in, const Checker& check) {
  long n = 0;
  for (std::string line; std::getline(in, line);) {
    ++n;
    const auto t = tokens(line);
    if (t.empty()) continue;
    if (t[0] == "vertex")
      check.numbers(t, 1, n);
    else if (t[0] == "facet" && t.size() > 1 && t[1] == "normal")
      check.numbers(t, 2, n);
  }
}

}  // namespace

void checkTextMeshNumbers(const std::string& path) {
  std::string ext = structure::lower(fs::path(path).extension().string());
  if (ext == ".stl" && isBinaryStl(path)) return;
  std::ifstream in(path, std::ios::binary);
  if (!in) return;  // a missing or unreadable file is the reader's to report
  const Checker check(path);
  if (ext == ".obj") {
    std::vector<std::vector<std::string>> mtllibs;
    checkObjLike(in, check, {"v"}, &mtllibs);
    for (const auto& line : mtllibs)
      for (const fs::path mtl : mtllibFiles(fs::path(path).parent_path().string(), line)) {
        std::error_code ec;
        if (!fs::is_regular_file(mtl, ec)) continue;  // the structure check names a pipe or folder
        std::ifstream mtlIn(mtl, std::ios::binary);
        if (mtlIn) checkObjLike(mtlIn, Checker(mtl.string()), {"Kd", "Ke"}, nullptr);
      }
  } else if (ext == ".off") {
    checkOff(in, check);
  } else if (ext == ".ply") {
    checkPly(in, check);
  } else if (ext == ".stl") {
    checkStl(in, check);
  }
}

}  // namespace radkit
