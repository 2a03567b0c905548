// Matrix Market and CSV output of the form factors.
#include "radiosity/form_factor_writers.h"

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <type_traits>

#include "radiosity/form_factor_storage.h"
#include "util/output_folder.h"

namespace radkit {

DenseMatrix<double> surfaceFormFactors(const PatchMesh& mesh, const FormFactorMatrix& f) {
  const int surfaces = mesh.surfaceBegin.empty() ? 0 : int(mesh.surfaceBegin.size()) - 1;
  DenseMatrix<double> s(surfaces);
  std::vector<double> area(surfaces, 0.0);
  for (const Patch& p : mesh.patches) area[p.surface] += p.area;
  forEachNonZero(f, [&](int i, int j, double fij) {
    const Patch& pi = mesh.patches[i];
    s(pi.surface, mesh.patches[j].surface) += pi.area * fij;
  });
  for (int a = 0; a < surfaces; ++a)
    for (int b = 0; b < surfaces; ++b) s(a, b) = area[a] > 0 ? s(a, b) / area[a] : 0.0;
  return s;
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

std::vector<std::string> surfaceNames(const Scene& scene) {
  std::vector<std::string> names;
  for (const Surface& s : scene.surfaces) names.push_back(s.name);
  return names;
}

}  // namespace radkit
