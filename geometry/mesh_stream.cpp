// The streaming mesh reader (mesh_stream.h).
//
// Why a hand-written reader beside OpenMesh: the full path reads a file three times (the
// structure check into a string, the number check line by line, OpenMesh's parse into a
// half-edge mesh that is then copied out). For a 1-million-triangle terrain that took 4.7 s
// from ASCII OFF (40 MB) and 3.5 s from binary PLY (19 MB), with the whole file, the half-edge
// mesh and the copy in memory at once. This reader maps the file, parses each value once,
// writes vertices and faces where they stay and gives back the pages it has read: 0.6 s and
// 0.37 s, holding nothing but the result (measured on a busy 2-core machine). It covers the
// common layouts only; anything else goes the full way, which stays the reference
// (tests/geometry/large_mesh_test.cpp compares both on every shipped mesh).
#include "geometry/mesh_stream.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cfloat>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <unordered_map>
#include <vector>

#include "geometry/mesh_structure.h"
#include "geometry/positions.h"
#include "geometry/structure_text.h"
#include "util/errors.h"
#include "util/setting_names.h"

namespace radkit {

namespace {

namespace fs = std::filesystem;

/// A read-only mapping of a whole file; pages already parsed are given back as the reader
/// moves on, so resident memory does not grow with the file.
class MappedFile {
 public:
  explicit MappedFile(const std::string& path) {
    m_fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (m_fd < 0) return;
    struct stat st {};
    if (::fstat(m_fd, &st) != 0 || !S_ISREG(st.st_mode) || st.st_size <= 0) return;
    m_size = std::size_t(st.st_size);
    void* p = ::mmap(nullptr, m_size, PROT_READ, MAP_PRIVATE, m_fd, 0);
    if (p == MAP_FAILED) {
      m_size = 0;
      return;
    }
    m_data = static_cast<const char*>(p);
    ::madvise(p, m_size, MADV_SEQUENTIAL);
  }
  ~MappedFile() {
    if (m_data) ::munmap(const_cast<char*>(m_data), m_size);
    if (m_fd >= 0) ::close(m_fd);
  }
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;
  bool ok() const { return m_data != nullptr; }
  const char* data() const { return m_data; }
  std::size_t size() const { return m_size; }
  /// Gives back the pages wholly before `pos` (they are read again from the file if needed).
  void release(std::size_t pos) {
    static const std::size_t page = std::size_t(::sysconf(_SC_PAGESIZE));
    const std::size_t end = pos / page * page;
    if (end > m_released + (16u << 20)) {
      ::madvise(const_cast<char*>(m_data) + m_released, end - m_released, MADV_DONTNEED);
      m_released = end;
    }
  }

