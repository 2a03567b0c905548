#include "apps/job_summary.h"

#include <cstdio>
#include <string>

#include "apps/common.h"
#include "apps/console.h"
#include "job/report.h"

namespace radkit::app {

void printDenseSummary(const JobResult& result, bool writeMatrix, bool photometric) {
  const Scene& scene = result.scene;
  const PipelineResult& r = *result.dense;
  const FormFactorDiagnostics& d = r.formFactors->diagnostics;
  std::printf("\n");
  printField("scene", scene.name + " (" + scene.file + ")");
  printField("patches", std::to_string(r.mesh.size()));
  printField("form factors", d.method + ", " + d.storage + ", " + std::to_string(d.raysCast) +
                                 " rays (" + std::to_string(d.raysSaved) + " saved), " +
                                 fmt("%.3g rays/s", d.raysPerSecond));
  printField("row sums", fmt("%.6f", d.rowSumMin) + " .. " + fmt("%.6f", d.rowSumMax) +
                             ", reciprocity error " + fmt("%.2e", d.maxRelativeReciprocityError) +
                             (r.formFactorNoise > 0 ? ", gathered-light noise " +
                                                          fmt("%.2g %%", 100 * r.formFactorNoise)
                                                    : ""));
  printField("seconds",
             "mesh " + fmt("%.2f", r.seconds.mesh) + ", rays " + fmt("%.2f", r.seconds.rayScene) +
                 ", form factors " + fmt("%.2f", r.seconds.formFactors) +
                 (r.daylight ? ", daylight " + fmt("%.2f", r.seconds.daylight) : "") + ", solve " +
                 fmt("%.2f", r.seconds.solve) + ", F files " + fmt("%.2f", result.matrixSeconds) +
                 (writeMatrix ? " (with .mtx)" : "") + ", total " + fmt("%.2f", result.seconds));
  if (r.daylight)
    printField("daylight", r.sky->typeName() + " sky" + (r.sky->hasSun() ? " and sun" : "") +
                               ", open horizontal " +
                               fmt("%.4g lux", kLumensPerWatt * luminance(r.sky->horizontalSky() +
                                                                          r.sky->horizontalSun())) +
                               ", " + std::to_string(r.daylight->rays) + " rays, sky noise " +
                               fmt("%.2g %%", 100 * r.daylight->skyNoise));
  for (const SolveResult& s : r.solves)
    printField(s.solver, std::to_string(s.iterations) + " iterations, residual " +
                             fmt("%.2e", s.checkedResidual) + ", " + fmt("%.3f s", s.seconds) +
                             (s.converged ? "" : "  NOT CONVERGED: " + s.reason));
  if (!r.solves.empty()) printEnergyAndSurfaces(r.energy, r.surfaces, photometric);
  printField("peak memory", fmt("%.0f MiB", peakMemoryBytes() / 1048576.0));
  printField("wrote", result.out);
}

void printHierarchicalSummary(const JobResult& result, double epsilon, bool photometric) {
  const Scene& scene = result.scene;
  const HierarchicalResult& r = *result.hierarchical;
  const double total = result.seconds;
  std::printf("\n");
  printField("scene", scene.name + " (" + scene.file + ")");
  printField("method", "hierarchical, epsilon " + fmt("%.3g", epsilon) + ", min area " +
                           fmt("%.3g", r.minArea) + " " + scene.units + "^2");
  printField("hierarchy", std::to_string(r.hierarchy->base().size()) + " input faces, " +
                              std::to_string(r.hierarchy->size()) + " nodes, " +
                              std::to_string(r.leaves.size()) + " leaves");
  long long links = 0;
  for (long long k : r.linksByKind) links += k;
  printField("links", std::to_string(links) + " (" + std::to_string(r.linksByKind[0]) +
                          " element-element), " + std::to_string(r.raysCast) + " rays");
  if (r.daylight)
    printField("daylight",
               r.sky->typeName() + " sky" + (r.sky->hasSun() ? " and sun" : "") + ", " +
                   std::to_string(r.daylight->rays) + " rays on " +
                   (r.daylightPerLeaf
                        ? std::to_string(r.daylightElements) + " elements, " +
                              std::to_string(r.daylightSplits) + " split where it varies"
                        : "the " + std::to_string(r.hierarchy->base().size()) + " input faces"));
  printField("seconds", "hierarchy " + fmt("%.2f", r.seconds.hierarchy) + ", rays " +
                            fmt("%.2f", r.seconds.rayScene) +
                            (r.daylight ? ", daylight " + fmt("%.2f", r.seconds.daylight) : "") +
                            ", links " + fmt("%.2f", r.seconds.refine) + ", solve " +
                            fmt("%.2f", r.seconds.solve) + ", total " + fmt("%.2f", total));
  printField(r.solve.solver, std::to_string(r.solve.iterations) + " sweeps, change " +
                                 fmt("%.2e", r.solve.residual) +
                                 (r.solve.converged ? "" : "  NOT CONVERGED: " + r.solve.reason));
  printEnergyAndSurfaces(r.energy, r.surfaces, photometric,
                         " ± " + fmt("%.2g", luminance(r.escapedStandardError)));
  printField("peak memory", fmt("%.0f MiB", peakMemoryBytes() / 1048576.0));
  printField("wrote", result.out);
}

}  // namespace radkit::app
