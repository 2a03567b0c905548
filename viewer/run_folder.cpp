// Parsers of a run folder: report.json, formfactors.bin and .mtx, convergence.csv,
// surfaces.csv (output/run_files.h's CsvReader) and links.png (stb_image).
#include "viewer/run_folder.h"

#include <stb/stb_image.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "geometry/validation.h"  // kMaxCoordinate
#include "output/run_files.h"
#include "render/hdr_io.h"
#include "util/errors.h"
#include "util/format.h"

namespace radkit::viewer {

namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw InputError(path + ": " + what);
}

[[noreturn]] void failLine(const std::string& path, long long line, const std::string& what) {
  fail(path + ":" + std::to_string(line), what);
}

/// Refuses a path that is not a regular file after symlinks are followed, before anything
/// opens it: opening a FIFO blocks until a writer comes, and a device may never end.
void requireRegular(const std::string& path, const std::string& fix) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    fail(path, "is not a regular file (a folder, pipe or device). Fix: " + fix);
}

/// Whether an optional file of the folder is there: missing is false, anything there that is
/// not a regular file is refused.
bool present(const std::string& path, const std::string& fix) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return false;
  requireRegular(path, fix);
  return true;
}

/// Form factors lie in [0, 1]; far beyond that a value is corruption, and the views' colour
/// scales (log10 of sums over patch pairs) would overflow to infinity.
constexpr double kMaxFormFactor = 1e6;

std::string notAFormFactor(double v) {
  return "a value " + formatNumber(v) + " that is no form factor (they lie in [0, 1])";
}

const char* const kRewrite = "write the folder again with `radkit run --out DIR`";

std::ifstream openOrFail(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::exists(path, ec)) requireRegular(path, kRewrite);
  std::ifstream in(path, std::ios::binary);
  if (!in)
    fail(path, "cannot be opened (missing or unreadable); write it with `radkit run --out DIR`");
  return in;
}

double toNumber(const std::string& text, const std::string& path, long long line,
                const std::string& column) {
  char* end = nullptr;
  errno = 0;
  double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || errno == ERANGE)
    failLine(path, line, "column '" + column + "': '" + text + "' is not a number");
  return v;
}

/// A CSV file as a header and rows of fields, each row checked to have the header's width.
struct CsvTable {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  std::vector<long long> lines;  ///< the line each row starts on (a quoted field may span lines)

  int column(const std::string& name, const std::string& path) const {
    auto it = std::find(header.begin(), header.end(), name);
    if (it == header.end()) fail(path, "header has no column '" + name + "'");
    return static_cast<int>(it - header.begin());
  }
};

CsvTable readCsv(const std::string& path) {
  std::ifstream in = openOrFail(path);
  CsvReader csv(in, path);
  CsvTable t;
  if (!csv.next(t.header)) fail(path, "is empty (expected a header line)");
  std::vector<std::string> fields;
  while (csv.next(fields)) {
    if (fields.size() != t.header.size())
      failLine(
          path, csv.line(),
          std::to_string(fields.size()) + " fields, header has " + std::to_string(t.header.size()));
    t.rows.push_back(fields);
    t.lines.push_back(csv.line());
  }
  return t;
}

Vec3 jsonVec3(const nlohmann::json& j, const std::string& path, const std::string& key) {
  if (!j.is_array() || j.size() != 3 || !j[0].is_number() || !j[1].is_number() || !j[2].is_number())
    fail(path, key + " must be an array of 3 numbers");
  const Vec3 v{j[0].get<double>(), j[1].get<double>(), j[2].get<double>()};
  // The scenes' coordinate bound: far beyond it VTK's camera arithmetic (squared distances)
  // overflows.
  if (!isFinite(v) || std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)}) > kMaxCoordinate)
    fail(path, key + " must be 3 finite numbers within ±1e15. Fix: " + kRewrite);
  return v;
}

}  // namespace

Bounds3 PatchData::bounds() const {
  Bounds3 b;
  for (const Vec3& p : points) b.extend(p);
  return b;
}

