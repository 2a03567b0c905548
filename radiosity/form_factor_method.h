// FormFactorMethod: the interface every form-factor algorithm implements (Nori style: one
// header, one .cpp per method, a name table in form_factor_registry.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "geometry/patch_mesh.h"
#include "geometry/visibility.h"
#include "radiosity/quadrature.h"

namespace radkit {

enum class FormFactorPrecision { Double, Float };

/// Every setting of a form-factor run, with its default beside it. The CLI fills it once.
struct FormFactorSettings {
  std::string method = "point-polygon";  ///< --ff: a name from formFactorMethodNames()
  /// The method's own parameters, "key=value, ..." (--ff NAME:key=value;..., split by
  /// splitPluginChoice); each method
  /// reads its keys from Params and the registry refuses the keys it did not read.
  std::string parameters;
  int samples = 16;                 ///< --ff-samples K >= 1: rays / point pairs per pair
  std::uint64_t seed = 1;           ///< --seed: every stream derives from it
  bool enforceReciprocity = false;  ///< --ff-enforce reciprocity: A_iF_ij, A_jF_ji → mean
  FormFactorPrecision precision = FormFactorPrecision::Double;  ///< --ff-storage float
  std::size_t memoryBudget = std::size_t(8) << 30;              ///< --memory-budget, bytes
  QuadratureSettings quadrature;  ///< point-polygon's cubature over patch i
  bool cullUnblockable = true;    ///< point-polygon, monte-carlo: no rays for unblockable pairs
};

/// One computed entry of a row: F_ij and its standard error (0 for deterministic parts).
struct RowEntry {
  int column = 0;
  double value = 0;
  double standardError = 0;
};

/// The rules point-polygon counts: the adaptive contour and tensor levels 1..8.
constexpr int kPairRuleCount = 9;

/// What a method returns for row i, plus its work counters.
struct RowResult {
  std::vector<RowEntry> entries;  ///< non-zero entries only, columns ascending
  long long raysCast = 0;
  long long raysSaved = 0;         ///< rays not cast because nothing could block the pair
  long long pairsCulled = 0;       ///< facing pairs proven unblockable
  long long pairsFacing = 0;       ///< pairs that passed the facing test
  long long overlappingPairs = 0;  ///< coplanar pairs sharing area (coincident patches)
  long long quadraturePoints = 0;  ///< contour-formula evaluations
  long long kernelPoints = 0;      ///< point-to-point kernel evaluations of the tensor rules
  /// Pairs integrated by each rule: [0] the adaptive contour cubature, [n] the level-n
  /// tensor rule (pair_rule.h, levels 1..kMaxPairLevel = 8).
  long long pairsByRule[kPairRuleCount] = {};
  double raySeconds = 0;           ///< thread time spent casting (and sampling) rays
  double geometrySeconds = 0;      ///< thread time spent on everything else
  int firstOverlap[2] = {-1, -1};  ///< one overlapping pair, for the report
  void clear();
};

/// Which entries computeRow produces.
enum class RowCoverage {
  UpperTriangle,  ///< j > i only; F_ji = F_ij A_i/A_j by reciprocity
  FullRow         ///< every j
};

/// Abstract form-factor algorithm. Instances are immutable after construction and
/// computeRow is thread-safe; results depend only on (settings.seed, i, j).
class FormFactorMethod {
 public:
  virtual ~FormFactorMethod() = default;
  /// \brief Registry name ("point-polygon", ...).
  virtual std::string name() const = 0;
  /// \brief One line with the method and its parameters, for report.json.
  virtual std::string describe() const = 0;
  /// \brief Which entries computeRow fills.
  virtual RowCoverage coverage() const = 0;
  /// \brief Computes row i (see coverage()); out is cleared first.
  virtual void computeRow(int i, RowResult& out) const = 0;
};

/// \brief Creates the method registered under settings.method. The mesh and visibility must
/// outlive it. Throws std::invalid_argument for an unknown name (listing the known ones) or
/// for invalid settings (K < 1, ...).
std::unique_ptr<FormFactorMethod> makeFormFactorMethod(const PatchMesh& mesh,
                                                       const Visibility& visibility,
                                                       const FormFactorSettings& settings);

/// What the rest of radkit knows of a method without building it: its registry row's
/// behaviour, so that no caller compares method names.
struct FormFactorMethodTraits {
  /// K when --ff-samples is not given.
  int defaultSamples = 16;
  /// The K the study tries (radkit study's form-factor knob).
  std::vector<int> studySamples;
  /// The study's cost model: work in the method's own units for n patches at K samples, and
  /// the rate of those units per second before any run of the method is measured.
  double (*work)(double n, int samples) = nullptr;
  double workPerSecond = 5e6;
  /// K is the whole row's ray budget rather than per pair, so F's rows carry sampling noise
  /// that the run estimates from the gathered light and warns about.
  bool rowBudget = false;
  /// The method integrates pairs by the cubature rules of pair_rule.h and counts them.
  bool countsPairRules = false;
};

/// \brief The traits of a registered method; throws std::invalid_argument for an unknown name.
const FormFactorMethodTraits& formFactorTraits(const std::string& method);

/// \brief The registered names, default first.
std::vector<std::string> formFactorMethodNames();
/// \brief K for a method when --ff-samples is not given (each method has its own).
int defaultFormFactorSamples(const std::string& method);
/// \brief One help line per method: "name: summary (default K = N)".
std::vector<std::string> formFactorMethodHelp();

/// \brief Throws std::invalid_argument naming the flag when a setting is out of range.
void validateFormFactorSettings(const FormFactorSettings& settings);

}  // namespace radkit
