// Hierarchical radiosity with clustering as one call: the cluster tree over the input faces,
// link refinement against an error threshold ε, and the gather/push-pull solve, repeated from
// a coarse ε to the requested one (multigridding). The leaves come back as a PatchMesh, so
// every per-patch output of a dense run (patches.csv, radiosity.vtp, surfaces.csv, the image)
// is written by the same code.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "hierarchy/gather.h"
#include "radiosity/radiosity_pipeline.h"
#include "util/process_memory.h"

namespace radkit {

/// Smallest --epsilon: below it refinement stops only at --min-area, which takes far longer than
/// any run should (1e-7 ran past 40 s and 270 MB on the six-face furnace; 1e-300 was accepted).
constexpr double kMinEpsilon = 1e-6;

/// Sweeps the last round may take unless --max-iterations says otherwise. The dense solvers'
/// default (10⁸ steps over a small matrix) is no bound for a gather over 10⁵ links; this one
/// also makes an over-budget prediction (ConvergenceMonitor::overBudget) stop a closed box at
/// ρ = 0.999999 after a few hundred sweeps instead of millions.
constexpr long kDefaultHierarchicalSweeps = 100000;

/// Three quarters of the memory this process may use (availableMachineMemory()), leaving room
/// for the solve's arrays, which refinement does not count; 8 GiB where that is unknown.
std::size_t defaultHierarchicalMemoryBudget();

struct HierarchicalSettings {
  /// A link may carry an estimated error of at most ε times the power the scene emits.
  double epsilon = 1e-4;
  /// Elements are not split below this area (scene units²); 0: kDefaultMinAreaFraction of the
  /// scene's area.
  double minArea = 0;
  int raysPerLink = 16;  ///< K visibility rays per link
  /// Refine-and-solve rounds: ε·4^(rounds−1), …, 4ε, ε (each round warm-starts the next).
  int rounds = 3;
  GatherOrder order = GatherOrder::Jacobi;
  std::uint64_t seed = 1;
  /// Bytes the tree, its state and the links may reach while refining (the mesh and the ray
  /// scene included); default: defaultHierarchicalMemoryBudget().
  std::size_t memoryBudget = defaultHierarchicalMemoryBudget();
  /// With a sky: daylight estimated on every leaf element (and elements split where it varies,
  /// along sun shadow edges); false: once per input face, constant over its elements.
  bool elementDaylight = true;
  /// Keep the system's gather arrays and the ray scene in the result (checkLinks() needs
  /// them); false frees them before the results are assembled, which lowers the peak.
  bool keepGatherArrays = false;
  /// Tolerance on max|ΔB|/‖E‖∞ and the sweep limit of the last round.
  SolverSettings stopping = [] {
    SolverSettings s;
    s.maxIterations = kDefaultHierarchicalSweeps;
    return s;
  }();
};

/// The default smallest element, as a fraction of the scene's surface area.
constexpr double kDefaultMinAreaFraction = 2e-6;

/// \brief Throws std::invalid_argument naming the option when a setting is unusable.
void validateHierarchicalSettings(const HierarchicalSettings& s);

struct HierarchicalRound {
  double epsilon = 0;
  long long links = 0, leaves = 0, nodes = 0, rays = 0, sweeps = 0;
  double refineSeconds = 0, solveSeconds = 0;
};

struct HierarchicalResult {
  std::unique_ptr<Hierarchy> hierarchy;
  /// The links; its gather arrays only with HierarchicalSettings::keepGatherArrays.
  std::unique_ptr<HierarchicalSystem> system;
  /// Over the input faces; only with HierarchicalSettings::keepGatherArrays (else null).
  std::unique_ptr<RayScene> rays;
  PatchMesh leaves;              ///< leaf elements in output order (grouped by surface)
  std::vector<int> leafNodes;    ///< node of each leaf patch
  SourceState state;             ///< every node's radiosity (leaves solved, inner nodes pulled up)
  std::vector<Vec3> radiosity;   ///< B per leaf, W/m²
  std::vector<Vec3> irradiance;  ///< H per leaf, W/m²
  std::vector<double> rowSums;   ///< Σ_j F_ij of each leaf as the links see it
  std::vector<float> escape;  ///< 1 − Σ_j F_ij of each leaf from 32 rays, 1 024 on emitters (float:
                              ///< a ray count's fraction)
  std::vector<int> escapeRays;  ///< the rays behind each leaf's escape fraction
  /// Per surface: the share of its area whose leaves received no light at all.
  std::vector<double> zeroIrradianceShare;
  Vec3 escapedStandardError;  ///< of energy.escaped, W
  SolveResult solve;          ///< convergence of every round, one history
  std::vector<HierarchicalRound> rounds;
  std::array<long long, 4> linksByKind{};  ///< LinkKind order
  long long raysCast = 0;
  double minArea = 0;    ///< used (scene units²)
  double threshold = 0;  ///< τ = ε · emitted power of the last round
  /// The tree with every node's solve state; the links with the solver's arrays (landings,
  /// per-node sums).
  std::size_t hierarchyBytes = 0, linkBytes = 0;
  /// Memory after each stage: "input faces", "daylight" (with a sky), "hierarchy",
  /// "ray scene", "links and solve" (the rounds interleave them), "results".
  std::vector<StageMemory> memory;
  struct Seconds {
    double inputFaces = 0, hierarchy = 0, rayScene = 0, daylight = 0, refine = 0, solve = 0,
           results = 0;
  } seconds;
  std::vector<SurfaceResult> surfaces;
  EnergyBalance energy;
  /// With a sky: its model and the daylight of each leaf (daylight per element: indexed like
  /// `leaves`) or of each input face (per face: leaves take their face's).
  std::unique_ptr<SkyModel> sky;
  std::unique_ptr<Daylight> daylight;
  bool daylightPerLeaf = false;
  long long daylightSplits = 0;    ///< elements split because their daylight varied
  long long daylightElements = 0;  ///< elements whose daylight was estimated
};

/// \brief Solves a loaded scene. Throws std::invalid_argument for bad settings or a scene that
/// emits nothing, HierarchyMemoryError when the links outgrow settings.memoryBudget.
HierarchicalResult solveHierarchical(const Scene& scene, const HierarchicalSettings& settings,
                                     const PipelineLog& log = {});

/// \brief The same on input faces made elsewhere (tests): `base` has one patch per input face,
/// `surfaces` one entry per surface index.
/// `daylight`, when given, is each input face's daylight (W/m²): its ρ-fold is added to the
/// face's emission, so every face has radiometry of its own. `sky`, when given (and
/// settings.elementDaylight), lights every leaf element with daylight of its own instead
/// (`daylight` is then ignored): result.daylight holds the leaves' (docs/daylight.md).
HierarchicalResult solveHierarchical(PatchMesh base, std::vector<SurfaceRadiometry> surfaces,
                                     const HierarchicalSettings& settings,
                                     const PipelineLog& log = {},
                                     const std::vector<Vec3>* daylight = nullptr,
                                     const SkyModel* sky = nullptr);

/// "jacobi" or "gauss-seidel"; throws std::invalid_argument otherwise.
GatherOrder parseGatherOrder(const std::string& name);

}  // namespace radkit
