#include "output/run_files.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <type_traits>

#include <tbb/parallel_for.h>

#include "radiosity/form_factor_storage.h"
#include "radiosity/surface_form_factors.h"
#include "util/errors.h"         // InputError
#include "util/output_folder.h"  // writeFileAtomically, writeFileStreaming, csvField

namespace radkit {

namespace {
// Enough digits that a double read back is the same double.
constexpr int kDigits = 17;

void writeTriple(std::ostream& o, const Vec3& v) { o << ',' << v.x << ',' << v.y << ',' << v.z; }

/// Text of a double as `o << std::setprecision(kDigits) << x` writes it (printf's %.17g), by
/// std::to_chars: several times faster than the stream's printf, whose formatting was most of
/// the time a million-patch run spent writing its outputs.
void appendNumber(std::string& s, double x) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x, std::chars_format::general, kDigits);
  s.append(buf, r.ptr);
}
void appendNumber(std::string& s, long long x) {
  char buf[24];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  s.append(buf, r.ptr);
}
void appendNumber(std::string& s, int x) { appendNumber(s, static_cast<long long>(x)); }
/// x, y and z separated by `between`, after `before` unless it is '\0'.
void appendTriple(std::string& s, const Vec3& v, char before, char between) {
  if (before) s += before;
  appendNumber(s, v.x);
  s += between;
  appendNumber(s, v.y);
  s += between;
  appendNumber(s, v.z);
}

/// Writes rows [0, count) to `o` in order, formatting blocks of rows on every core: the text of
/// a block is made by `row(text, i)` appending row i, and at most a few blocks are held.
template <class Row>
void writeRows(std::ostream& o, std::size_t count, const Row& row) {
  constexpr std::size_t kBlock = 16384, kBlocks = 16;
  std::vector<std::string> text(kBlocks);
  for (std::size_t first = 0; first < count; first += kBlock * kBlocks) {
    const std::size_t blocks = std::min(kBlocks, (count - first + kBlock - 1) / kBlock);
    tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t b) {
      std::string& t = text[b];
      t.clear();
      const std::size_t end = std::min(count, first + (b + 1) * kBlock);
      for (std::size_t i = first + b * kBlock; i < end; ++i) row(t, i);
    });
    for (std::size_t b = 0; b < blocks; ++b)
      o.write(text[b].data(), std::streamsize(text[b].size()));
  }
}

}  // namespace

bool CsvReader::next(std::vector<std::string>& fields) {
  std::streambuf* buf = m_in.rdbuf();
  while (true) {
    fields.assign(1, std::string());
    m_recordLine = m_line;
    bool quoted = false, any = false, blank = true;
    int c;
    while ((c = buf->sbumpc()) != std::char_traits<char>::eof()) {
      any = true;
      if (c == '\n') ++m_line;
      if (c != '\r' && c != '\n') blank = false;
      if (quoted) {
        if (c != '"')
          fields.back() += char(c);  // commas, CR and LF included
        else if (buf->sgetc() == '"')
          fields.back() += '"', buf->sbumpc();
        else
          quoted = false;
      } else if (c == '"') {
        quoted = true;
      } else if (c == ',') {
        fields.emplace_back();
      } else if (c == '\n') {
        break;
      } else if (c != '\r') {  // CR of CRLF (a stray one outside quotes too)
        fields.back() += char(c);
      }
    }
    if (quoted)
      throw InputError(m_path + ":" + std::to_string(m_recordLine) +
                       ": a quoted field opened in this record is not closed before the end of "
                       "the file. Fix: close the quote (\"\" is a quote inside one), or write the "
                       "file again with radkit");
    if (!any) return false;
    if (!blank) return true;
    // A blank line (LF or CRLF alone): skipped, as the readers always did.
  }
}

std::vector<std::string> splitCsvLine(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> fields;
  try {
    if (CsvReader(in, "CSV line").next(fields)) return fields;
  } catch (const InputError&) {
    // An unclosed quote runs to the end of the line, as this function always read it.
  }
  return fields.empty() ? std::vector<std::string>(1) : fields;
}

