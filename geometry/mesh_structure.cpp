#include "geometry/mesh_structure.h"

#include <cctype>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "geometry/structure_text.h"
#include "util/errors.h"

namespace radkit {

namespace {

namespace fs = std::filesystem;
using namespace structure;

std::string readAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  // An unreadable file read as "" was then reported as empty.
  if (!in)
    throw InputError(path + ": cannot be read (" + std::strerror(errno) +
                     "). Fix: check the file's permissions.");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError(path + ": reading failed (" + std::strerror(errno) + ").");
  return text.str();
}

// ---------------------------------------------------------------------------------------- OFF

long long checkBinaryOff(const Fail& fail, const std::string& text, const Lines& lines) {
  const std::size_t at = lines.pos();
  if (text.size() < at + 12)
    fail("binary OFF header ends before its counts." + std::string(kTruncated));
  const std::size_t body = text.size() - at - 12;
  for (bool big : {true, false}) {  // the counts' byte order is not recorded in the file
    long long c[2];
    for (int k = 0; k < 2; ++k) {
      std::uint32_t v = 0;
      for (int b = 0; b < 4; ++b)
        v |= std::uint32_t(static_cast<unsigned char>(text[at + 4 * std::size_t(k) + b]))
             << (big ? 24 - 8 * b : 8 * b);
      c[k] = v;
    }
    if (c[0] <= INT_MAX && c[1] <= INT_MAX && c[0] * 12.0 + c[1] * 16.0 <= double(body)) return -1;
  }
  fail("binary OFF declares more vertices and faces than its " + std::to_string(text.size()) +
       " bytes can hold." + kTruncated);
}

/// An ASCII OFF's header: its key line ("OFF", "COFF", ...; absent in some files) and counts.
struct OffHeader {
  std::string key;                  ///< empty when the file starts with its counts
  std::vector<std::string> counts;  ///< "vertices faces [edges]" as written
  long long vertices = 0, faces = 0;
  long line = 0;        ///< the counts' line
  bool binary = false;  ///< "OFF BINARY": nothing after the key line was read
};

/// Reads the header from `lines`, leaving them after the counts.
OffHeader readOffHeader(const Fail& fail, Lines& lines) {
  OffHeader h;
  std::vector<std::string> t;
  if (!lines.nextTokens(t))
    fail("the file is empty. Fix: an OFF file starts with 'OFF' and its counts.");
  std::size_t first = 0;
  const std::string key = lower(t[0]);
  if (key.size() >= 3 && key.compare(key.size() - 3, 3, "off") == 0) {
    h.key = t[0];
    if (t.size() > 1 && lower(t[1]) == "binary") {
      h.binary = true;
      return h;
    }
    first = 1;
    if (t.size() == 1) {
      if (!lines.nextTokens(t))
        fail(
            "the header has no vertex and face counts. Fix: write 'vertices faces edges' after "
            "'OFF'.");
      first = 0;
    }
  }
  h.line = lines.number();
  if (t.size() < first + 2)
    fail.at(h.line,
            "the header needs the vertex and face counts. Fix: write 'vertices faces edges'.");
  h.counts.assign(t.begin() + std::ptrdiff_t(first), t.end());
  h.vertices = headerCount(fail, h.line, t[first], "vertex");
  h.faces = headerCount(fail, h.line, t[first + 1], "face");
  return h;
}

/// `faceExtras`, when given, is set when a face line holds values after its indices (per-face
/// colours), which OpenMesh's reader stops at.
long long checkOff(const Fail& fail, const std::string& text, bool* faceExtras = nullptr) {
  Lines lines(text);
  const OffHeader h = readOffHeader(fail, lines);
  if (h.binary) return checkBinaryOff(fail, text, lines);
  std::vector<std::string> t;
  const long header = h.line;
  const long long nv = h.vertices, nf = h.faces;
  // At least "0 0 0\n" per vertex and "n\n" per face (a short face is named below); the last
  // line may lack its '\n'.
  const std::size_t rest = text.size() - lines.pos() + 1;
  requireRoom(fail, header, nv, 6, rest, "vertices");
  requireRoom(fail, header, nf, 2, rest - std::size_t(nv) * 6, "faces");
  for (long long v = 0; v < nv; ++v) {
    if (!lines.nextTokens(t))
      fail("the file ends after " + std::to_string(v) + " of the " + std::to_string(nv) +
           " vertices "
           "its header declares." +
           kTruncated);
    if (t.size() < 3)
      fail.at(lines.number(), "vertex " + std::to_string(v) + " has " + std::to_string(t.size()) +
                                  " coordinates. Fix: write x y z.");
  }
  for (long long f = 0; f < nf; ++f) {
    if (!lines.nextTokens(t))
      fail("the file ends after " + std::to_string(f) + " of the " + std::to_string(nf) +
           " faces "
           "its header declares." +
           kTruncated);
    const long line = lines.number();
    long long n = 0;
    if (!parseInteger(t[0], n)) fail.at(line, "'" + t[0] + "' is not a face's vertex count.");
    checkFaceSize(fail, line, f, n);
    if (n > (long long)t.size() - 1)
      fail.at(line, "face " + std::to_string(f) + " declares " + std::to_string(n) +
                        " vertices but lists " + std::to_string(t.size() - 1) +
                        ". Fix: list every vertex index.");
    for (long long k = 1; k <= n; ++k) {
      long long index = 0;
      if (!parseInteger(t[k], index)) fail.at(line, "'" + t[k] + "' is not a vertex index.");
      checkIndex(fail, line, f, index, nv);
    }
    if (faceExtras && (long long)t.size() > n + 1) *faceExtras = true;
  }
  return nf;
}

/// A checked ASCII OFF as OpenMesh reads it right: the header, then one vertex or face per
/// line, without comments and blank lines, each face cut to its count and indices.
std::string offForOpenMesh(const Fail& fail, const std::string& text) {
  Lines lines(text);
  const OffHeader h = readOffHeader(fail, lines);
  auto joined = [](const std::vector<std::string>& t, std::size_t count) {
    std::string line;
    for (std::size_t k = 0; k < count; ++k) line += (k ? " " : "") + t[k];
    return line + '\n';
  };
  std::string out = h.key.empty() ? "" : h.key + '\n';
  out += joined(h.counts, h.counts.size());
  std::vector<std::string> t;
  for (long long v = 0; v < h.vertices && lines.nextTokens(t); ++v) out += joined(t, t.size());
  for (long long f = 0; f < h.faces && lines.nextTokens(t); ++f)
    out += joined(t, std::size_t(std::stoll(t[0])) + 1);  // checkOff vetted the count
  return out;
}

// ---------------------------------------------------------------------------------------- STL

long long checkStl(const Fail& fail, const std::string& text) {
  std::uint32_t count = 0;
  if (text.size() >= 84)
    for (int k = 3; k >= 0; --k) count = count << 8 | static_cast<unsigned char>(text[80 + k]);
  if (text.size() >= 84 && text.size() == 84 + 50 * std::uintmax_t(count)) return count;
  if (text.compare(0, 5, "solid") != 0) {
    if (text.size() < 84)
      fail("too short for a binary STL (an 84-byte header) and not an ASCII STL ('solid').");
    fail("a binary STL of " + std::to_string(count) + " triangles has " +
         std::to_string(84 + 50 * std::uintmax_t(count)) + " bytes, but this file has " +
         std::to_string(text.size()) + "." + kTruncated);
  }
  Lines lines(text);
  std::vector<std::string> t;
  long long facets = 0;
  int vertices = -1;   // -1: outside a facet
  bool ended = false;  // the last solid is closed (CAD exports write one solid per body)
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
        fail.at(n, "facet " + std::to_string(facets) + " has " +
                       std::to_string(std::max(vertices, 0)) +
                       " vertices. Fix: an STL facet is a triangle of 3 vertices.");
      vertices = -1;
      ++facets;
    } else if (t[0] == "endsolid") {
      if (vertices >= 0) fail.at(n, "'endsolid' inside a facet." + std::string(kTruncated));
      ended = true;
    } else if (t[0] == "solid") {
      ended = false;
    }
  }
  if (ended) return facets;
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
        fail.at(n, "a vertex has " + std::to_string(t.size() - 1) +
                       " coordinates. Fix: write 'v x y z'.");
      ++vertices;
    } else if (t[0] == "f") {
      checkFaceSize(fail, n, faces, (long long)t.size() - 1);
      for (std::size_t k = 1; k < t.size(); ++k) {
        long long v = 0;
        if (!parseInteger(t[k].substr(0, t[k].find('/')), v) || v == 0)
          fail.at(n, "'" + t[k] +
                         "' is not a vertex reference. Fix: OBJ counts vertices from 1 "
                         "(negative: back from the last one).");
        if (v < 0 && -v > vertices)
          fail.at(n, "face " + std::to_string(faces) + " refers to vertex " + t[k] + ", but only " +
                         std::to_string(vertices) +
                         " vertices come before it. Fix: correct the index.");
        if (v > highest) highest = v, highestLine = n;
      }
      ++faces;
    } else if (t[0] == "mtllib") {
      for (const std::string& mtl : mtllibFiles(fs::path(path).parent_path().string(), t)) {
        // A name the file system refuses (too long, say) is a missing MTL, reported by the
        // reader: the non-throwing overload keeps it from ending as a filesystem_error.
        std::error_code ec;
        if (fs::exists(mtl, ec)) checkMtl(mtl);
      }
    }
  }
  if (highest > vertices)
    fail.at(highestLine, "a face names vertex " + std::to_string(highest) + ", but the file has " +
                             std::to_string(vertices) + " vertices. Fix: correct the index.");
  return -1;
}

}  // namespace

