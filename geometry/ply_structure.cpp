// The PLY part of checkMeshStructure: header, counts against the file's size, and the body
// (ASCII or binary, either byte order) walked row by row.
#include <cstdint>
#include <string>
#include <vector>

#include "geometry/structure_text.h"

namespace radkit::structure {

namespace {

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

/// Reads the values of a binary PLY body, checking that each lies inside the file.
class BinaryCursor {
 public:
  BinaryCursor(const std::string& text, std::size_t pos, bool big)
      : m_text(text), m_pos(pos), m_big(big) {}
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
  TokenCursor(const std::string& text, std::size_t pos, long line)
      : m_text(text), m_pos(pos), m_line(line) {}
  bool next(std::string& token) {
    while (m_pos < m_text.size() && std::isspace(static_cast<unsigned char>(m_text[m_pos])))
      if (m_text[m_pos++] == '\n') ++m_line;
    if (m_pos >= m_text.size()) return false;
    const std::size_t start = m_pos;
    while (m_pos < m_text.size() && !std::isspace(static_cast<unsigned char>(m_text[m_pos])))
      ++m_pos;
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
  return e.name == "face" && p.countSize > 0 &&
         (p.name == "vertex_indices" || p.name == "vertex_index");
}

/// Triangle strips (Stanford's igea.ply and other range scans): index lists where -1 restarts.
bool isStripIndexList(const PlyElement& e, const PlyProperty& p) {
  return e.name == "tristrips" && p.countSize > 0 &&
         (p.name == "vertex_indices" || p.name == "vertex_index");
}

void checkPlyBody(const Fail& fail, const std::string& text, std::size_t pos, long line,
                  const std::string& format, const std::vector<PlyElement>& elements,
                  long long vertices, std::vector<long long>* strips) {
  const bool ascii = format == "ascii";
  TokenCursor tokens(text, pos, line);
  BinaryCursor bytes(text, pos, format == "binary_big_endian");
  std::string token;
  for (const PlyElement& e : elements) {
    long previousRowEnd = -1;  // ASCII: the line the previous row's last value was on
    std::string names;
    for (const PlyProperty& p : e.properties) names += (names.empty() ? "" : ", ") + p.name;
    for (long long row = 0; row < e.count; ++row) {
      auto truncated = [&]() {
        fail("the file ends inside element '" + e.name + "' row " + std::to_string(row) +
             " of the " + std::to_string(e.count) + " its header declares (line " +
             std::to_string(e.line) + ")." + kTruncated);
      };
      bool first = true;
      // An ASCII token; the row's first must start a line after the previous row's last, or
      // that row held more values than the header's properties take (any later complaint
      // would name the wrong row).
      auto nextToken = [&]() {
        if (!tokens.next(token)) truncated();
        if (first && row > 0 && tokens.line() == previousRowEnd)
          fail.at(tokens.line(),
                  "element '" + e.name + "' row " + std::to_string(row - 1) +
                      " has more values than its header's properties (" + names +
                      ") take, so row " + std::to_string(row) +
                      " would start inside it. Fix: give each row exactly the values the "
                      "header declares (a list's count first), or declare the extra ones.");
        first = false;
      };
      for (const PlyProperty& p : e.properties) {
        const bool strip = isStripIndexList(e, p);
        const bool indices = isFaceIndexList(e, p) || strip;
        long long n = 1;
        if (p.countSize > 0) {
          if (ascii) {
            nextToken();
            if (!parseInteger(token, n) || n < 0)
              fail.at(tokens.line(), "'" + token + "' is not a list length in element '" + e.name +
                                         "' row " + std::to_string(row) +
                                         ". Fix: write a whole number >= 0.");
          } else {
            if (!bytes.has(p.countSize)) truncated();
            n = bytes.integer(p.countSize);
          }
          if (indices && !strip) checkFaceSize(fail, ascii ? tokens.line() : 0, row, n);
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
            nextToken();
            if (indices && !parseInteger(token, index))
              fail.at(tokens.line(), "'" + token + "' is not a vertex index.");
          } else {
            index = bytes.integer(p.size);
            if (p.isSigned && index >= (1LL << (8 * p.size - 1))) index -= 1LL << (8 * p.size);
          }
          if (strip && index == -1) {  // a restart
            if (strips) strips->push_back(-1);
            continue;
          }
          if (indices) checkIndex(fail, ascii ? tokens.line() : 0, row, index, vertices);
          if (strip && strips) strips->push_back(index);
        }
        if (strip && strips) strips->push_back(-1);  // each row is its own strip
      }
      if (ascii && !first) previousRowEnd = tokens.line();
    }
  }
}

}  // namespace

int plyTypeSize(const std::string& type) {
  static const std::pair<const char*, int> types[] = {
      {"char", 1},  {"uchar", 1},   {"int8", 1},   {"uint8", 1},  {"short", 2}, {"ushort", 2},
      {"int16", 2}, {"uint16", 2},  {"int", 4},    {"uint", 4},   {"int32", 4}, {"uint32", 4},
      {"float", 4}, {"float32", 4}, {"double", 8}, {"float64", 8}};
  for (const auto& t : types)
    if (type == t.first) return t.second;
  return 0;
}

long long checkPly(const Fail& fail, const std::string& text, std::vector<long long>* strips) {
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
      // Exactly one line, version 1.0: OpenMesh's header reader loops on any other version,
      // logging a line per byte (fuzz_ply timeout, tests/geometry/malformed_mesh_test.cpp).
      if (t.size() != 3 || t[2] != "1.0" ||
          (t[1] != "ascii" && t[1] != "binary_little_endian" && t[1] != "binary_big_endian"))
        fail.at(n,
                "unknown format or version. Fix: 'format ascii 1.0', 'format "
                "binary_little_endian 1.0' or 'format binary_big_endian 1.0'.");
      if (!format.empty()) fail.at(n, "a second 'format' line. Fix: keep one.");
      format = t[1];
    } else if (t[0] == "element") {
      if (t.size() != 3) fail.at(n, "an element line is 'element NAME COUNT'.");
      elements.push_back({t[1], headerCount(fail, n, t[2], "element"), n, {}});
    } else if (t[0] == "property") {
      if (elements.empty())
        fail.at(n, "a property comes before any element. Fix: declare the element first.");
      PlyProperty p;
      const bool list = t.size() == 5 && t[1] == "list";
      if (!list && t.size() != 3)
        fail.at(n,
                "a property line is 'property TYPE NAME' or 'property list COUNT_TYPE TYPE NAME'.");
      p.name = t.back();
      p.size = plyTypeSize(t[t.size() - 2]);
      p.isFloat = t[t.size() - 2].find_first_of("fd") == 0;
      p.isSigned = t[t.size() - 2][0] != 'u';
      p.countSize = list ? plyTypeSize(t[2]) : 0;
      if (p.size == 0 || (list && (p.countSize == 0 || t[2][0] == 'f' || t[2][0] == 'd')))
        fail.at(n,
                "unknown property type. Fix: use char, uchar, short, ushort, int, uint, float or "
                "double "
                "(an integer type for a list's count).");
      if ((isFaceIndexList(elements.back(), p) || isStripIndexList(elements.back(), p)) &&
          p.isFloat)
        fail.at(n, "vertex indices must have an integer type.");
      elements.back().properties.push_back(p);
    } else {
      fail.at(n, "unknown header line '" + t[0] +
                     "'. Fix: the header holds format, element, property "
                     "and comment lines and ends with 'end_header'.");
    }
  }
  if (!ended) fail("the header has no 'end_header' line." + std::string(kTruncated));
  if (format.empty())
    fail("the header has no 'format' line. Fix: add 'format ascii 1.0' after 'ply'.");
  const std::size_t body = text.size() - lines.pos() + 1;  // the last value may lack a separator
  double minBytes = 0;
  long long vertices = 0, faces = 0;
  for (const PlyElement& e : elements) {
    double row = 0;
    for (const PlyProperty& p : e.properties)
      row += format == "ascii" ? 2 : (p.countSize ? p.countSize : p.size);
    requireRoom(fail, e.line, e.count, std::max(row, 1.0),
                std::size_t(std::max(0.0, body - minBytes)), "'" + e.name + "' rows");
    minBytes += e.count * std::max(row, 1.0);
    if (e.name == "vertex") vertices = e.count;
    if (e.name == "face") faces = e.count;
  }
  // OpenMesh, which reads the PLY, misreads a binary face row holding a list besides its
  // indices (MeshLab's per-face texture coordinates): every index after the first row is off.
  if (format != "ascii")
    for (const PlyElement& e : elements)
      for (const PlyProperty& p : e.properties)
        if (e.name == "face" && p.countSize > 0 && !isFaceIndexList(e, p))
          fail.at(e.line, "element 'face' has the list '" + p.name +
                              "' beside its vertex indices, which the binary PLY reader radkit "
                              "uses (OpenMesh) cannot read. Fix: save the mesh without it "
                              "(MeshLab: untick the per-face texture coordinates on export), or "
                              "as ASCII PLY or OFF.");
  checkPlyBody(fail, text, lines.pos(), lines.number() + 1, format, elements, vertices, strips);
  return faces;
}

}  // namespace radkit::structure
