// The table of form-factor methods: the one place a name meets its constructor.
#include <stdexcept>

#include "radiosity/form_factor_method.h"
#include "util/params.h"
#include "util/setting_names.h"

namespace radkit {

// Factories, one per method .cpp (no headers: the registry is their only caller).
// Each reads its own parameters from `params`; the registry refuses the keys it did not read.
std::unique_ptr<FormFactorMethod> createPointPolygon(Params& params, const PatchMesh&,
                                                     const Visibility&, const FormFactorSettings&);
std::unique_ptr<FormFactorMethod> createMonteCarlo(Params& params, const PatchMesh&,
                                                   const Visibility&, const FormFactorSettings&);
std::unique_ptr<FormFactorMethod> createHemisphere(Params& params, const PatchMesh&,
                                                   const Visibility&, const FormFactorSettings&);

namespace {

// Work units of the study's cost model: point-polygon does its cubature (about 8 rays' worth)
// and K rays per facing pair, monte-carlo K rays per pair, hemisphere K rays per patch.
double pointPolygonWork(double n, int k) { return n * n * (8.0 + k); }
double pairSampleWork(double n, int k) { return n * n * double(k); }
double rowBudgetWork(double n, int k) { return n * k; }

struct MethodEntry {
  const char* name;
  const char* help;
  std::unique_ptr<FormFactorMethod> (*create)(Params&, const PatchMesh&, const Visibility&,
                                              const FormFactorSettings&);
  FormFactorMethodTraits traits;
};

// hemisphere's K rays are a whole row's budget, so it needs far more than the per-pair
// methods: 16 384 keeps the median patch's gathered light within 5 % standard error on the
// 4 000-patch Cornell box (16 gave 39 %, a patchwork).
const MethodEntry kMethods[] = {
    {"point-polygon",
     "Gauss-Legendre points on patch i, exact contour formula to patch j, visibility "
     "fraction from K rays (default)",
     createPointPolygon,
     {16, {1, 4, 16, 64}, pointPolygonWork, 2.4e7, false, true}},
    {"monte-carlo",
     "K uniform point pairs per patch pair (area-to-area), slow reference",
     createMonteCarlo,
     {16, {4, 16, 64, 256}, pairSampleWork, 5e6, false, false}},
    {"hemisphere",
     "K cosine-distributed rays per patch, counting first hits (ray-traced "
     "hemicube)",
     createHemisphere,
     {16384, {256, 1024, 4096, 16384}, rowBudgetWork, 5e6, true, false}},
};

const MethodEntry* findMethod(const std::string& name) {
  for (const MethodEntry& m : kMethods)
    if (name == m.name) return &m;
  return nullptr;
}

/// The entry called name; throws std::invalid_argument listing the known names otherwise.
const MethodEntry& methodEntry(const std::string& name) {
  if (const MethodEntry* m = findMethod(name)) return *m;
  std::string known;
  for (const MethodEntry& m : kMethods) known += std::string(" ") + m.name;
  throw std::invalid_argument("unknown form-factor method '" + name + "' (" + setting("ff") +
                              "); known:" + known);
}

}  // namespace

const FormFactorMethodTraits& formFactorTraits(const std::string& method) {
  return methodEntry(method).traits;
}

void validateFormFactorSettings(const FormFactorSettings& s) {
  if (s.samples < 1)
    throw std::invalid_argument(setting("ff_samples") + " must be at least 1 (got " +
                                std::to_string(s.samples) + ")");
  if (s.quadrature.order < 1 || s.quadrature.order > 16)
    throw std::invalid_argument("quadrature order must be in [1, 16] (got " +
                                std::to_string(s.quadrature.order) + ")");
  if (!(s.quadrature.tolerance > 0))
    throw std::invalid_argument("quadrature tolerance must be positive");
  if (s.quadrature.maxDepth < 0 || s.quadrature.maxDepth > 30)
    throw std::invalid_argument("quadrature depth must be in [0, 30]");
}

std::unique_ptr<FormFactorMethod> makeFormFactorMethod(const PatchMesh& mesh,
                                                       const Visibility& visibility,
                                                       const FormFactorSettings& settings) {
  validateFormFactorSettings(settings);
  const MethodEntry& m = methodEntry(settings.method);
  try {
    Params params = Params::parse(settings.parameters);
    std::unique_ptr<FormFactorMethod> method = m.create(params, mesh, visibility, settings);
    params.rejectUnused(m.name);
    return method;
  } catch (const ParamError& e) {
    throw ParamError(std::string("form-factor method \"") + m.name + "\": " + e.what());
  }
}

std::vector<std::string> formFactorMethodNames() {
  std::vector<std::string> names;
  for (const MethodEntry& m : kMethods) names.emplace_back(m.name);
  return names;
}

int defaultFormFactorSamples(const std::string& method) {
  const MethodEntry* m = findMethod(method);
  return m ? m->traits.defaultSamples
           : FormFactorSettings{}.samples;  // unknown names are refused by makeFormFactorMethod
}

std::vector<std::string> formFactorMethodHelp() {
  std::vector<std::string> lines;
  for (const MethodEntry& m : kMethods)
    lines.push_back(std::string(m.name) + ": " + m.help +
                    " (default K = " + std::to_string(m.traits.defaultSamples) + ")");
  return lines;
}

void RowResult::clear() { *this = RowResult{}; }

}  // namespace radkit