std::vector<double> FormFactorRows::row(int i) const {
  std::vector<double> r(n, 0.0);
  for (long long k = rowStart[i]; k < rowStart[i + 1]; ++k) r[column[k]] = value[k];
  return r;
}

double FormFactorRows::maxValue() const {
  return value.empty() ? 0.0 : *std::max_element(value.begin(), value.end());
}

std::string RunFolder::surfaceName(int patch) const {
  int s = patches.surface[patch];
  return s >= 0 && s < int(report.surfaces.size()) ? report.surfaces[s] : "#" + std::to_string(s);
}

RunReport readRunReport(const std::string& path) {
  std::ifstream in = openOrFail(path);
  nlohmann::json j;
  try {
    in >> j;
  } catch (const nlohmann::json::exception& e) {
    fail(path, std::string("is not valid JSON: ") + e.what());
  }
  if (!j.contains("scene") || !j["scene"].is_object()) fail(path, "has no \"scene\" object");
  const nlohmann::json& s = j["scene"];
  RunReport r;
  try {
    r.sceneName = s.value("name", "");
    r.sceneFile = s.value("file", "");
    r.units = s.value("units", "");
    r.surfaces = s.value("surfaces", std::vector<std::string>{});
  } catch (const nlohmann::json::exception& e) {
    fail(path, std::string("scene: ") + e.what());
  }
  if (s.contains("camera") && !s["camera"].is_null()) {
    const nlohmann::json& c = s["camera"];
    if (!c.is_object())
      fail(path, "scene.camera must be an object or null. Fix: " + std::string(kRewrite));
    Camera cam;
    cam.position = jsonVec3(c.value("position", nlohmann::json()), path, "scene.camera.position");
    cam.lookAt = jsonVec3(c.value("look_at", nlohmann::json()), path, "scene.camera.look_at");
    cam.up = jsonVec3(c.value("up", nlohmann::json()), path, "scene.camera.up");
    if (c.contains("fov_deg") && c["fov_deg"].is_number()) cam.fovDeg = c["fov_deg"].get<double>();
    if (!(cam.fovDeg > 0 && cam.fovDeg < 180))
      fail(path, "scene.camera.fov_deg must be in (0, 180)");
    r.camera = cam;
  }
  if (j.contains("sky_panorama") && !j["sky_panorama"].is_null()) {
    const nlohmann::json& p = j["sky_panorama"];
    if (!p.is_object() || !p.contains("file") || !p["file"].is_string() ||
        p["file"].get<std::string>() != "sky.pfm")
      fail(path, "sky_panorama must be an object whose \"file\" is \"sky.pfm\". Fix: " +
                     std::string(kRewrite));
    SkyFrame f;
    f.up = jsonVec3(p.value("up", nlohmann::json()), path, "sky_panorama.up");
    f.north = jsonVec3(p.value("north", nlohmann::json()), path, "sky_panorama.north");
    f.east = jsonVec3(p.value("east", nlohmann::json()), path, "sky_panorama.east");
    // VTK's skybox takes the frame as it is: it must be a right-handed orthonormal one.
    const double tolerance = 1e-6;
    if (std::fabs(length(f.up) - 1) > tolerance || std::fabs(length(f.north) - 1) > tolerance ||
        std::fabs(dot(f.up, f.north)) > tolerance ||
        length(cross(f.north, f.up) - f.east) > tolerance)
      fail(path,
           "sky_panorama's up, north and east are not a right-handed orthonormal frame "
           "(east = north × up). Fix: " +
               std::string(kRewrite));
    r.skyFrame = f;
  }
  return r;
}

