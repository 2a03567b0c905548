#include "geometry/mesh_structure.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "geometry/scene_loader.h"

namespace radkit {

namespace {

namespace fs = std::filesystem;

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

std::vector<std::string> tokens(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> out;
  for (std::string t; in >> t;) out.push_back(t);
  return out;
}

std::string uncommented(const std::string& line) { return line.substr(0, line.find('#')); }

std::string readAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// Whole-token decimal integer; false on anything else, including overflow of long long.
bool parseInteger(const std::string& t, long long& v) {
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
  [[noreturn]] void operator()(const std::string& what) const { throw InputError(m_path + ": " + what); }
  /// line <= 0: a binary body, where lines mean nothing.
  [[noreturn]] void at(long line, const std::string& what) const {
    (*this)(line > 0 ? "line " + std::to_string(line) + ": " + what : what);
  }

 private:
  std::string m_path;
};

const char* kTruncated = " Fix: restore the missing data (the file looks truncated) or correct the count.";

/// A count read from a header: a whole number in [0, INT_MAX] (what the readers index with).
long long headerCount(const Fail& fail, long line, const std::string& token, const std::string& what) {
  long long v = 0;
  if (!parseInteger(token, v) || v < 0 || v > INT_MAX)
    fail.at(line, "'" + token + "' is not a valid " + what + " count. Fix: write a whole number "
                  "from 0 to " + std::to_string(INT_MAX) + ".");
  return v;
}

/// Refuses a count that the file's bytes cannot hold at `minBytes` per item.
void requireRoom(const Fail& fail, long line, long long count, double minBytes, std::size_t bytes,
                 const std::string& what) {
  if (count * minBytes > double(bytes))
    fail.at(line, "the header declares " + std::to_string(count) + " " + what + ", but the " +
                      std::to_string(bytes) + " bytes that follow can hold at most " +
                      std::to_string((long long)(double(bytes) / minBytes)) + "." + kTruncated);
}

/// One face's vertex index against the vertex count.
void checkIndex(const Fail& fail, long line, long long face, long long index, long long vertices) {
  if (index < 0 || index >= vertices)
    fail.at(line, "face " + std::to_string(face) + " names vertex " + std::to_string(index) +
                      ", but the file has " + std::to_string(vertices) + " vertices (0 to " +
                      std::to_string(vertices - 1) + "). Fix: correct the index.");
}

void checkFaceSize(const Fail& fail, long line, long long face, long long n) {
  if (n < 3)
    fail.at(line, "face " + std::to_string(face) + " has " + std::to_string(n) +
                      " vertices. Fix: a face needs at least 3 vertex indices.");
}

// ---------------------------------------------------------------------------------------- OFF

long long checkBinaryOff(const Fail& fail, const std::string& text, const Lines& lines) {
  const std::size_t at = lines.pos();
  if (text.size() < at + 12) fail("binary OFF header ends before its counts." + std::string(kTruncated));
  const std::size_t body = text.size() - at - 12;
  for (bool big : {true, false}) {  // the counts' byte order is not recorded in the file
    long long c[2];
    for (int k = 0; k < 2; ++k) {
      std::uint32_t v = 0;
      for (int b = 0; b < 4; ++b)
        v |= std::uint32_t(static_cast<unsigned char>(text[at + 4 * k + b])) << (big ? 24 - 8 * b : 8 * b);
      c[k] = v;
    }
    if (c[0] <= INT_MAX && c[1] <= INT_MAX && c[0] * 12.0 + c[1] * 16.0 <= double(body)) return -1;
  }
  fail("binary OFF declares more vertices and faces than its " + std::to_string(text.size()) +
       " bytes can hold." + kTruncated);
}

long long checkOff(const Fail& fail, const std::string& text) {
  Lines lines(text);
  std::vector<std::string> t;
  if (!lines.nextTokens(t)) fail("the file is empty. Fix: an OFF file starts with 'OFF' and its counts.");
  std::size_t first = 0;
  const std::string key = lower(t[0]);
  if (key.size() >= 3 && key.compare(key.size() - 3, 3, "off") == 0) {
    if (t.size() > 1 && lower(t[1]) == "binary") return checkBinaryOff(fail, text, lines);
    first = 1;
    if (t.size() == 1) {
      if (!lines.nextTokens(t))
        fail("the header has no vertex and face counts. Fix: write 'vertices faces edges' after 'OFF'.");
      first = 0;
    }
  }
  const long header = lines.number();
  if (t.size() < first + 2)
    fail.at(header, "the header needs the vertex and face counts. Fix: write 'vertices faces edges'.");
  const long long nv = headerCount(fail, header, t[first], "vertex");
  const long long nf = headerCount(fail, header, t[first + 1], "face");
  // At least "0 0 0\n" per vertex and "n\n" per face (a short face is named below); the last
  // line may lack its '\n'.
  const std::size_t rest = text.size() - lines.pos() + 1;
  requireRoom(fail, header, nv, 6, rest, "vertices");
  requireRoom(fail, header, nf, 2, rest - std::size_t(nv) * 6, "faces");
  for (long long v = 0; v < nv; ++v) {
    if (!lines.nextTokens(t))
      fail("the file ends after " + std::to_string(v) + " of the " + std::to_string(nv) + " vertices "
           "its header declares." + kTruncated);
    if (t.size() < 3)
      fail.at(lines.number(), "vertex " + std::to_string(v) + " has " + std::to_string(t.size()) +
                                  " coordinates. Fix: write x y z.");
  }
  for (long long f = 0; f < nf; ++f) {
    if (!lines.nextTokens(t))
      fail("the file ends after " + std::to_string(f) + " of the " + std::to_string(nf) + " faces "
           "its header declares." + kTruncated);
    const long line = lines.number();
    long long n = 0;
    if (!parseInteger(t[0], n)) fail.at(line, "'" + t[0] + "' is not a face's vertex count.");
    checkFaceSize(fail, line, f, n);
    if (n > (long long)t.size() - 1)
      fail.at(line, "face " + std::to_string(f) + " declares " + std::to_string(n) + " vertices but lists " +
                        std::to_string(t.size() - 1) + ". Fix: list every vertex index.");
    for (long long k = 1; k <= n; ++k) {
      long long index = 0;
      if (!parseInteger(t[k], index)) fail.at(line, "'" + t[k] + "' is not a vertex index.");
      checkIndex(fail, line, f, index, nv);
    }
  }
  return nf;
}

// ---------------------------------------------------------------------------------------- PLY

struct PlyProperty {
  std::string name;
  int size = 0;       ///< bytes of the value (of each item for a list)
  int countSize = 0;  ///< bytes of a list's count; 0 for a scalar
  bool isFloat = false, isSigned = false;
};

struct PlyElement {
  std::string name;
  long long count = 0;
  long line = 0;
  std::vector<PlyProperty> properties;
};

int plyTypeSize(const std::string& type) {
  static const std::pair<const char*, int> types[] = {
      {"char", 1},   {"uchar", 1},  {"int8", 1},  {"uint8", 1},   {"short", 2},   {"ushort", 2},
      {"int16", 2},  {"uint16", 2}, {"int", 4},   {"uint", 4},    {"int32", 4},   {"uint32", 4},
      {"float", 4},  {"float32", 4}, {"double", 8}, {"float64", 8}};
  for (const auto& t : types)
    if (type == t.first) return t.second;
  return 0;
}

/// Reads the values of a binary PLY body, checking that each lies inside the file.
class BinaryCursor {
 public:
  BinaryCursor(const std::string& text, std::size_t pos, bool big) : m_text(text), m_pos(pos), m_big(big) {}
  bool has(double bytes) const { return double(m_text.size() - m_pos) >= bytes; }
  void skip(std::size_t bytes) { m_pos += bytes; }
  /// The unsigned integer value of `size` (<= 4) bytes.
  long long integer(int size) {
    std::uint64_t v = 0;
    for (int b = 0; b < size; ++b) {
      const std::uint64_t byte = static_cast<unsigned char>(m_text[m_pos + b]);
      v |= byte << (m_big ? 8 * (size - 1 - b) : 8 * b);
    }
    m_pos += size;
    return (long long)v;
  }