std::vector<std::string> mtllibFiles(const std::string& objDir,
                                     const std::vector<std::string>& tokens) {
  std::string whole;  // the names joined by one space: a name's single spaces survive
  for (std::size_t k = 1; k < tokens.size(); ++k) whole += (k > 1 ? " " : "") + tokens[k];
  std::error_code ec;
  if (!whole.empty() && fs::is_regular_file(fs::path(objDir) / whole, ec))
    return {(fs::path(objDir) / whole).string()};
  std::vector<std::string> names;
  std::string name;
  bool escaped = false;
  for (char c : whole) {
    if (escaped) {
      name += c, escaped = false;
    } else if (c == '\\') {
      escaped = true;
    } else if (std::isspace(static_cast<unsigned char>(c))) {
      if (!name.empty()) names.push_back((fs::path(objDir) / name).string()), name.clear();
    } else {
      name += c;
    }
  }
  if (!name.empty()) names.push_back((fs::path(objDir) / name).string());
  return names;
}

void requireRegularFile(const std::string& path, const std::string& what) {
  std::error_code ec;
  if (fs::exists(path, ec) && !fs::is_regular_file(path, ec))
    throw InputError(path + ": the " + what +
                     " is not a regular file (a folder, pipe or device). "
                     "Fix: give the path of a file.");
}