 private:
  int m_fd = -1;
  const char* m_data = nullptr;
  std::size_t m_size = 0, m_released = 0;
};

/// Thrown inside the reader when the file needs the full path; never leaves this file.
struct Fallback {};

bool isSpace(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\v' || c == '\f' || c == '\r';
}

/// A token copied into a terminated buffer for strtof/strtod (tokens of numbers are short).
struct TokenText {
  char text[128];
  bool set(const char* b, const char* e) {
    const std::size_t n = std::size_t(e - b);
    if (n >= sizeof text) return false;
    std::memcpy(text, b, n);
    text[n] = 0;
    return true;
  }
};

enum class Number { Ok, NotFinite, Fallback };

/// A coordinate token as OpenMesh reads it (istream >> float: strtof), checked as
/// checkTextMeshNumbers checks it (a whole finite decimal for strtod, no hex).
Number parseFloat(const char* b, const char* e, float& out) {
  TokenText t;
  if (!t.set(b, e)) {
    // Very long: decide with the full check's own functions on a std::string.
    const std::string s(b, e);
    if (s.find_first_of("xX") != std::string::npos) return Number::NotFinite;
    char* end = nullptr;
    errno = 0;
    const double d = std::strtod(s.c_str(), &end);
    if (end != s.c_str() + s.size() || (errno == ERANGE && std::fabs(d) > 1.0) || !std::isfinite(d))
      return Number::NotFinite;
    return Number::Fallback;
  }
  for (const char* p = b; p != e; ++p)
    if (*p == 'x' || *p == 'X') return Number::NotFinite;
  // The common token, a plain decimal: from_chars rounds as strtof does (to nearest).
  const auto fast = std::from_chars(b, e, out);
  if (fast.ec == std::errc() && fast.ptr == e && std::isfinite(out) &&
      (out != 0 || std::all_of(b, e, [](char c) { return c == '0' || c == '.' || c == '-'; })))
    return Number::Ok;
  char* end = nullptr;
  out = std::strtof(t.text, &end);
  if (end != t.text + (e - b)) return Number::NotFinite;
  if (std::isfinite(out)) return Number::Ok;
  errno = 0;
  const double d = std::strtod(t.text, &end);
  if ((errno == ERANGE && std::fabs(d) > 1.0) || !std::isfinite(d)) return Number::NotFinite;
  return Number::Fallback;  // finite as a double, beyond a float: OpenMesh's stream fails there
}

/// checkTextMeshNumbers's test of any other token.
bool isFiniteDecimal(const char* b, const char* e) {
  float ignored;
  const Number n = parseFloat(b, e, ignored);
  return n != Number::NotFinite;
}

/// A whole-token decimal integer as structure::parseInteger reads it.
bool parseInt(const char* b, const char* e, long long& v) {
  const char* p = b;
  bool negative = false;
  if (p != e && (*p == '-' || *p == '+')) negative = *p++ == '-';
  if (p == e || e - p > 18) return structure::parseInteger(std::string(b, e), v);
  long long r = 0;
  for (; p != e; ++p) {
    if (*p < '0' || *p > '9') return false;
    r = r * 10 + (*p - '0');
  }
  v = negative ? -r : r;
  return true;
}

/// Lines and tokens of a text body as structure::Lines and the number check see them: lines end
/// at '\n', a '#' where a token starts begins a comment (`comments`), tokens split at spaces.
class TextCursor {
 public:
  TextCursor(const MappedFile& file, std::size_t pos, long line, bool comments)
      : m_file(file),
        m_p(file.data() + pos),
        m_end(file.data() + file.size()),
        m_line(line),
        m_comments(comments) {}
  /// The tokens of the next line that has any ('#' comments dropped when `comments`).
  /// Returns false at the end of the file.
  bool nextLine(std::vector<std::pair<const char*, const char*>>& t) {
    while (m_p < m_end) {
      t.clear();
      ++m_line;
      const char* lineEnd =
          static_cast<const char*>(std::memchr(m_p, '\n', std::size_t(m_end - m_p)));
      if (!lineEnd) lineEnd = m_end;
      const char* p = m_p;
      while (p < lineEnd) {
        while (p < lineEnd && isSpace(*p)) ++p;
        if (p >= lineEnd) break;
        if (m_comments && *p == '#' && (p == m_p || p[-1] == ' ' || p[-1] == '\t')) break;
        const char* b = p;
        while (p < lineEnd && !isSpace(*p)) ++p;
        t.emplace_back(b, p);
      }
      m_p = lineEnd < m_end ? lineEnd + 1 : m_end;
      if (!t.empty()) return true;
    }
    return false;
  }
  /// The next token across lines (PLY bodies); line() is then its line.
  bool nextToken(const char*& b, const char*& e) {
    while (m_p < m_end && isSpace(*m_p))
      if (*m_p++ == '\n') ++m_line;
    if (m_p >= m_end) return false;
    b = m_p;
    while (m_p < m_end && !isSpace(*m_p)) ++m_p;
    e = m_p;
    return true;
  }
  long line() const { return m_line; }
  std::size_t pos() const { return std::size_t(m_p - m_file.data()); }

