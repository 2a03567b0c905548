// radiosity.vtp as radkit writes it (VTK XML PolyData, ASCII), read with expat and checked
// here, not by VTK's XML reader: VTK 9.1 trusts the file's counts and crashed (a NumberOfPolys
// larger than the data, a negative one), aborted (NumberOfComponents="-3") or hung
// (NumberOfComponents="2000000000") on tampered files before any check could run. Every
// count is compared with the values actually present, every index with what it indexes, and
// no allocation follows a declared size. Binary and appended data (ParaView's default) are
// refused with a message: their block headers would need the same distrust.
#include <expat.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <type_traits>

#include "geometry/validation.h"  // kMaxCoordinate
#include "util/errors.h"
#include "util/format.h"
#include "viewer/run_folder.h"

namespace radkit::viewer {

namespace {

const char* const kFix = "write the folder again with `radkit run --out DIR`";

std::string fmt(double v) { return formatNumber(v); }

/// A DataArray the reader keeps: its attributes and ASCII text.
struct ArrayText {
  std::string type, format;
  long long components = 1;
  std::string text;
};

/// What the SAX handlers collect. Only the arrays the viewer needs keep their text.
struct VtpParse {
  std::string path, error;  ///< error: set to stop the parse with that message
  XML_Parser parser = nullptr;
  std::vector<std::string> open;  ///< element names from the root
  int pieces = 0;
  long long points = -1, polys = -1, others = 0;  ///< Piece counts; others: verts, lines, strips
  std::map<std::string, ArrayText> arrays;  ///< "points", "connectivity", "offsets", cell arrays
  ArrayText* current = nullptr;             ///< the array whose text is being read