 private:
  const std::string& m_text;
  std::size_t m_pos;
  bool m_big;
};

/// ASCII PLY body tokens with their line numbers.
class TokenCursor {
 public:
  TokenCursor(const std::string& text, std::size_t pos, long line) : m_text(text), m_pos(pos), m_line(line) {}
  bool next(std::string& token) {
    while (m_pos < m_text.size() && std::isspace(static_cast<unsigned char>(m_text[m_pos])))
      if (m_text[m_pos++] == '\n') ++m_line;
    if (m_pos >= m_text.size()) return false;
    const std::size_t start = m_pos;
    while (m_pos < m_text.size() && !std::isspace(static_cast<unsigned char>(m_text[m_pos]))) ++m_pos;
    token = m_text.substr(start, m_pos - start);
    return true;
  }
  long line() const { return m_line; }

 private:
  const std::string& m_text;
  std::size_t m_pos;
  long m_line;
};

bool isFaceIndexList(const PlyElement& e, const PlyProperty& p) {
  return e.name == "face" && p.countSize > 0 && (p.name == "vertex_indices" || p.name == "vertex_index");
}

void checkPlyBody(const Fail& fail, const std::string& text, std::size_t pos, long line,
                  const std::string& format, const std::vector<PlyElement>& elements, long long vertices) {
  const bool ascii = format == "ascii";
  TokenCursor tokens(text, pos, line);
  BinaryCursor bytes(text, pos, format == "binary_big_endian");
  std::string token;
  for (const PlyElement& e : elements)
    for (long long row = 0; row < e.count; ++row) {
      auto truncated = [&]() {
        fail("the file ends inside element '" + e.name + "' row " + std::to_string(row) + " of the " +
             std::to_string(e.count) + " its header declares (line " + std::to_string(e.line) + ")." +
             kTruncated);
      };
      for (const PlyProperty& p : e.properties) {
        const bool indices = isFaceIndexList(e, p);
        long long n = 1;
        if (p.countSize > 0) {
          if (ascii) {
            if (!tokens.next(token)) truncated();
            if (!parseInteger(token, n) || n < 0)
              fail.at(tokens.line(), "'" + token + "' is not a list length in element '" + e.name + "' row " +
                                         std::to_string(row) + ". Fix: write a whole number >= 0.");
          } else {
            if (!bytes.has(p.countSize)) truncated();
            n = bytes.integer(p.countSize);
          }
          if (indices) checkFaceSize(fail, ascii ? tokens.line() : 0, row, n);
        }
        if (!ascii) {
          if (!bytes.has(double(n) * p.size)) truncated();
          if (!indices) {
            bytes.skip(std::size_t(n) * p.size);
            continue;
          }
        }
        for (long long k = 0; k < n; ++k) {
          long long index = 0;
          if (ascii) {
            if (!tokens.next(token)) truncated();
            if (indices && !parseInteger(token, index))
              fail.at(tokens.line(), "'" + token + "' is not a vertex index.");
          } else {
            index = bytes.integer(p.size);
            if (p.isSigned && index >= (1LL << (8 * p.size - 1))) index -= 1LL << (8 * p.size);
          }
          if (indices) checkIndex(fail, ascii ? tokens.line() : 0, row, index, vertices);
        }
      }
    }
}

long long checkPly(const Fail& fail, const std::string& text) {
  Lines lines(text);
  std::string line;
  if (!lines.next(line) || line != "ply") fail.at(1, "a PLY file starts with the line 'ply'.");
  std::string format;
  std::vector<PlyElement> elements;
  bool ended = false;
  while (!ended && lines.next(line)) {
    const auto t = tokens(line);
    const long n = lines.number();
    if (t.empty() || t[0] == "comment" || t[0] == "obj_info") continue;
    if (t[0] == "end_header") {
      ended = true;
    } else if (t[0] == "format") {
      if (t.size() < 2 || (t[1] != "ascii" && t[1] != "binary_little_endian" && t[1] != "binary_big_endian"))
        fail.at(n, "unknown format. Fix: 'format ascii 1.0', 'format binary_little_endian 1.0' or "
                   "'format binary_big_endian 1.0'.");
      format = t[1];
    } else if (t[0] == "element") {
      if (t.size() != 3) fail.at(n, "an element line is 'element NAME COUNT'.");
      elements.push_back({t[1], headerCount(fail, n, t[2], "element"), n, {}});
    } else if (t[0] == "property") {
      if (elements.empty()) fail.at(n, "a property comes before any element. Fix: declare the element first.");
      PlyProperty p;
      const bool list = t.size() == 5 && t[1] == "list";
      if (!list && t.size() != 3)
        fail.at(n, "a property line is 'property TYPE NAME' or 'property list COUNT_TYPE TYPE NAME'.");
      p.name = t.back();
      p.size = plyTypeSize(t[t.size() - 2]);
      p.isFloat = t[t.size() - 2].find_first_of("fd") == 0;
      p.isSigned = t[t.size() - 2][0] != 'u';
      p.countSize = list ? plyTypeSize(t[2]) : 0;
      if (p.size == 0 || (list && (p.countSize == 0 || t[2][0] == 'f' || t[2][0] == 'd')))
        fail.at(n, "unknown property type. Fix: use char, uchar, short, ushort, int, uint, float or double "
                   "(an integer type for a list's count).");
      if (isFaceIndexList(elements.back(), p) && p.isFloat)
        fail.at(n, "vertex indices must have an integer type.");
      elements.back().properties.push_back(p);
    } else {
      fail.at(n, "unknown header line '" + t[0] + "'. Fix: the header holds format, element, property "
                 "and comment lines and ends with 'end_header'.");
    }
  }
  if (!ended) fail("the header has no 'end_header' line." + std::string(kTruncated));
  if (format.empty()) fail("the header has no 'format' line. Fix: add 'format ascii 1.0' after 'ply'.");
  const std::size_t body = text.size() - lines.pos() + 1;  // the last value may lack a separator
  double minBytes = 0;
  long long vertices = 0, faces = 0;
  for (const PlyElement& e : elements) {
    double row = 0;
    for (const PlyProperty& p : e.properties) row += format == "ascii" ? 2 : (p.countSize ? p.countSize : p.size);
    requireRoom(fail, e.line, e.count, std::max(row, 1.0), std::size_t(std::max(0.0, body - minBytes)),
                "'" + e.name + "' rows");
    minBytes += e.count * std::max(row, 1.0);
    if (e.name == "vertex") vertices = e.count;
    if (e.name == "face") faces = e.count;
  }
  checkPlyBody(fail, text, lines.pos(), lines.number() + 1, format, elements, vertices);
  return faces;
}

// ---------------------------------------------------------------------------------------- STL

long long checkStl(const Fail& fail, const std::string& text) {
  std::uint32_t count = 0;
  if (text.size() >= 84)
    for (int k = 3; k >= 0; --k) count = count << 8 | static_cast<unsigned char>(text[80 + k]);
  if (text.size() >= 84 && text.size() == 84 + 50 * std::uintmax_t(count)) return count;
  if (text.compare(0, 5, "solid") != 0) {
    if (text.size() < 84) fail("too short for a binary STL (an 84-byte header) and not an ASCII STL ('solid').");
    fail("a binary STL of " + std::to_string(count) + " triangles has " + std::to_string(84 + 50 * std::uintmax_t(count)) +
         " bytes, but this file has " + std::to_string(text.size()) + "." + kTruncated);
  }
  Lines lines(text);
  std::vector<std::string> t;
  long long facets = 0;
  int vertices = -1;  // -1: outside a facet
  while (lines.nextTokens(t)) {
    const long n = lines.number();
    if (t[0] == "facet") {
      if (vertices >= 0) fail.at(n, "'facet' before the previous facet's 'endfacet'.");
      vertices = 0;
    } else if (t[0] == "vertex") {
      if (vertices < 0) fail.at(n, "'vertex' outside a facet.");
      if (t.size() != 4) fail.at(n, "a vertex is 'vertex x y z'.");
      ++vertices;
    } else if (t[0] == "endfacet") {
      if (vertices != 3)
        fail.at(n, "facet " + std::to_string(facets) + " has " + std::to_string(std::max(vertices, 0)) +
                       " vertices. Fix: an STL facet is a triangle of 3 vertices.");
      vertices = -1;
      ++facets;
    } else if (t[0] == "endsolid") {
      if (vertices >= 0) fail.at(n, "'endsolid' inside a facet." + std::string(kTruncated));
      return facets;
    }
  }
  fail("the file ends at line " + std::to_string(lines.number()) + " without 'endsolid' (after " +
       std::to_string(facets) + " complete facets)." + kTruncated);
}

// ---------------------------------------------------------------------------------------- OBJ

void checkMtl(const std::string& path) {
  requireRegularFile(path, "MTL file");
  const std::string text = readAll(path);
  const Fail fail(path);
  Lines lines(text);
  std::vector<std::string> t;
  while (lines.nextTokens(t))
    if ((t[0] == "Kd" || t[0] == "Ke") && t.size() != 4)
      fail.at(lines.number(), "'" + t[0] + "' needs three values (r g b), found " +
                                  std::to_string(t.size() - 1) + ". Fix: write all three.");
}

long long checkObj(const std::string& path, const Fail& fail, const std::string& text) {
  Lines lines(text);
  std::vector<std::string> t;
  long long vertices = 0, faces = 0, highest = 0;
  long highestLine = 0;
  while (lines.nextTokens(t)) {
    const long n = lines.number();
    if (t[0] == "v") {
      if (t.size() < 4)
        fail.at(n, "a vertex has " + std::to_string(t.size() - 1) + " coordinates. Fix: write 'v x y z'.");
      ++vertices;
    } else if (t[0] == "f") {
      checkFaceSize(fail, n, faces, (long long)t.size() - 1);
      for (std::size_t k = 1; k < t.size(); ++k) {
        long long v = 0;
        if (!parseInteger(t[k].substr(0, t[k].find('/')), v) || v == 0)
          fail.at(n, "'" + t[k] + "' is not a vertex reference. Fix: OBJ counts vertices from 1 "
                     "(negative: back from the last one).");
        if (v < 0 && -v > vertices)
          fail.at(n, "face " + std::to_string(faces) + " refers to vertex " + t[k] + ", but only " +
                         std::to_string(vertices) + " vertices come before it. Fix: correct the index.");
        if (v > highest) highest = v, highestLine = n;
      }
      ++faces;
    } else if (t[0] == "mtllib") {
      for (std::size_t k = 1; k < t.size(); ++k) {
        const fs::path mtl = fs::path(path).parent_path() / t[k];
        if (fs::exists(mtl)) checkMtl(mtl.string());
      }
    }
  }
  if (highest > vertices)
    fail.at(highestLine, "a face names vertex " + std::to_string(highest) + ", but the file has " +
                             std::to_string(vertices) + " vertices. Fix: correct the index.");
  return -1;
}

}  // namespace

void requireRegularFile(const std::string& path, const std::string& what) {
  std::error_code ec;
  if (fs::exists(path, ec) && !fs::is_regular_file(path, ec))
    throw InputError(path + ": the " + what + " is not a regular file (a folder, pipe or device). "
                     "Fix: give the path of a file.");
}

long long checkMeshStructure(const std::string& path) {
  requireRegularFile(path, "mesh file");
  const std::string ext = lower(fs::path(path).extension().string());
  const std::string text = readAll(path);
  const Fail fail(path);
  if (ext == ".obj") return checkObj(path, fail, text);
  if (ext == ".off") return checkOff(fail, text);
  if (ext == ".ply") return checkPly(fail, text);
  if (ext == ".stl") return checkStl(fail, text);
  return -1;
}

}  // namespace radkit