 private:
  const MappedFile& m_file;
  const char* m_p;
  const char* m_end;
  long m_line;
  bool m_comments;
};

/// The first text number that is not finite, reported after the structure is known good (the
/// full path checks the structure of the whole file before any number).
struct NumberError {
  bool found = false;
  long line = 0;
  std::string token, element;
  void note(long atLine, const char* b, const char* e, const std::string& what) {
    if (found) return;
    found = true;
    line = atLine;
    token.assign(b, e);
    element = what;
  }
  void raise(const std::string& path) const {
    if (!found) return;
    throw InputError(path + ": line " + std::to_string(line) + ": '" + token +
                     "' is not a finite number" + (element.empty() ? "" : " (" + element + ")") +
                     ". Fix: write every number as a finite decimal (a '.' as the decimal "
                     "point, no NaN or infinity).");
  }
};

/// Progress every 1/64 of the file, and pages behind the cursor released.
class Pacer {
 public:
  Pacer(MappedFile& file, const MeshReadProgress& progress) : m_file(file), m_progress(progress) {}
  void at(std::size_t pos) {
    if (pos < m_next) return;
    m_file.release(pos);
    if (m_progress) m_progress(double(pos) / double(m_file.size()));
    m_next = pos + std::max<std::size_t>(m_file.size() / 64, 1u << 20);
  }