  void stop(const std::string& message) {
    if (error.empty()) error = message;
    XML_StopParser(parser, XML_FALSE);
  }
};

const char* attribute(const char** attrs, const char* name) {
  for (int k = 0; attrs[k]; k += 2)
    if (std::strcmp(attrs[k], name) == 0) return attrs[k + 1];
  return nullptr;
}

/// A whole non-negative count attribute; -1 when absent, -2 when not one.
long long wholeCount(const char* text) {
  if (!text) return -1;
  char* end = nullptr;
  errno = 0;
  const long long v = std::strtoll(text, &end, 10);
  while (*end == ' ') ++end;
  return end == text || *end != '\0' || errno == ERANGE || v < 0 ? -2 : v;
}

const std::vector<std::string> kCellArrays = {"surface", "area", "reflectance", "emission",
                                              "radiosity"};

void XMLCALL startElement(void* data, const XML_Char* name, const XML_Char** attrs) {
  auto& s = *static_cast<VtpParse*>(data);
  const std::string parent = s.open.empty() ? "" : s.open.back();
  const std::string element = name;
  s.open.push_back(element);
  if (s.open.size() == 1) {
    const char* type = attribute(attrs, "type");
    if (element != "VTKFile" || !type || std::string(type) != "PolyData")
      return s.stop("not a VTK XML PolyData file (no <VTKFile type=\"PolyData\">)");
    if (attribute(attrs, "compressor"))
      return s.stop(
          "holds compressed binary data; the viewer reads the ASCII radiosity.vtp radkit "
          "writes. Fix: " +
          std::string(kFix) + " (or save it from ParaView as ASCII)");
    return;
  }
  if (element == "AppendedData")
    return s.stop(
        "holds appended binary data; the viewer reads the ASCII radiosity.vtp radkit "
        "writes. Fix: " +
        std::string(kFix) + " (or save it from ParaView as ASCII)");
  if (element == "Piece" && parent == "PolyData" && s.open.size() == 3) {
    if (++s.pieces > 1) return s.stop("holds more than one Piece; radkit writes one");
    s.points = wholeCount(attribute(attrs, "NumberOfPoints"));
    s.polys = wholeCount(attribute(attrs, "NumberOfPolys"));
    if (s.points < 0 || s.polys < 0)
      return s.stop("Piece needs whole, non-negative NumberOfPoints and NumberOfPolys");
    for (const char* other : {"NumberOfVerts", "NumberOfLines", "NumberOfStrips"}) {
      const long long n = wholeCount(attribute(attrs, other));
      if (n == -2) return s.stop(std::string("Piece's ") + other + " is not a whole count >= 0");
      if (n > 0) s.others += n;
    }
    return;
  }
  if (element != "DataArray" || s.open.size() != 5 || s.open[1] != "PolyData" ||
      s.open[2] != "Piece")
    return;
  // <Piece><Points|Polys|CellData><DataArray>: the arrays the viewer reads; others are skipped.
  const char* named = attribute(attrs, "Name");
  std::string key;
  const bool polys = parent == "Polys" && named &&
                     (std::string(named) == "connectivity" || std::string(named) == "offsets");
  const bool cells = parent == "CellData" && named &&
                     std::find(kCellArrays.begin(), kCellArrays.end(), named) != kCellArrays.end();
  if (parent == "Points")
    key = "points";
  else if (polys || cells)
    key = named;
  if (key.empty()) return;
  if (s.arrays.count(key))
    return s.stop("has two arrays '" + key + "' (" + parent + "); radkit writes one");
  ArrayText& a = s.arrays[key];
  const char* type = attribute(attrs, "type");
  const char* format = attribute(attrs, "format");
  a.type = type ? type : "";
  a.format = format ? format : "";
  a.components = wholeCount(attribute(attrs, "NumberOfComponents"));
  if (a.components == -1) a.components = 1;
  if (a.components < 0)
    return s.stop("array '" + key + "': NumberOfComponents is not a whole count");
  if (a.format != "ascii")
    return s.stop("array '" + key + "' is in format '" + a.format +
                  "'; the viewer reads the ASCII radiosity.vtp radkit writes. Fix: " + kFix +
                  " (or save it from ParaView as ASCII)");
  static const char* const kTypes[] = {"Int8",   "UInt8", "Int16",  "UInt16",  "Int32",
                                       "UInt32", "Int64", "UInt64", "Float32", "Float64"};
  if (std::none_of(std::begin(kTypes), std::end(kTypes),
                   [&](const char* t) { return a.type == t; }))
    return s.stop("array '" + key + "' has type '" + a.type + "', not a number type");
  s.current = &a;
}

void XMLCALL endElement(void* data, const XML_Char*) {
  auto& s = *static_cast<VtpParse*>(data);
  if (s.open.size() == 5) s.current = nullptr;
  s.open.pop_back();
}

void XMLCALL characters(void* data, const XML_Char* text, int length) {
  auto& s = *static_cast<VtpParse*>(data);
  if (s.current && s.open.size() == 5) s.current->text.append(text, std::size_t(length));
}

/// The numbers of an array's text, each token read whole ("12abc" is refused).
std::vector<double> numbers(const VtpParse& s, const std::string& key) {
  const ArrayText& a = s.arrays.at(key);
  std::vector<double> v;
  const char* p = a.text.c_str();
  while (true) {
    while (*p == ' ' || *p == '\n' || *p == '\r' || *p == '\t') ++p;
    if (!*p) break;
    char* end = nullptr;
    const double x = std::strtod(p, &end);
    if (end == p || (*end && !std::strchr(" \n\r\t", *end)))
      throw InputError(s.path + ": array '" + key + "': value " + std::to_string(v.size()) + " '" +
                       std::string(p, std::min<std::size_t>(std::strcspn(p, " \n\r\t"), 40)) +
                       "' is not a number. Fix: " + kFix);
    v.push_back(x);
    p = end;
  }
  return v;
}

/// The values of an array that must hold `tuples` × `components` numbers.
std::vector<double> tuples(const VtpParse& s, const std::string& key, long long tuples,
                           long long components, const std::string& what) {
  if (!s.arrays.count(key))
    throw InputError(s.path + ": no " + what +
                     (key == "radiosity" ? " (radkit mesh writes patches.vtp without radiosity; "
                                           "view the folder of `radkit run`)"
                                         : ". Fix: " + std::string(kFix)));
  if (s.arrays.at(key).components != components)
    throw InputError(s.path + ": " + what + " must have " + std::to_string(components) +
                     " component(s) per " + (key == "points" ? "point" : "patch") +
                     ", not NumberOfComponents=" + std::to_string(s.arrays.at(key).components));
  std::vector<double> v = numbers(s, key);
  if (double(v.size()) != double(tuples) * double(components))
    throw InputError(s.path + ": " + what + " holds " + std::to_string(v.size()) +
                     " numbers; the Piece's count needs " + std::to_string(tuples) + " × " +
                     std::to_string(components) + ". Fix: " + kFix);
  return v;
}

std::string patchError(const std::string& path, long long i, const std::string& what) {
  return path + ": patch " + std::to_string(i) + " " + what + ". Fix: " + kFix;
}

}  // namespace

PatchData readPatchesVtp(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec))
    throw InputError(path + ": missing; `radkit run --out DIR` writes radiosity.vtp into DIR");
  if (!std::filesystem::is_regular_file(path, ec))  // a FIFO would block the read
    throw InputError(path + ": is not a regular file (a folder, pipe or device). Fix: " + kFix);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot be opened. Fix: " + kFix);

  VtpParse s;
  s.path = path;
  std::unique_ptr<std::remove_pointer_t<XML_Parser>, void (*)(XML_Parser)> parser(
      XML_ParserCreate(nullptr), XML_ParserFree);
  if (!parser) throw std::bad_alloc();
  s.parser = parser.get();
  XML_SetUserData(s.parser, &s);
  XML_SetElementHandler(s.parser, startElement, endElement);
  XML_SetCharacterDataHandler(s.parser, characters);
  std::vector<char> chunk(1 << 16);
  bool last = false;
  while (!last) {
    in.read(chunk.data(), std::streamsize(chunk.size()));
    last = in.gcount() < std::streamsize(chunk.size());
    if (XML_Parse(s.parser, chunk.data(), int(in.gcount()), last) != XML_STATUS_OK) {
      if (!s.error.empty()) throw InputError(path + ": " + s.error);
      throw InputError(path + ": not a readable VTK XML PolyData file: " +
                       XML_ErrorString(XML_GetErrorCode(s.parser)) + " at line " +
                       std::to_string(XML_GetCurrentLineNumber(s.parser)) + ". Fix: " + kFix);
    }
  }
  if (s.pieces == 0)
    throw InputError(
        path + ": not a readable VTK XML PolyData file (no Piece). Fix: " + std::string(kFix));
  if (s.others > 0)
    throw InputError(path + ": holds vertices, lines or strips; radkit patches are polygons only");
  if (s.points == 0 || s.polys == 0)
    throw InputError(path +
                     ": not a readable VTK XML PolyData file (no points or no patches). "
                     "Fix: " +
                     std::string(kFix));

  PatchData p;
  const std::vector<double> xyz = tuples(s, "points", s.points, 3, "Points array");
  p.points.resize(std::size_t(s.points));
  for (std::size_t i = 0; i < p.points.size(); ++i) {
    p.points[i] = {xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]};
    // The scenes' own bound: the views' camera and bounds arithmetic stay finite.
    if (!isFinite(p.points[i]) || std::max({std::fabs(p.points[i].x), std::fabs(p.points[i].y),
                                            std::fabs(p.points[i].z)}) > kMaxCoordinate)
      throw InputError(path + ": point " + std::to_string(i) +
                       " is not finite or lies beyond ±1e15. Fix: " + kFix);
  }

  // offsets: where each polygon's corners end in connectivity (VTK's layout, without the 0).
  const std::vector<double> offsets = tuples(s, "offsets", s.polys, 1, "Polys offsets array");
  if (!s.arrays.count("connectivity"))
    throw InputError(path + ": no Polys connectivity array. Fix: " + std::string(kFix));
  const std::vector<double> ids = numbers(s, "connectivity");
  double begin = 0;
  p.polygons.resize(std::size_t(s.polys));
  for (std::size_t i = 0; i < offsets.size(); ++i) {
    const double corners = offsets[i] - begin;
    if (!(corners == 3 || corners == 4) || offsets[i] > double(ids.size()))
      throw InputError(patchError(path, long(i),
                                  "has offset " + fmt(offsets[i]) + " after " + fmt(begin) +
                                      " among " + std::to_string(ids.size()) +
                                      " connectivity ids; patches are triangles or quads"));
    for (auto k = std::size_t(begin); k < std::size_t(offsets[i]); ++k) {
      const double id = ids[k];
      if (!(id >= 0 && id < double(s.points) && id == std::floor(id)))
        throw InputError(patchError(path, long(i),
                                    "names point " + fmt(id) + ", but the file has " +
                                        std::to_string(s.points) + " points"));
      p.polygons[i].push_back(int(id));
    }
    begin = offsets[i];
  }
  if (begin != double(ids.size()))
    throw InputError(path + ": the connectivity array holds " + std::to_string(ids.size()) +
                     " ids, but the offsets end at " + fmt(begin) + ". Fix: " + kFix);

  const std::size_t n = std::size_t(s.polys);
  const std::vector<double> surface = tuples(s, "surface", s.polys, 1, "cell array 'surface'");
  const std::vector<double> area = tuples(s, "area", s.polys, 1, "cell array 'area'");
  const std::vector<double> rho = tuples(s, "reflectance", s.polys, 3, "cell array 'reflectance'");
  const std::vector<double> e = tuples(s, "emission", s.polys, 3, "cell array 'emission'");
  const std::vector<double> b = tuples(s, "radiosity", s.polys, 3, "cell array 'radiosity'");
  auto triple = [](const std::vector<double>& v, std::size_t i) {
    return Vec3{v[3 * i], v[3 * i + 1], v[3 * i + 2]};
  };
  for (std::size_t i = 0; i < n; ++i) {
    // Converting NaN or 3e9 to int is undefined: checked as a double first. readRunFolder
    // checks the index against report.json's surfaces.
    if (!(surface[i] >= 0 && surface[i] <= 2147483647 && surface[i] == std::floor(surface[i])))
      throw InputError(patchError(
          path, long(i),
          "has surface index " + fmt(surface[i]) + ", not a whole number in [0, 2147483647]"));
    p.surface.push_back(int(surface[i]));
    if (!(area[i] > 0 && std::isfinite(area[i])))
      throw InputError(
          patchError(path, long(i), "has area " + fmt(area[i]) + ", not a finite number > 0"));
    p.area.push_back(area[i]);
    const Vec3 r = triple(rho, i), em = triple(e, i), rad = triple(b, i);
    if (!(std::min({r.x, r.y, r.z}) >= 0 && maxComponent(r) <= 1))
      throw InputError(patchError(path, long(i), "has a reflectance outside [0, 1] (or NaN)"));
    if (!(std::min({em.x, em.y, em.z}) >= 0 && isFinite(em) && maxComponent(em) <= kMaxRadiosity))
      throw InputError(patchError(
          path, long(i),
          "has an emission that is negative, NaN or beyond " + fmt(kMaxRadiosity) + " W/m²"));
    if (!isFinite(rad) ||
        std::max({std::fabs(rad.x), std::fabs(rad.y), std::fabs(rad.z)}) > kMaxRadiosity)
      throw InputError(patchError(
          path, long(i),
          "has a radiosity that is NaN, infinite or beyond ±" + fmt(kMaxRadiosity) + " W/m²"));
    p.reflectance.push_back(r);
    p.emission.push_back(em);
    p.radiosity.push_back(rad);
  }
  return p;
}

}  // namespace radkit::viewer