void writePatchesCsv(const std::string& path, const Scene& scene, const PatchMesh& mesh,
                     const std::vector<Vec3>* radiosity) {
  const double m = scene.metresPerUnit();
  // Streamed to the file: at a million patches the text would be hundreds of MiB.
  writeFileStreaming(path, [&](std::ostream& o) {
    o << kPatchesCsvHeader << '\n';
    writeRows(o, mesh.patches.size(), [&](std::string& t, std::size_t i) {
      const Patch& p = mesh.patches[i];
      const Material& mat = scene.materials[scene.surfaces[p.surface].material];
      appendNumber(t, static_cast<long long>(i));
      t += ',';
      t += csvField(scene.surfaces[p.surface].name);
      t += ',';
      appendNumber(t, p.area * m * m);
      appendTriple(t, p.centroid * m, ',', ',');
      appendTriple(t, p.normal, ',', ',');
      appendTriple(t, mat.diffuseAlbedo(), ',', ',');
      appendTriple(t, mat.emission, ',', ',');
      appendTriple(t, radiosity ? (*radiosity)[i] : Vec3{}, ',', ',');
      t += '\n';
    });
  });
}

void writeSolutionCsv(const std::string& path, const Scene& scene, const PatchMesh& mesh,
                      const SolveResult& solve) {
  const std::vector<Vec3> b = toVec3(solve.radiosity);
  writePatchesCsv(path, scene, mesh, &b);
}

void writePatchesVtp(const std::string& path, const Scene& scene, const PatchMesh& mesh,
                     const std::vector<Vec3>* radiosity, const std::vector<CellArray>& extra) {
  writeFileStreaming(path, [&](std::ostream& o) {
    o << std::setprecision(kDigits);
    o << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n<PolyData>\n"
      << "<Piece NumberOfPoints=\"" << mesh.vertices.size() << "\" NumberOfPolys=\"" << mesh.size()
      << "\">\n"
      << "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    writeRows(o, mesh.vertices.size(), [&](std::string& t, std::size_t i) {
      appendTriple(t, mesh.vertices[i], '\0', ' ');
      t += '\n';
    });
    o << "</DataArray></Points>\n<Polys>\n<DataArray type=\"Int64\" Name=\"connectivity\" "
         "format=\"ascii\">\n";
    writeRows(o, mesh.patches.size(), [&](std::string& t, std::size_t i) {
      const Patch& p = mesh.patches[i];
      for (int k = 0; k < p.vertexCount; ++k) appendNumber(t, p.vertex[k]), t += ' ';
      t += '\n';
    });
    o << "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
    std::vector<long long> offsets(mesh.patches.size());
    long long offset = 0;
    for (std::size_t i = 0; i < offsets.size(); ++i)
      offsets[i] = offset += mesh.patches[i].vertexCount;
    writeRows(o, offsets.size(), [&](std::string& t, std::size_t i) {
      appendNumber(t, offsets[i]);
      t += '\n';
    });
    o << "</DataArray>\n</Polys>\n<CellData Scalars=\"surface\">\n";
    o << "<DataArray type=\"Int32\" Name=\"surface\" format=\"ascii\">\n";
    writeRows(o, mesh.patches.size(), [&](std::string& t, std::size_t i) {
      appendNumber(t, mesh.patches[i].surface);
      t += '\n';
    });
    o << "</DataArray>\n<DataArray type=\"Float64\" Name=\"area\" format=\"ascii\">\n";
    writeRows(o, mesh.patches.size(), [&](std::string& t, std::size_t i) {
      appendNumber(t, mesh.patches[i].area);
      t += '\n';
    });
    o << "</DataArray>\n";
    auto triples = [&](const char* name, auto value) {
      o << "<DataArray type=\"Float64\" Name=\"" << name
        << "\" NumberOfComponents=\"3\" format=\"ascii\">\n";
      writeRows(o, mesh.patches.size(), [&](std::string& t, std::size_t i) {
        appendTriple(t, value(static_cast<int>(i)), '\0', ' ');
        t += '\n';
      });
      o << "</DataArray>\n";
    };
    auto material = [&](int i) -> const Material& {
      return scene.materials[scene.surfaces[mesh.patches[i].surface].material];
    };
    triples("reflectance", [&](int i) { return material(i).diffuseAlbedo(); });
    triples("emission", [&](int i) { return material(i).emission; });
    if (radiosity) triples("radiosity", [&](int i) { return (*radiosity)[i]; });
    for (const CellArray& a : extra) {
      o << "<DataArray type=\"Float64\" Name=\"" << a.name << "\" format=\"ascii\">\n";
      writeRows(o, a.values.size(), [&](std::string& t, std::size_t i) {
        appendNumber(t, a.values[i]);
        t += '\n';
      });
      o << "</DataArray>\n";
    }
    o << "</CellData>\n</Piece>\n</PolyData>\n</VTKFile>\n";
  });
}

