// Helpers shared by the mesh-file structure checks (mesh_structure.cpp, ply_structure.cpp):
// lines and tokens of a file held in memory, and the messages' common parts. Internal to
// geometry/.
#pragma once

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "util/errors.h"

namespace radkit::structure {

inline std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

inline std::vector<std::string> tokens(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> out;
  for (std::string t; in >> t;) out.push_back(t);
  return out;
}

inline std::string uncommented(const std::string& line) {
  // A '#' starts a comment only where a token starts: MSVC's "1.#QNAN" stays one token, which
  // the number check refuses, instead of reading as "1." and a comment.
  for (std::size_t at = line.find('#'); at != std::string::npos; at = line.find('#', at + 1))
    if (at == 0 || line[at - 1] == ' ' || line[at - 1] == '\t') return line.substr(0, at);
  return line;
}

/// Whole-token decimal integer; false on anything else, including overflow of long long.
inline bool parseInteger(const std::string& t, long long& v) {
  if (t.empty()) return false;
  char* end = nullptr;
  errno = 0;
  v = std::strtoll(t.c_str(), &end, 10);
  return end == t.c_str() + t.size() && errno == 0;
}

/// Lines of a file held in memory, numbered from 1, '\r' stripped.
class Lines {
 public:
  explicit Lines(const std::string& text) : m_text(text) {}
  bool next(std::string& line) {
    if (m_pos >= m_text.size()) return false;
    std::size_t end = m_text.find('\n', m_pos);
    if (end == std::string::npos) end = m_text.size();
    line = m_text.substr(m_pos, end - m_pos);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    m_pos = end + 1;
    ++m_number;
    return true;
  }
  /// The next line with tokens outside '#' comments.
  bool nextTokens(std::vector<std::string>& t) {
    for (std::string line; next(line);) {
      t = tokens(uncommented(line));
      if (!t.empty()) return true;
    }
    return false;
  }
  long number() const { return m_number; }
  std::size_t pos() const { return std::min(m_pos, m_text.size()); }

 private:
  const std::string& m_text;
  std::size_t m_pos = 0;
  long m_number = 0;
};

class Fail {
 public:
  explicit Fail(std::string path) : m_path(std::move(path)) {}
  [[noreturn]] void operator()(const std::string& what) const {
    throw InputError(m_path + ": " + what);
  }
  /// line <= 0: a binary body, where lines mean nothing.
  [[noreturn]] void at(long line, const std::string& what) const {
    (*this)(line > 0 ? "line " + std::to_string(line) + ": " + what : what);
  }

 private:
  std::string m_path;
};

inline const char* const kTruncated =
    " Fix: restore the missing data (the file looks truncated) or correct the count.";

/// A count read from a header: a whole number in [0, INT_MAX] (what the readers index with).
inline long long headerCount(const Fail& fail, long line, const std::string& token,
                             const std::string& what) {
  long long v = 0;
  if (!parseInteger(token, v) || v < 0 || v > INT_MAX)
    fail.at(line, "'" + token + "' is not a valid " + what +
                      " count. Fix: write a whole number "
                      "from 0 to " +
                      std::to_string(INT_MAX) + ".");
  return v;
}

/// Refuses a count that the file's bytes cannot hold at `minBytes` per item.
inline void requireRoom(const Fail& fail, long line, long long count, double minBytes,
                        std::size_t bytes, const std::string& what) {
  if (count * minBytes > double(bytes))
    fail.at(line, "the header declares " + std::to_string(count) + " " + what + ", but the " +
                      std::to_string(bytes) + " bytes that follow can hold at most " +
                      std::to_string((long long)(double(bytes) / minBytes)) + "." + kTruncated);
}

/// One face's vertex index against the vertex count.
inline void checkIndex(const Fail& fail, long line, long long face, long long index,
                       long long vertices) {
  if (index < 0 || index >= vertices)
    fail.at(line, "face " + std::to_string(face) + " names vertex " + std::to_string(index) +
                      ", but the file has " + std::to_string(vertices) + " vertices (0 to " +
                      std::to_string(vertices - 1) + "). Fix: correct the index.");
}

inline void checkFaceSize(const Fail& fail, long line, long long face, long long n) {
  if (n < 3)
    fail.at(line, "face " + std::to_string(face) + " has " + std::to_string(n) +
                      " vertices. Fix: a face needs at least 3 vertex indices.");
}

/// Bytes of a PLY scalar type ("uchar", "float32", ...); 0 for a name PLY does not have.
int plyTypeSize(const std::string& type);

/// The PLY check (ply_structure.cpp): returns the face count the header declares.
/// `strips`: when given, the vertex indices of a "tristrips" element, each strip ended by -1.
long long checkPly(const Fail& fail, const std::string& text,
                   std::vector<long long>* strips = nullptr);

}  // namespace radkit::structure
