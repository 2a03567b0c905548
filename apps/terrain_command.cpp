// radkit terrain: a procedural landscape (ridged multifractal or fBm heightfield) written as
// meshes by material (grass, rock, snow by slope and height) and a scene file that puts them
// under a sky, ready for `radkit run` (docs/terrain.md).
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "apps/common.h"
#include "job/terrain_job.h"
#include "sky/sky_radiance.h"
#include "util/format.h"

namespace radkit::app {

namespace {

using nlohmann::json;

void printSummary(const TerrainJobResult& r) {
  const json& s = r.report["settings"];
  const json& counts = r.report["triangles_by_material"];
  printField("terrain", s["type"].get<std::string>() + ", seed " + s["seed"].dump() + ", " +
                            s["resolution"].dump() + "² vertices, " + r.report["triangles"].dump() +
                            " triangles");
  printField("materials", "grass " + counts["grass"].dump() + ", rock " + counts["rock"].dump() +
                              ", snow " + counts["snow"].dump() + " triangles");
  printField("seconds", formatNumber(r.report["seconds"]["generate"].get<double>()));
  if (r.report.contains("landscape")) {
    const json& l = r.report["landscape"];
    auto seconds = [&](const char* who) {
      return formatNumber(l[who]["seconds"].get<double>()) + " s (hits and shadows " +
             formatNumber(l[who]["visibility_thread_seconds"].get<double>()) + " thread-s)";
    };
    printField("landscape", "march " + seconds("march") + ", Embree " + seconds("embree") +
                                ", relative RMSE " +
                                formatNumber(l["relative_rmse"].get<double>()));
  }
  printField("wrote", r.out + "/terrain.json (run it: radkit run " + r.out + "/terrain.json)");
}

}  // namespace

void addTerrainCommand(CLI::App& app) {
  auto cmd = std::make_shared<TerrainJobSettings>();
  CLI::App* sub = app.add_subcommand(
      "terrain", "Generate a procedural landscape (meshes and a scene under a sky)");
  terrain::TerrainSettings& s = cmd->settings;
  sub->add_option("--type", cmd->type, "Noise: ridged (multifractal) or fbm")
      ->check(CLI::IsMember({"ridged", "fbm"}))
      ->capture_default_str();
  sub->add_option("--octaves", s.fractal.octaves, "Octaves of noise")
      ->check(CLI::Range(1, 24))
      ->capture_default_str();
  sub->add_option("--lacunarity", s.fractal.lacunarity, "Frequency ratio between octaves")
      ->check(FiniteRange(1.01, 16))
      ->capture_default_str();
  sub->add_option("--H", s.fractal.H, "Fractal increment: octave i weighs lacunarity^(-iH)")
      ->check(FiniteRange(0, 4))
      ->capture_default_str();
  sub->add_option("--gain", s.fractal.gain, "Ridged: how much a ridge damps finer octaves")
      ->check(FiniteRange(0, 16))
      ->capture_default_str();
  sub->add_option("--offset", s.fractal.offset, "Ridged: ridge height before squaring")
      ->check(FiniteRange(0, 4))
      ->capture_default_str();
  sub->add_option("--seed", s.fractal.seed, "Seed: the same seed gives the same terrain")
      ->capture_default_str();
  sub->add_option("--resolution", s.resolution, "Vertices along each side (2 triangles a cell)")
      ->check(CLI::Range(2, 4097))
      ->capture_default_str();
  sub->add_option("--size", s.size, "Metres along each side")
      ->check(FinitePositive)
      ->capture_default_str();
  sub->add_option("--height", s.height, "Metres from the lowest to the highest point")
      ->check(FiniteNonNegative)
      ->capture_default_str();
  sub->add_option("--feature-size", s.featureSize, "Metres: wavelength of the first octave")
      ->check(FinitePositive)
      ->capture_default_str();
  sub->add_option("--snow-line", s.snowLine, "Fraction of the height above which snow lies")
      ->check(FiniteRange(0, 1))
      ->capture_default_str();
  sub->add_option("--rock-slope", s.rockSlopeDeg, "Degrees: steeper faces are rock")
      ->check(FiniteRange(0, 90))
      ->capture_default_str();
  sub->add_option("--format", cmd->format, "Mesh files: obj or ply")
      ->check(CLI::IsMember({"obj", "ply"}))
      ->capture_default_str();
  sub->add_option("--sky", cmd->sky,
                  "The scene's sky: " + skyRegistry().namesText() +
                      ", with parameters as NAME:key=value;... (without them, 10 000 lux for the "
                      "uniform and CIE skies)")
      ->capture_default_str();
  sub->add_option("--sun-elevation", cmd->sunElevation, "Physical sky: sun elevation, degrees")
      ->check(FiniteRange(-90, 90))
      ->capture_default_str();
  sub->add_option("--sun-azimuth", cmd->sunAzimuth, "Physical sky: degrees clockwise from north")
      ->check(FiniteRange(-360, 360))
      ->capture_default_str();
  sub->add_option("--sky-samples", cmd->skySamples, "The scene's sky rays per patch")
      ->check(CLI::Range(1, 1 << 20))
      ->capture_default_str();
  sub->add_flag("--image", cmd->image,
                "Render the landscape by ray marching and by Embree (the reference) and compare");
  sub->add_option("--image-width", cmd->landscape.width, "Landscape image width")
      ->check(CLI::Range(8, 8192))
      ->capture_default_str();
  sub->add_option("--image-height", cmd->landscape.height, "Landscape image height")
      ->check(CLI::Range(8, 8192))
      ->capture_default_str();
  sub->add_option("--march-steps", cmd->landscape.maxSteps, "Ray-marching steps per ray")
      ->check(CLI::Range(1, 1 << 20))
      ->capture_default_str();
  sub->add_option("--sun-rays", cmd->landscape.sunSamples, "Reference: shadow rays per pixel")
      ->check(CLI::Range(1, 4096))
      ->capture_default_str();
  sub->add_option("--aerial-samples", cmd->landscape.aerialSamples,
                  "Samples along each view ray for aerial perspective")
      ->check(CLI::Range(1, 4096))
      ->capture_default_str();
  sub->add_option("--exposure", cmd->exposure, "Image exposure (default: automatic)")
      ->check(FiniteNonNegative);
  sub->add_option("--out", cmd->out, "Output folder")->capture_default_str();
  sub->callback([cmd] { printSummary(runTerrainJob(*cmd)); });
}

}  // namespace radkit::app