SkyPanorama readSkyPanorama(const std::string& path) {
  requireRegular(path, kRewrite);
  RadianceImage image;
  try {
    image = readPfm(path);
  } catch (const std::runtime_error& e) {
    throw InputError(std::string(e.what()) + " (the run's sky panorama; " + kRewrite + ")");
  }
  if (image.width != 2 * image.height || image.width > kMaxSkySide)
    fail(path, "is " + std::to_string(image.width) + "×" + std::to_string(image.height) +
                   " pixels; a sky panorama is twice as wide as high and at most " +
                   std::to_string(kMaxSkySide) + " wide. Fix: " + kRewrite);
  for (const Vec3& v : image.radiance)
    if (maxComponent(v) > kMaxRadiosity)
      fail(path, "holds a radiance above " + formatNumber(kMaxRadiosity) + ". Fix: " + kRewrite);
  SkyPanorama p;
  p.width = image.width;
  p.height = image.height;
  p.radiance = std::move(image.radiance);
  return p;
}

FormFactorRows readFormFactorsMtx(const std::string& path) {
  std::ifstream in = openOrFail(path);
  std::string line;
  long long lineNo = 1;
  if (!std::getline(in, line) ||
      line.rfind("%%MatrixMarket matrix coordinate real general", 0) != 0)
    failLine(path, 1, "expected the header '%%MatrixMarket matrix coordinate real general'");
  while (std::getline(in, line) && (line.empty() || line[0] == '%')) ++lineNo;
  ++lineNo;
  long long rows = 0, cols = 0, entries = 0;
  if (!(std::istringstream(line) >> rows >> cols >> entries) || rows != cols || rows <= 0 ||
      entries < 0)
    failLine(path, lineNo, "expected the size line 'n n nonzeros' of a square matrix");
  // Counts are checked before allocating: "n n 4000000000" asked for 64 GB. An entry line has
  // at least 6 bytes ("1 1 0\n"); radkit meshes at most 10 000 000 patches.
  const std::uintmax_t bytes = std::filesystem::file_size(path);
  if (rows > 10000000 || entries > (long long)(bytes / 6) ||
      double(entries) > double(rows) * double(rows))
    failLine(
        path, lineNo,
        "the size line says " + std::to_string(rows) + " rows and " + std::to_string(entries) +
            " entries, more than a " + std::to_string(bytes) + "-byte file of at most " +
            "10000000 patches holds. Fix: write the file again with `radkit run --write-matrix`");
  std::vector<int> row(entries), col(entries);
  std::vector<double> val(entries);
  for (long long k = 0; k < entries; ++k) {
    ++lineNo;
    if (!std::getline(in, line))
      failLine(path, lineNo,
               "ends after " + std::to_string(k) + " of " + std::to_string(entries) + " entries");
    const char* p = line.c_str();
    char* end = nullptr;
    long i = std::strtol(p, &end, 10);
    long jj = std::strtol(end, &end, 10);
    val[k] = std::strtod(end, &end);
    if (i < 1 || i > rows || jj < 1 || jj > rows || !std::isfinite(val[k]))
      failLine(path, lineNo,
               "expected 'row column value' with 1 <= row, column <= " + std::to_string(rows));
    if (std::fabs(val[k]) > kMaxFormFactor)
      failLine(
          path, lineNo,
          notAFormFactor(val[k]) + ". Fix: write the file again with `radkit run --write-matrix`");
    row[k] = int(i - 1);
    col[k] = int(jj - 1);
  }
  // Counting sort by row: the writer's order is not part of the contract.
  FormFactorRows f;
  f.n = int(rows);
  f.rowStart.assign(rows + 1, 0);
  for (int r : row) ++f.rowStart[r + 1];
  for (long long r = 0; r < rows; ++r) f.rowStart[r + 1] += f.rowStart[r];
  std::vector<long long> next(f.rowStart.begin(), f.rowStart.end() - 1);
  f.column.resize(entries);
  f.value.resize(entries);
  for (long long k = 0; k < entries; ++k) {
    long long at = next[row[k]]++;
    f.column[at] = col[k];
    f.value[at] = val[k];
  }
  return f;
}