void writeSurfacesCsv(const std::string& path, const Scene& scene,
                      const std::vector<SurfaceResult>& results, bool photometric) {
  (void)scene;  // SurfaceResult areas are in m² already
  namespace c = surfaces_csv;
  std::ostringstream o;
  o << std::setprecision(kDigits) << c::kSurface << ',' << c::kArea << ',' << c::kRadiosity[0]
    << ',' << c::kRadiosity[1] << ',' << c::kRadiosity[2];
  // Daylight's answer is illuminance (lux): a sky scene always has the photometric columns.
  const bool daylit = !results.empty() && results.front().daylit;
  photometric = photometric || daylit;
  if (photometric) o << ',' << c::kLuminance << ',' << c::kIlluminance;
  if (daylit) o << ',' << c::kSkyViewFactor << ',' << c::kDaylightIlluminance;
  o << '\n';
  for (const SurfaceResult& r : results) {
    o << csvField(r.name) << ',' << r.area;
    writeTriple(o, r.radiosity);
    if (photometric) o << ',' << r.luminance << ',' << r.illuminance;
    if (daylit) o << ',' << r.skyViewFactor << ',' << r.daylightIlluminance;
    o << '\n';
  }
  writeFileAtomically(path, o.str());
}

std::vector<SurfaceRadiosity> readSurfacesCsv(const std::string& path) {
  namespace c = surfaces_csv;
  // Opening a FIFO blocks until a writer comes; a folder or device is no CSV either.
  std::error_code ec;
  if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec))
    throw InputError(path +
                     ": is not a regular file (a folder, pipe or device). Fix: give the folder "
                     "of a `radkit run` (it holds surfaces.csv)");
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw std::runtime_error(
        path + ": cannot open. Fix: give the folder of a `radkit run` (it holds surfaces.csv)");
  CsvReader csv(in, path);
  std::vector<std::string> header, f;
  csv.next(header);
  auto column = [&](const char* name) {
    const auto it = std::find(header.begin(), header.end(), name);
    if (it == header.end())
      throw std::runtime_error(path + ": line 1 has no column " + name +
                               ". Fix: give the folder of a `radkit run` of this radkit version");
    return std::size_t(it - header.begin());
  };
  const std::size_t name = column(c::kSurface), area = column(c::kArea);
  const std::size_t rgb[3] = {column(c::kRadiosity[0]), column(c::kRadiosity[1]),
                              column(c::kRadiosity[2])};
  const std::size_t need = std::max({name, area, rgb[0], rgb[1], rgb[2]}) + 1;
  std::vector<SurfaceRadiosity> rows;
  while (csv.next(f)) {
    const long long number = csv.line();
    SurfaceRadiosity r;
    try {
      if (f.size() < need) throw std::invalid_argument("short");
      std::size_t used = 0;
      auto parse = [&](std::size_t k) {
        const double v = std::stod(f[k], &used);
        if (used != f[k].size() || !std::isfinite(v)) throw std::invalid_argument("not a number");
        return v;
      };
      r.name = f[name];
      r.area = parse(area);
      r.radiosity = {parse(rgb[0]), parse(rgb[1]), parse(rgb[2])};
    } catch (const std::exception&) {
      throw std::runtime_error(path + ": line " + std::to_string(number) +
                               " does not give a name and finite numbers in the columns of line "
                               "1. Fix: rerun `radkit run`");
    }
    rows.push_back(r);
  }
  return rows;
}

void writeConvergenceCsv(const std::string& path, const std::vector<SolveResult>& solves,
                         double metresPerUnit) {
  namespace c = convergence_csv;
  const double m2 = metresPerUnit * metresPerUnit;
  std::ostringstream o;
  o << std::setprecision(kDigits) << c::kSolver << ',' << c::kIteration << ',' << c::kSweeps << ','
    << c::kSeconds << ',' << c::kResidual << ',' << c::kUnshotPower << '\n';
  for (const SolveResult& s : solves)
    for (const HistoryRow& row : s.history)
      o << csvField(s.solver) << ',' << row.iteration << ',' << row.sweeps << ',' << row.seconds
        << ',' << row.residual << ',' << row.unshotPower * m2 << '\n';
  writeFileAtomically(path, o.str());
}

void writeComparisonCsv(const std::string& path, const std::vector<SurfaceComparison>& rows,
                        double metresPerUnit) {
  const double m2 = metresPerUnit * metresPerUnit;
  std::ostringstream o;
  o << std::setprecision(10) << "surface,area_m2";
  const std::pair<const char*, const char*> columns[] = {{"photon_b", "_W_m2"},
                                                         {"radiosity_b", "_W_m2"},
                                                         {"rel_diff", ""},
                                                         {"photon_se", "_W_m2"},
                                                         {"z", ""}};
  for (const auto& [col, unit] : columns)
    for (const char* ch : {"_r", "_g", "_b"}) o << ',' << col << ch << unit;
  o << '\n';
  for (const SurfaceComparison& r : rows) {
    o << csvField(r.name) << ',' << r.area * m2;
    for (const Vec3* v :
         {&r.photon, &r.radiosity, &r.relativeDifference, &r.photonError, &r.zScore})
      writeTriple(o, *v);
    o << '\n';
  }
  writeFileAtomically(path, o.str());
}

