// Adaptive subdivision: solve on a coarse mesh, split the patches whose radiosity differs most
// from their neighbours' (and those a shadow boundary crosses), recompute, repeat.
#pragma once

#include <vector>

#include "geometry/patch_mesh.h"
#include "geometry/scene.h"
#include "radiosity/radiosity_pipeline.h"

namespace radkit {

class SkyModel;

/// When and where to refine. The starting mesh is PipelineSettings::mesh.
struct AdaptiveSettings {
  int maxPatches = 2000;  ///< patch budget: stop before a round would exceed it
  int maxRounds = 8;      ///< refine-and-solve rounds after the first solve
  /// Stop when no patch's indicator A_i·δ_i / Σ_k A_k Y(B_k) exceeds this (δ_i below).
  double tolerance = 1e-4;
  double splitFraction = 0.25;   ///< split at most this fraction of the patches per round
  bool shadowBoundaries = true;  ///< also split patches whose corners disagree on seeing an emitter
  int emitterPoints = 16;        ///< points per emitter surface used by the shadow test
  double minAreaFraction = 1e-6;  ///< never split a patch smaller than this × total area
};

/// One round: the mesh it solved on and what it decided.
struct AdaptiveRound {
  int patches = 0;
  double maxIndicator = 0;  ///< largest A_i·δ_i / Σ A_k Y(B_k)
  int shadowPatches = 0;    ///< patches a shadow boundary crosses
  int split = 0;            ///< patches split after this round (0 in the last)
  StageSeconds seconds;
};

struct AdaptiveResult {
  /// The last round: its mesh (T-junctions allowed, areas tile exactly), F, solution and
  /// results, as a uniform run returns them.
  PipelineResult final;
  std::vector<AdaptiveRound> rounds;
  std::string stopReason;
  double seconds = 0;  ///< wall clock of every round
};

/// \brief Refinement indicator per patch: A_i·δ_i / Σ_k A_k Y(B_k), with δ_i the largest
/// |Y(B_i) − Y(B_j)| over the neighbours j on the same surface (surfaceNeighbours), raised to
/// Y(B_i) when shadowed[i] (a shadow boundary can change B across the patch by all of its
/// direct part). Y = Rec. 709 luminance. Emitters get 0: their B is mostly E.
std::vector<double> refinementIndicator(const Scene& scene, const PatchMesh& mesh,
                                        const std::vector<Vec3>& radiosity,
                                        const std::vector<char>& shadowed);

/// \brief Marks patches crossed by a shadow boundary: for some point on an emitter, or for the
/// sun's centre when `sky` has a sun up, one corner of the patch (pulled 1e-3 toward the
/// centroid) sees it and another does not.
std::vector<char> shadowBoundaryPatches(const Scene& scene, const PatchMesh& mesh,
                                        const Visibility& visibility, int emitterPoints,
                                        const SkyModel* sky = nullptr);

/// \brief Solves on settings.mesh, then refines and re-solves until the indicator is below
/// adaptive.tolerance, the patch budget or maxRounds is reached. Form factors are recomputed
/// from scratch each round (settings.formFactors); the first of settings.solvers solves.
/// Throws what runPipeline throws.
AdaptiveResult solveAdaptive(const Scene& scene, const PipelineSettings& settings,
                             const AdaptiveSettings& adaptive, const PipelineLog& log = {});

}  // namespace radkit