FormFactorRows readFormFactorsBin(const std::string& path) {
  // The layout is output/run_files.h's writeFormFactorBinary (little-endian).
  std::ifstream in = openOrFail(path);
  const std::uintmax_t bytes = std::filesystem::file_size(path);
  const std::string fix = ". Fix: write the folder again with `radkit run`";
  auto read = [&](void* to, std::size_t size, const char* what) {
    in.read(static_cast<char*>(to), std::streamsize(size));
    if (!in) fail(path, std::string("ends inside ") + what + fix);
  };
  char magic[8];
  read(magic, 8, "its header");
  if (std::string(magic, 8) != "RADKITF1")
    fail(path, "is not a radkit form-factor file (no 'RADKITF1' header)" + fix);
  std::int64_t n = 0, nonZeros = 0;
  read(&n, 8, "its header");
  read(&nonZeros, 8, "its header");
  // Checked before allocating: each row takes at least 4 bytes, each non-zero 8 (sparse) or
  // 4/n² of a dense row.
  if (n <= 0 || n > 10000000 || nonZeros < 0 || double(nonZeros) > double(n) * double(n) ||
      double(n) * 4 + 24 > double(bytes))
    fail(path, "header says " + std::to_string(n) + " patches and " + std::to_string(nonZeros) +
                   " non-zeros, more than a " + std::to_string(bytes) + "-byte file holds" + fix);
  FormFactorRows f;
  f.n = int(n);
  f.rowStart.assign(std::size_t(n) + 1, 0);
  f.column.reserve(std::size_t(std::min<std::int64_t>(nonZeros, std::int64_t(bytes / 4))));
  f.value.reserve(f.column.capacity());
  std::vector<std::uint32_t> columns;
  std::vector<float> values;
  for (std::int64_t i = 0; i < n; ++i) {
    std::int32_t k = 0;
    read(&k, 4, "a row");
    if (k == -1) {
      values.resize(std::size_t(n));
      read(values.data(), values.size() * 4, "a dense row");
      for (std::int64_t j = 0; j < n; ++j)
        if (values[j] != 0) f.column.push_back(int(j)), f.value.push_back(values[j]);
    } else {
      if (k < 0 || k > n)
        fail(path, "row " + std::to_string(i) + " says " + std::to_string(k) + " entries" + fix);
      columns.resize(std::size_t(k));
      values.resize(std::size_t(k));
      read(columns.data(), columns.size() * 4, "a row's columns");
      read(values.data(), values.size() * 4, "a row's values");
      for (std::int32_t e = 0; e < k; ++e) {
        if (columns[e] >= std::uint64_t(n) || (e > 0 && columns[e] <= columns[e - 1]))
          fail(path, "row " + std::to_string(i) + " has columns out of order or beyond " +
                         std::to_string(n) + fix);
        f.column.push_back(int(columns[e]));
        f.value.push_back(values[e]);
      }
    }
    f.rowStart[std::size_t(i) + 1] = static_cast<long long>(f.value.size());
  }
  for (double v : f.value) {
    if (!std::isfinite(v)) fail(path, "holds a value that is not a finite number" + fix);
    if (std::fabs(v) > kMaxFormFactor) fail(path, "holds " + notAFormFactor(v) + fix);
  }
  return f;
}

std::vector<SolverHistory> readConvergenceCsv(const std::string& path) {
  namespace c = convergence_csv;
  CsvTable t = readCsv(path);
  const int cSolver = t.column(c::kSolver, path), cIter = t.column(c::kIteration, path);
  const int cSec = t.column(c::kSeconds, path), cRes = t.column(c::kResidual, path);
  const int cUnshot = t.column(c::kUnshotPower, path);
  std::vector<SolverHistory> runs;
  for (std::size_t k = 0; k < t.rows.size(); ++k) {
    const auto& r = t.rows[k];
    const long long line = t.lines[k];
    const double it = toNumber(r[cIter], path, line, c::kIteration);
    if (!(it >= 0 && it <= 2147483647))  // converting NaN or 1e20 to int is undefined
      failLine(path, line, "column 'iteration': '" + r[cIter] + "' is not an iteration count >= 0");
    const int iteration = int(it);
    // A new block when the solver changes or its iteration count starts again.
    if (runs.empty() || runs.back().solver != r[cSolver] ||
        iteration <= runs.back().iteration.back())
      runs.push_back(SolverHistory{r[cSolver], {}, {}, {}, {}});
    SolverHistory& h = runs.back();
    h.iteration.push_back(iteration);
    h.seconds.push_back(toNumber(r[cSec], path, line, c::kSeconds));
    h.residual.push_back(toNumber(r[cRes], path, line, c::kResidual));
    h.unshotPower.push_back(toNumber(r[cUnshot], path, line, c::kUnshotPower));
  }
  return runs;
}