 private:
  MappedFile& m_file;
  const MeshReadProgress& m_progress;
  std::size_t m_next = 0;
};

/// Faces OpenMesh refuses (repeating a vertex) dropped or reported as readWithOpenMesh does.
bool repeatsVertex(const FaceIndices& f) {
  for (std::size_t a = 0; a < f.size(); ++a)
    for (std::size_t b = a + 1; b < f.size(); ++b)
      if (f[a] == f[b]) return true;
  return false;
}

/// A face repeating a vertex is dropped and counted; without `repair` the caller reports it
/// once the whole file is known to be well formed (the full path checks structure first).
void addFace(RawMesh& raw, FaceIndices&& face) {
  if (repeatsVertex(face)) {
    ++raw.droppedFaces;
    return;
  }
  raw.faces.push_back(Face{std::move(face)});
}

void requireNoRepeats(const RawMesh& raw, bool repair, const std::string& path) {
  if (raw.droppedFaces > 0 && !repair)
    throw InputError(path +
                     ": a face repeats a vertex (degenerate face). Fix: remove the "
                     "repeated index from the face, or give " +
                     setting("repair") + " to drop such faces.");
}

/// OpenMesh gives faces it cannot join manifoldly copies of their vertices, and the full path
/// maps those back to the first vertex at each position: where no two vertices share a
/// position that is the file's own vertex, so this reader's result is the same. Where some do,
/// the full path decides.
void requireDistinctPositions(const RawMesh& raw) {
  if (repeatedPositions(raw.vertices, true) > 0) throw Fallback{};
}

// ---------------------------------------------------------------------------------------- OFF

RawMesh readOff(MappedFile& file, const std::string& path, bool repair,
                const MeshReadProgress& progress) {
  TextCursor cursor(file, 0, 0, true);
  std::vector<std::pair<const char*, const char*>> t;
  Pacer pacer(file, progress);
  NumberError numbers;
  // "OFF" alone on its line, then "vertices faces [edges]": other keys (COFF, NOFF, 4OFF,
  // "OFF BINARY"), counts on the key's line or no key take the full path.
  if (!cursor.nextLine(t) || t.size() != 1 || std::string(t[0].first, t[0].second) != "OFF")
    throw Fallback{};
  if (!cursor.nextLine(t) || t.size() < 2 || t.size() > 3) throw Fallback{};
  long long nv = 0, nf = 0, ne = 0;
  if (!parseInt(t[0].first, t[0].second, nv) || !parseInt(t[1].first, t[1].second, nf) ||
      (t.size() == 3 && !parseInt(t[2].first, t[2].second, ne)) || nv < 0 || nf < 0 ||
      nv > INT_MAX || nf > INT_MAX)
    throw Fallback{};
  const std::size_t rest = file.size() - cursor.pos() + 1;
  if (double(nv) * 6 > double(rest) || double(nf) * 2 > double(rest) - double(nv) * 6)
    throw Fallback{};
  RawMesh raw;
  raw.vertices.reserve(std::size_t(nv));
  raw.faces.reserve(std::size_t(nf));
  for (long long v = 0; v < nv; ++v) {
    if (!cursor.nextLine(t) || t.size() != 3) throw Fallback{};
    float c[3];
    for (int k = 0; k < 3; ++k) {
      const Number n = parseFloat(t[k].first, t[k].second, c[k]);
      if (n == Number::Fallback) throw Fallback{};
      if (n == Number::NotFinite) {
        numbers.note(cursor.line(), t[k].first, t[k].second, "vertex " + std::to_string(v));
        c[k] = 0;
      }
    }
    raw.vertices.push_back({double(c[0]), double(c[1]), double(c[2])});
    pacer.at(cursor.pos());
  }
  for (long long f = 0; f < nf; ++f) {
    if (!cursor.nextLine(t)) throw Fallback{};
    long long n = 0;
    if (!parseInt(t[0].first, t[0].second, n) || n < 3 || n > (long long)t.size() - 1)
      throw Fallback{};
    FaceIndices face;
    face.reserve(std::size_t(n));
    for (long long k = 1; k <= n; ++k) {
      long long index = 0;
      if (!parseInt(t[k].first, t[k].second, index) || index < 0 || index >= nv) throw Fallback{};
      face.push_back(int(index));
    }
    // Values after the indices (per-face colours) are dropped, as the full path drops them;
    // they are numbers all the same.
    for (std::size_t k = std::size_t(n) + 1; k < t.size(); ++k)
      if (!isFiniteDecimal(t[k].first, t[k].second))
        numbers.note(cursor.line(), t[k].first, t[k].second, "face " + std::to_string(f));
    if (!numbers.found) addFace(raw, std::move(face));
    pacer.at(cursor.pos());
  }
  // The number check reads to the end of the file.
  while (cursor.nextLine(t))
    for (const auto& token : t)
      if (!isFiniteDecimal(token.first, token.second))
        numbers.note(cursor.line(), token.first, token.second, "after the faces");
  numbers.raise(path);
  requireNoRepeats(raw, repair, path);
  return raw;
}

// ---------------------------------------------------------------------------------------- PLY

struct Property {
  std::string name, type, countType;
  int size = 0, countSize = 0;
  bool isFloat = false, isSigned = false;
};

/// Binary values of either byte order.
struct Bytes {
  const unsigned char* p;
  bool big;
  std::uint64_t raw(int size) const {
    std::uint64_t v = 0;
    for (int b = 0; b < size; ++b) v |= std::uint64_t(p[b]) << (big ? 8 * (size - 1 - b) : 8 * b);
    return v;
  }
  /// A value of a PLY type as OpenMesh's reader turns it into a float coordinate.
  float asFloat(const Property& prop) const {
    const std::uint64_t v = raw(prop.size);
    if (prop.size == 4) {
      float f;
      const std::uint32_t u = std::uint32_t(v);
      std::memcpy(&f, &u, 4);
      return f;
    }
    double d;
    std::memcpy(&d, &v, 8);
    return float(d);
  }
  long long asInteger(int size, bool isSigned) const {
    long long v = (long long)raw(size);
    if (isSigned && v >= (1LL << (8 * size - 1))) v -= 1LL << (8 * size);
    return v;
  }
};

RawMesh readPly(MappedFile& file, const std::string& path, bool repair,
                const MeshReadProgress& progress) {
  // The header: "ply", one "format ... 1.0", comments, then exactly the elements "vertex" and
  // "face" in that order; vertex x, y, z as float or double among other scalars, face with its
  // index list and scalars only. Anything else (tristrips, other elements, lists beside the
  // indices) takes the full path.
  const char* data = file.data();
  const std::size_t size = file.size();
  std::size_t pos = 0;
  long lineNo = 0;
  auto nextHeaderLine = [&](std::string& line) {
    if (pos >= size) return false;
    const char* nl = static_cast<const char*>(std::memchr(data + pos, '\n', size - pos));
    const std::size_t end = nl ? std::size_t(nl - data) : size;
    if (end - pos > 4096) throw Fallback{};
    line.assign(data + pos, end - pos);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    pos = end + 1;
    ++lineNo;
    return true;
  };
  std::string line;
  if (!nextHeaderLine(line) || line != "ply") throw Fallback{};
  std::string format;
  struct Element {
    std::string name;
    long long count = 0;
    std::vector<Property> properties;
  };
  std::vector<Element> elements;
  bool ended = false;
  while (!ended && nextHeaderLine(line)) {
    const auto t = structure::tokens(line);
    if (t.empty() || t[0] == "comment" || t[0] == "obj_info") continue;
    if (t[0] == "end_header") {
      ended = true;
    } else if (t[0] == "format") {
      if (!format.empty() || t.size() != 3 || t[2] != "1.0" ||
          (t[1] != "ascii" && t[1] != "binary_little_endian" && t[1] != "binary_big_endian"))
        throw Fallback{};
      format = t[1];
    } else if (t[0] == "element") {
      long long count = 0;
      if (t.size() != 3 || !structure::parseInteger(t[2], count) || count < 0 || count > INT_MAX)
        throw Fallback{};
      elements.push_back({t[1], count, {}});
    } else if (t[0] == "property") {
      if (elements.empty()) throw Fallback{};
      Property p;
      const bool list = t.size() == 5 && t[1] == "list";
      if (!list && t.size() != 3) throw Fallback{};
      p.name = t.back();
      p.type = t[t.size() - 2];
      p.size = structure::plyTypeSize(p.type);
      p.isFloat = p.type.find_first_of("fd") == 0;
      p.isSigned = p.type[0] != 'u';
      if (list) {
        p.countType = t[2];
        p.countSize = structure::plyTypeSize(t[2]);
        if (p.countSize == 0 || t[2][0] == 'f' || t[2][0] == 'd') throw Fallback{};
      }
      if (p.size == 0) throw Fallback{};
      elements.back().properties.push_back(p);
    } else {
      throw Fallback{};
    }
  }
  if (!ended || format.empty() || elements.size() != 2 || elements[0].name != "vertex" ||
      elements[1].name != "face")
    throw Fallback{};
  const Element& ve = elements[0];
  const Element& fe = elements[1];
  int xyz[3] = {-1, -1, -1};
  for (std::size_t k = 0; k < ve.properties.size(); ++k) {
    const Property& p = ve.properties[k];
    if (p.countSize) throw Fallback{};
    for (int c = 0; c < 3; ++c)
      if (p.name == std::string(1, char('x' + c))) {
        if (xyz[c] >= 0 || !p.isFloat) throw Fallback{};
        xyz[c] = int(k);
      }
  }
  if (xyz[0] < 0 || xyz[1] < 0 || xyz[2] < 0) throw Fallback{};
  int indexList = -1;
  for (std::size_t k = 0; k < fe.properties.size(); ++k) {
    const Property& p = fe.properties[k];
    if (!p.countSize) continue;
    if (indexList >= 0 || (p.name != "vertex_indices" && p.name != "vertex_index") || p.isFloat)
      throw Fallback{};
    indexList = int(k);
  }
  if (indexList < 0) throw Fallback{};
  const bool ascii = format == "ascii";
  // The full path's room check: the header's counts against the bytes after it.
  {
    const double body = double(size - std::min(pos, size) + 1);
    double minBytes = 0;
    for (const Element& e : elements) {
      double row = 0;
      for (const Property& p : e.properties)
        row += ascii ? 2 : (p.countSize ? p.countSize : p.size);
      row = std::max(row, 1.0);
      if (double(e.count) * row > std::max(0.0, body - minBytes)) throw Fallback{};
      minBytes += double(e.count) * row;
    }
  }
  const long long nv = ve.count, nf = fe.count;
  RawMesh raw;
  raw.vertices.reserve(std::size_t(nv));
  raw.faces.reserve(std::size_t(nf));
  Pacer pacer(file, progress);
  if (!ascii) {
    const bool big = format == "binary_big_endian";
    const unsigned char* p = reinterpret_cast<const unsigned char*>(data) + std::min(pos, size);
    const unsigned char* end = reinterpret_cast<const unsigned char*>(data) + size;
    std::size_t vertexRow = 0;
    std::vector<std::size_t> offset(ve.properties.size());
    for (std::size_t k = 0; k < ve.properties.size(); ++k)
      offset[k] = vertexRow, vertexRow += std::size_t(ve.properties[k].size);
    if (std::size_t(end - p) < vertexRow * std::size_t(nv)) throw Fallback{};
    for (long long v = 0; v < nv; ++v, p += vertexRow) {
      float c[3];
      for (int k = 0; k < 3; ++k)
        c[k] =
            Bytes{p + offset[std::size_t(xyz[k])], big}.asFloat(ve.properties[std::size_t(xyz[k])]);
      raw.vertices.push_back({double(c[0]), double(c[1]), double(c[2])});
      if ((v & 0xffff) == 0) pacer.at(std::size_t(reinterpret_cast<const char*>(p) - data));
    }
    const Property& list = fe.properties[std::size_t(indexList)];
    for (long long f = 0; f < nf; ++f) {
      FaceIndices face;
      for (std::size_t k = 0; k < fe.properties.size(); ++k) {
        const Property& prop = fe.properties[k];
        if (int(k) != indexList) {
          if (end - p < prop.size) throw Fallback{};
          p += prop.size;
          continue;
        }
        if (end - p < list.countSize) throw Fallback{};
        const long long n = Bytes{p, big}.asInteger(list.countSize, false);
        // A signed count with its top bit set reads negative in OpenMesh: the full path decides.
        if (list.countType[0] != 'u' && n >= (1LL << (8 * list.countSize - 1))) throw Fallback{};
        p += list.countSize;
        if (n < 3 || double(end - p) < double(n) * list.size) throw Fallback{};
        face.reserve(std::size_t(n));
        for (long long i = 0; i < n; ++i, p += list.size) {
          const long long index = Bytes{p, big}.asInteger(list.size, list.isSigned);
          if (index < 0 || index >= nv) throw Fallback{};
          face.push_back(int(index));
        }
      }
      addFace(raw, std::move(face));
      if ((f & 0xffff) == 0) pacer.at(std::size_t(reinterpret_cast<const char*>(p) - data));
    }
    requireNoRepeats(raw, repair, path);
    return raw;
  }
  // ASCII: tokens across lines; a row starts on a later line than the previous row ended.
  TextCursor cursor(file, std::min(pos, size), lineNo + 1, false);
  NumberError numbers;
  const char *b = nullptr, *e = nullptr;
  long previousRowEnd = -1;
  for (long long v = 0; v < nv; ++v) {
    float c[3] = {0, 0, 0};
    for (std::size_t k = 0; k < ve.properties.size(); ++k) {
      if (!cursor.nextToken(b, e)) throw Fallback{};
      if (k == 0 && v > 0 && cursor.line() == previousRowEnd) throw Fallback{};
      int which = -1;
      for (int q = 0; q < 3; ++q)
        if (xyz[q] == int(k)) which = q;
      if (which >= 0) {
        const Number n = parseFloat(b, e, c[which]);
        if (n == Number::Fallback) throw Fallback{};
        if (n == Number::NotFinite)
          numbers.note(cursor.line(), b, e, "vertex " + std::to_string(v));
      } else if (!isFiniteDecimal(b, e)) {
        numbers.note(cursor.line(), b, e, "vertex " + std::to_string(v));
      }
    }
    previousRowEnd = ve.properties.empty() ? previousRowEnd : cursor.line();
    raw.vertices.push_back({double(c[0]), double(c[1]), double(c[2])});
    pacer.at(cursor.pos());
  }
  previousRowEnd = -1;
  for (long long f = 0; f < nf; ++f) {
    FaceIndices face;
    bool first = true;
    for (std::size_t k = 0; k < fe.properties.size(); ++k) {
      if (!cursor.nextToken(b, e)) throw Fallback{};
      if (first && f > 0 && cursor.line() == previousRowEnd) throw Fallback{};
      first = false;
      if (int(k) != indexList) {  // a scalar beside the indices (lists took the full path)
        if (!isFiniteDecimal(b, e)) numbers.note(cursor.line(), b, e, "face " + std::to_string(f));
        continue;
      }
      long long n = 0;
      // Each index takes two bytes at least ("0 "): a count the rest of the file cannot hold is
      // the full path's to word (and reserving it would allocate without bound).
      if (!parseInt(b, e, n) || n < 3 || double(n) * 2 > double(file.size() - cursor.pos()) + 1)
        throw Fallback{};
      face.reserve(std::size_t(n));
      for (long long i = 0; i < n; ++i) {
        long long index = 0;
        if (!cursor.nextToken(b, e) || !parseInt(b, e, index) || index < 0 || index >= nv)
          throw Fallback{};
        face.push_back(int(index));
      }
    }
    previousRowEnd = cursor.line();
    if (!numbers.found) addFace(raw, std::move(face));
    pacer.at(cursor.pos());
  }
  while (cursor.nextToken(b, e))
    if (!isFiniteDecimal(b, e)) numbers.note(cursor.line(), b, e, "after the faces");
  numbers.raise(path);
  requireNoRepeats(raw, repair, path);
  return raw;
}

// ---------------------------------------------------------------------------------------- STL

/// Binary STL: each triangle's corners welded by exact position, vertices numbered in order of
/// first use, as OpenMesh's reader numbers them. A hash map keeps it linear in the triangles.
RawMesh readBinaryStl(MappedFile& file, const std::string& path, bool repair,
                      const MeshReadProgress& progress) {
  const std::size_t size = file.size();
  if (size < 84) throw Fallback{};
  const unsigned char* d = reinterpret_cast<const unsigned char*>(file.data());
  const std::uint32_t count = std::uint32_t(Bytes{d + 80, false}.raw(4));
  if (size != 84 + 50 * std::uintmax_t(count)) throw Fallback{};  // ASCII, or truncated
  struct Key {
    float c[3];
    bool operator==(const Key& o) const {
      return c[0] == o.c[0] && c[1] == o.c[1] && c[2] == o.c[2];
    }
  };
  struct KeyHash {
    std::size_t operator()(const Key& k) const {
      std::uint64_t h = 1469598103934665603ull;
      for (float f : k.c) {
        std::uint32_t bits;
        std::memcpy(&bits, &f, 4);
        h = (h ^ bits) * 1099511628211ull;
      }
      return std::size_t(h ^ (h >> 31));
    }
  };
  std::unordered_map<Key, int, KeyHash> index;
  index.reserve(std::size_t(count) / 2 + 16);
  RawMesh raw;
  raw.vertices.reserve(std::size_t(count) / 2 + 3);
  raw.faces.reserve(count);
  Pacer pacer(file, progress);
  for (std::uint32_t t = 0; t < count; ++t) {
    const unsigned char* p = d + 84 + 50 * std::size_t(t) + 12;  // after the normal
    FaceIndices face;
    for (std::size_t corner = 0; corner < 3; ++corner) {
      Key key;
      std::memcpy(key.c, p + 12 * corner, 12);
      for (float& c : key.c) {
        // OpenMesh compares within FLT_MIN: -0 and +0 are one position; subnormal or
        // non-finite values take the full path.
        if (!std::isfinite(c) || (c != 0 && std::fabs(c) < FLT_MIN)) throw Fallback{};
        if (c == 0) c = 0.0f;
      }
      const auto [it, added] = index.emplace(key, int(raw.vertices.size()));
      if (added) {
        float original[3];
        std::memcpy(original, p + 12 * corner, 12);  // the first corner's own signs of zero
        raw.vertices.push_back({double(original[0]), double(original[1]), double(original[2])});
      }
      face.push_back(it->second);
    }
    addFace(raw, std::move(face));
    if ((t & 0xffff) == 0) pacer.at(84 + 50 * std::size_t(t));
  }
  requireNoRepeats(raw, repair, path);
  return raw;
}

}  // namespace

std::optional<RawMesh> readMeshStreaming(const std::string& path, bool repair,
                                         const MeshReadProgress& progress) {
  const std::string ext = structure::lower(fs::path(path).extension().string());
  if (ext != ".off" && ext != ".ply" && ext != ".stl") return std::nullopt;
  requireRegularFile(path, "mesh file");
  MappedFile file(path);
  if (!file.ok()) return std::nullopt;  // missing, empty or unreadable: the full path words it
  try {
    RawMesh raw = ext == ".off"   ? readOff(file, path, repair, progress)
                  : ext == ".ply" ? readPly(file, path, repair, progress)
                                  : readBinaryStl(file, path, repair, progress);
    if (ext != ".stl") requireDistinctPositions(raw);
    if (progress) progress(1.0);
    return raw;
  } catch (const Fallback&) {
    return std::nullopt;
  }
}

}  // namespace radkit