std::vector<std::vector<int>> plyStripTriangles(const std::string& path) {
  std::vector<long long> strips;
  checkPly(Fail(path), readAll(path), &strips);
  std::vector<std::vector<int>> triangles;
  std::vector<int> strip;
  for (long long index : strips) {
    if (index >= 0) {
      strip.push_back(int(index));
      continue;
    }
    for (std::size_t k = 2; k < strip.size(); ++k) {
      const int a = strip[k - 2], b = strip[k - 1], c = strip[k];
      if (a == b || b == c || a == c) continue;  // a join between strips
      triangles.push_back(k % 2 == 0 ? std::vector<int>{a, b, c} : std::vector<int>{b, a, c});
    }
    strip.clear();
  }
  return triangles;
}

long long checkMeshStructure(const std::string& path, std::string* offText) {
  requireRegularFile(path, "mesh file");
  const std::string ext = lower(fs::path(path).extension().string());
  const std::string text = readAll(path);
  const Fail fail(path);
  if (ext == ".obj") return checkObj(path, fail, text);
  if (ext == ".off") {
    bool faceExtras = false;
    const long long faces = checkOff(fail, text, &faceExtras);
    // OpenMesh takes a comment after the header for the counts and then reads for tens of
    // seconds or asks for gigabytes, and stops at per-face colours: such files are rewritten.
    // A binary OFF's bytes may hold '#': it is read as it is.
    Lines first(text);
    if (offText && (faceExtras || text.find('#') != std::string::npos) &&
        !readOffHeader(fail, first).binary)
      *offText = offForOpenMesh(fail, text);
    return faces;
  }
  if (ext == ".ply") return checkPly(fail, text);
  if (ext == ".stl") return checkStl(fail, text);
  return -1;
}

}  // namespace radkit