std::vector<SurfaceSummary> readSurfacesCsv(const std::string& path) {
  namespace c = surfaces_csv;
  CsvTable t = readCsv(path);
  const int cName = t.column(c::kSurface, path), cArea = t.column(c::kArea, path);
  int cB[3];
  for (int k = 0; k < 3; ++k) cB[k] = t.column(c::kRadiosity[k], path);
  auto optional = [&](const char* name) {
    auto it = std::find(t.header.begin(), t.header.end(), name);
    return it == t.header.end() ? -1 : int(it - t.header.begin());
  };
  const int cLum = optional(c::kLuminance), cLux = optional(c::kIlluminance);
  std::vector<SurfaceSummary> out;
  for (std::size_t k = 0; k < t.rows.size(); ++k) {
    const auto& r = t.rows[k];
    const long long line = t.lines[k];
    SurfaceSummary s;
    s.name = r[cName];
    s.area = toNumber(r[cArea], path, line, c::kArea);
    s.radiosity = {toNumber(r[cB[0]], path, line, c::kRadiosity[0]),
                   toNumber(r[cB[1]], path, line, c::kRadiosity[1]),
                   toNumber(r[cB[2]], path, line, c::kRadiosity[2])};
    if (cLum >= 0) s.luminance = toNumber(r[cLum], path, line, c::kLuminance);
    if (cLux >= 0) s.illuminance = toNumber(r[cLux], path, line, c::kIlluminance);
    out.push_back(s);
  }
  return out;
}

LinksImage readLinksPng(const std::string& path) {
  const std::string fix =
      "rerun `radkit run --method hierarchical` into this folder to write it again, or delete it";
  requireRegular(path, fix);
  // VTK 9.1's PNG reader crashed after libpng's error on a truncated file; stb_image returns
  // an error instead. The declared size is checked before decoding allocates for it.
  const std::uintmax_t bytes = std::filesystem::file_size(path);
  if (bytes > (std::uintmax_t(1) << 28))
    fail(path,
         "is " + std::to_string(bytes) + " bytes, more than a links image needs. Fix: " + fix);
  std::ifstream in = openOrFail(path);
  std::string data(static_cast<std::size_t>(bytes), '\0');
  in.read(data.data(), std::streamsize(bytes));
  if (!in) fail(path, "could not be read whole. Fix: " + fix);
  static const char kSignature[] = "\x89PNG\r\n\x1a\n";
  // Only the PNG decoder of stb_image runs, not its guesses at other formats.
  if (data.compare(0, 8, kSignature, 8) != 0) fail(path, "not a PNG image. Fix: " + fix);
  // The size as IHDR declares it (big-endian, right after the signature), checked here: stb
  // refuses more than 1 GB itself, but only as "unknown image type".
  if (data.size() < 24 || data.compare(12, 4, "IHDR") != 0)
    fail(path, "has no PNG header (IHDR chunk). Fix: " + fix);
  auto be32 = [&](std::size_t at) {
    std::uint32_t v = 0;
    for (std::size_t k = 0; k < 4; ++k) v = v << 8 | std::uint8_t(data[at + k]);
    return v;
  };
  const std::uint32_t declaredW = be32(16), declaredH = be32(20);
  if (declaredW < 1 || declaredH < 1 || declaredW > std::uint32_t(kMaxLinksSide) ||
      declaredH > std::uint32_t(kMaxLinksSide) ||
      std::uint64_t(declaredW) * declaredH > std::uint64_t(kMaxLinksPixels))
    fail(path, "declares " + std::to_string(declaredW) + "x" + std::to_string(declaredH) +
                   " pixels, more than a links image has (at most " +
                   std::to_string(kMaxLinksSide) + " a side, " + std::to_string(kMaxLinksPixels) +
                   " in all). Fix: " + fix);
  const auto* png = reinterpret_cast<const stbi_uc*>(data.data());
  const int size = int(data.size());
  int w = 0, h = 0, channels = 0;
  auto reason = [] {
    const char* r = stbi_failure_reason();
    return std::string(r ? r : "no reason given");
  };
  if (!stbi_info_from_memory(png, size, &w, &h, &channels))
    fail(path, "has no readable PNG header (" + reason() + "). Fix: " + fix);
  stbi_uc* pixels = stbi_load_from_memory(png, size, &w, &h, &channels, 3);
  if (!pixels) fail(path, "is damaged or truncated (" + reason() + "). Fix: " + fix);
  LinksImage image;
  image.width = w;
  image.height = h;
  image.rgb.assign(pixels, pixels + std::size_t(w) * h * 3);
  stbi_image_free(pixels);
  return image;
}

