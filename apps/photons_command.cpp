// radkit photons: photon mapping (Jensen 1996) of a scene, compared with radiosity.
// Writes patches.csv, surfaces.csv, photonmap.png, caustics.png, comparison.csv,
// difference.png and report.json (docs/photon-mapping.md).
#include <cstdio>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "apps/common.h"
#include "apps/console.h"
#include "job/photons_job.h"

namespace radkit::app {

namespace {

using nlohmann::json;

struct PhotonsCommand {
  MeshOptions mesh;
  PhotonsJobSettings job;
  std::string filter = "epanechnikov";
  bool noRadiosity = false, noImage = false;
};

void printSummary(const PhotonsJobResult& r) {
  const json& rates = r.report["rates"];
  const json& photons = r.report["photons"];
  std::printf("\n");
  printField("scene", r.report["scene"]["name"].get<std::string>() + " (" +
                          r.report["scene"]["file"].get<std::string>() + ")");
  printField("photons", photons["emitted"].dump() + " emitted, " + photons["stored"].dump() +
                            " stored, " + photons["caustic"].dump() + " caustic, " +
                            fmt("%.3g photons/s", rates["photons_per_second"].get<double>()));
  printField("rays", fmt("%.3g/s tracing photons", rates["photon_rays_per_second"].get<double>()) +
                         fmt(", %.3g/s raw Embree",
                             rates["embree_closest_hit_rays_per_second"].get<double>()));
  for (const SurfaceEstimate& s : r.surfaces) {
    std::string line = fmt("%10.4f", s.radiosity.x) + fmt(" %10.4f", s.radiosity.y) +
                       fmt(" %10.4f W/m²", s.radiosity.z) +
                       fmt("  ± %.2g", luminance(s.radiosityError));
    for (const SurfaceComparison& c : r.comparison)
      if (c.name == s.name && luminance(c.radiosity) > 0)
        line += fmt("   radiosity %10.4f", luminance(c.radiosity)) +
                fmt(" (%+.2f %%)", 100 * (luminance(c.photon) / luminance(c.radiosity) - 1));
    printField(s.name, line);
  }
  printField("seconds", fmt("trace %.2f", r.report["seconds"]["trace"].get<double>()) +
                            fmt(", total %.2f", r.report["seconds"]["total"].get<double>()));
  printField("wrote", r.out);
}

}  // namespace

void addPhotonsCommand(CLI::App& app) {
  auto cmd = std::make_shared<PhotonsCommand>();
  CLI::App* sub = app.add_subcommand(
      "photons",
      "Photon mapping (Jensen): per-patch radiosity with standard errors, photonmap.png, "
      "caustics.png, and "
      "a comparison with the radiosity solution (comparison.csv, difference.png)");
  addMeshOptions(*sub, cmd->mesh, true);
  addCameraOption(*sub, cmd->job.camera);
  sub->add_option("--photons", cmd->job.settings.photons, "Photons emitted")
      ->check(CLI::Range(std::size_t(1), kMaxPhotons))
      ->capture_default_str();
  sub->add_option("--k", cmd->job.settings.neighbours,
                  "Photons in each irradiance estimate (k nearest)")
      ->check(CLI::Range(2, 100000))
      ->capture_default_str();
  sub->add_option("--filter", cmd->filter, "Density-estimation kernel")
      ->check(CLI::IsMember({"epanechnikov", "cone"}))
      ->capture_default_str();
  sub->add_option("--seed", cmd->job.settings.seed, "Random seed (photon i uses stream (seed, i))")
      ->check(Unsigned)
      ->capture_default_str();
  sub->add_option("--gather", cmd->job.settings.gatherRays,
                  "Final-gathering rays per pixel (0: show the map directly)")
      ->check(CLI::Range(0, 4096))
      ->capture_default_str();
  sub->add_option("--view", cmd->job.view,
                  "photonmap.png: final gathering or the global map itself")
      ->check(CLI::IsMember({"gather", "map"}))
      ->capture_default_str();
  addImageSizeOptions(*sub, cmd->job.imageWidth, cmd->job.imageHeight, "the images");
  auto* compare = sub->add_option(
      "--compare", cmd->job.compare,
      "A `radkit run` output folder to compare with (its surfaces.csv); default: solve "
      "radiosity on the same mesh here");
  sub->add_flag("--no-radiosity", cmd->noRadiosity, "Skip the comparison with radiosity")
      ->excludes(compare);
  sub->add_flag("--no-image", cmd->noImage,
                "Skip photonmap.png and caustics.png (and their gathering)");
  sub->add_option("--bench-rays", cmd->job.benchRays,
                  "Random rays timed for the raw Embree reference, and a hundredth as many "
                  "k-nearest queries (0: skip)")
      ->check(CLI::Range(0LL, 1000000000LL))
      ->capture_default_str();
  sub->add_option("--out", cmd->job.out, "Output folder")->required();
  sub->callback([cmd] {
    PhotonsJobSettings& job = cmd->job;
    job.scene = cmd->mesh.scene;
    job.load = cmd->mesh.load;
    if (cmd->mesh.maxArea > 0 || cmd->mesh.patches > 0)
      job.mesh = SubdivisionSettings{cmd->mesh.maxArea, cmd->mesh.patches};
    job.settings.filter =
        cmd->filter == "cone" ? IrradianceFilter::Cone : IrradianceFilter::Epanechnikov;
    job.radiosity = !cmd->noRadiosity;
    job.image = !cmd->noImage;
    Progress progress;
    const PipelineLog log = consoleLog(progress);
    printSummary(runPhotonsJob(job, log));
  });
}

}  // namespace radkit::app
