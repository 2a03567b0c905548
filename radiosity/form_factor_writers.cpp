// Matrix Market and CSV output of the form factors.
#include "radiosity/form_factor_writers.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

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
  std::string out = "%%MatrixMarket matrix coordinate real general\n";
  for (const std::string& c : comments) out += "% " + c + "\n";
  const int n = matrixSize(f);
  out += std::to_string(n) + " " + std::to_string(n) + " " + std::to_string(nonZeros) + "\n";
  out.reserve(out.size() + nonZeros * 32);
  char line[64];
  forEachNonZero(f, [&](int i, int j, double v) {
    std::snprintf(line, sizeof line, single ? "%d %d %.9g\n" : "%d %d %.17g\n", i + 1, j + 1, v);
    out += line;
  });
  writeFileAtomically(path, out);
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
