// Surface-level form factors (the sums behind surface_formfactors.csv and the heat map).
#include "radiosity/surface_form_factors.h"

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

std::vector<std::string> surfaceNames(const Scene& scene) {
  std::vector<std::string> names;
  for (const Surface& s : scene.surfaces) names.push_back(s.name);
  return names;
}

}  // namespace radkit