RunFolder readRunFolder(const std::string& folder) {
  namespace fs = std::filesystem;
  if (!fs::is_directory(folder))
    throw InputError(folder + ": no such run folder; create one with `radkit run --out " + folder +
                     "`");
  auto file = [&](const char* name) { return (fs::path(folder) / name).string(); };
  RunFolder run;
  run.path = folder;
  run.report = readRunReport(file("report.json"));
  run.patches = readPatchesVtp(file("radiosity.vtp"));
  // The views index report.json's surface names, the form factors' rows and columns and the
  // patch arrays with these; readPatchesVtp checked the arrays against each other.
  for (int i = 0; i < run.patches.size(); ++i)
    if (run.patches.surface[i] < 0 || run.patches.surface[i] >= int(run.report.surfaces.size()))
      fail(file("radiosity.vtp"), "patch " + std::to_string(i) + " has surface index " +
                                      std::to_string(run.patches.surface[i]) +
                                      ", but report.json lists " +
                                      std::to_string(run.report.surfaces.size()) + " surfaces");
  // The binary first: written by every run, smaller and faster to read than the text.
  const bool bin = present(file("formfactors.bin"), kRewrite);
  const std::string matrixFile = bin ? file("formfactors.bin") : file("formfactors.mtx");
  if (bin || present(matrixFile, "write it again with `radkit run --write-matrix`, or delete it")) {
    run.formFactors = bin ? readFormFactorsBin(matrixFile) : readFormFactorsMtx(matrixFile);
    if (run.formFactors->n != run.patches.size())
      fail(matrixFile, "is " + std::to_string(run.formFactors->n) + "×" +
                           std::to_string(run.formFactors->n) + " but radiosity.vtp has " +
                           std::to_string(run.patches.size()) +
                           " patches (files of different runs?)");
  } else {
    const bool links = present(file("links.png"),
                               "rerun `radkit run --method hierarchical` into "
                               "this folder to write it again, or delete it");
    run.formFactorsMissing =
        links ? "a hierarchical run has no F matrix: links.png draws its links as blocks of F"
              : "no formfactors.bin or formfactors.mtx (written by `radkit run` and "
                "`radkit formfactors`; `radkit solvers` writes neither: rerun with `radkit run`)";
    if (links) {
      run.linksImage = file("links.png");
      run.links = readLinksPng(run.linksImage);
    }
  }
  if (present(file("convergence.csv"), kRewrite))
    run.convergence = readConvergenceCsv(file("convergence.csv"));
  else
    run.convergenceMissing = "no convergence.csv in " + folder;
  if (present(file("surfaces.csv"), kRewrite)) run.surfaces = readSurfacesCsv(file("surfaces.csv"));
  // A run under a sky: drawn behind the patches when its panorama is there.
  if (run.report.skyFrame && present(file("sky.pfm"), kRewrite)) {
    run.sky = readSkyPanorama(file("sky.pfm"));
    run.sky->frame = *run.report.skyFrame;
  }
  return run;
}

}  // namespace radkit::viewer