void writeSurfaceFormFactors(const std::string& path, const PatchMesh& mesh,
                             const std::vector<std::string>& names, const FormFactorMatrix& f) {
  DenseMatrix<double> s = surfaceFormFactors(mesh, f);
  if (int(names.size()) != s.rows())
    throw std::invalid_argument("writeSurfaceFormFactors: " + std::to_string(names.size()) +
                                " names for " + std::to_string(s.rows()) + " surfaces");
  std::ostringstream out;
  out << "from,to,F\n";
  char value[32];
  for (int a = 0; a < s.rows(); ++a)
    for (int b = 0; b < s.cols(); ++b) {
      std::snprintf(value, sizeof value, "%.10g", s(a, b));
      out << csvField(names[a]) << ',' << csvField(names[b]) << ',' << value << '\n';
    }
  writeFileAtomically(path, out.str());
}

void writeMatrixMarket(const std::string& path, const FormFactorMatrix& f,
                       const std::vector<std::string>& comments) {
  const bool single = f.index() == 1 || f.index() == 3;
  std::size_t nonZeros = 0;
  forEachNonZero(f, [&](int, int, double) { ++nonZeros; });
  // Streamed: at 5 400 patches the text is 789 MB, and building it in memory peaked at 1.7 GiB.
  writeFileStreaming(path, [&](std::ostream& out) {
    out << "%%MatrixMarket matrix coordinate real general\n";
    for (const std::string& c : comments) out << "% " << c << "\n";
    const int n = matrixSize(f);
    out << n << " " << n << " " << nonZeros << "\n";
    // to_chars: the shortest text that reads back to the same value, several times faster
    // than printf's %.17g, which dominated the write.
    char line[80];
    forEachNonZero(f, [&](int i, int j, double v) {
      char* p = std::to_chars(line, line + 16, i + 1).ptr;
      *p++ = ' ';
      p = std::to_chars(p, p + 16, j + 1).ptr;
      *p++ = ' ';
      p = single ? std::to_chars(p, line + 78, float(v)).ptr : std::to_chars(p, line + 78, v).ptr;
      *p++ = '\n';
      out.write(line, p - line);
    });
  });
}

namespace {

template <typename T>
void putLittleEndian(std::ostream& out, T value) {
  static_assert(std::is_trivially_copyable_v<T>);
  unsigned char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  if constexpr (__BYTE_ORDER__ == __ORDER_BIG_ENDIAN__) std::reverse(bytes, bytes + sizeof(T));
  out.write(reinterpret_cast<const char*>(bytes), sizeof(T));
}

/// An array at once (one write per row, not per number) on little-endian machines.
template <typename T>
void putArray(std::ostream& out, const std::vector<T>& a) {
  if constexpr (__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__)
    out.write(reinterpret_cast<const char*>(a.data()), std::streamsize(a.size() * sizeof(T)));
  else
    for (const T& v : a) putLittleEndian(out, v);
}

}  // namespace

void writeFormFactorBinary(const std::string& path, const FormFactorMatrix& f) {
  const int n = matrixSize(f);
  long long nonZeros = 0;
  forEachNonZero(f, [&](int, int, double) { ++nonZeros; });
  writeFileStreaming(path, [&](std::ostream& out) {
    out.write(kFormFactorBinaryMagic, 8);
    putLittleEndian<std::int64_t>(out, n);
    putLittleEndian<std::int64_t>(out, nonZeros);
    std::vector<std::uint32_t> columns;
    std::vector<float> values;
    int row = 0;
    auto flush = [&] {
      if (2 * columns.size() > std::size_t(n)) {  // sparse would be larger: a dense row
        putLittleEndian<std::int32_t>(out, -1);
        std::vector<float> dense(n, 0.0f);
        for (std::size_t k = 0; k < columns.size(); ++k) dense[columns[k]] = values[k];
        putArray(out, dense);
      } else {
        putLittleEndian<std::int32_t>(out, std::int32_t(columns.size()));
        putArray(out, columns);
        putArray(out, values);
      }
      columns.clear(), values.clear();
      ++row;
    };
    forEachNonZero(f, [&](int i, int j, double v) {
      while (row < i) flush();
      columns.push_back(std::uint32_t(j));
      values.push_back(float(v));
    });
    while (row < n) flush();
  });
}

}  // namespace radkit
