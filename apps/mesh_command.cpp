// radkit mesh: load, validate and subdivide a scene; write patches.csv and patches.vtp.
#include <algorithm>
#include <cstdio>
#include <memory>

#include "apps/common.h"
#include "output/run_files.h"
#include "util/format.h"
#include "util/output_folder.h"

namespace radkit::app {

namespace {

struct MeshCommand {
  MeshOptions mesh;
  std::string out;
};

std::string number(double v) { return formatNumber(v); }

void runMesh(const MeshCommand& cmd) {
  Scene scene = loadSceneReporting(cmd.mesh.scene, cmd.mesh.load);
  OutputFolder folder(cmd.out);  // refuses an --out it cannot replace before meshing, not after
  PatchMesh patches = meshScene(scene, cmd.mesh);
  writePatchesCsv(folder.path("patches.csv"), scene, patches, nullptr);
  writePatchesVtp(folder.path("patches.vtp"), scene, patches, nullptr);
  folder.commit();

  std::size_t faces = 0, quads = 0;
  double minArea = INFINITY, maxArea = 0, worstAspect = 0;
  for (const Surface& s : scene.surfaces) faces += s.faces.size();
  for (const Patch& p : patches.patches) {
    quads += p.isQuad();
    minArea = std::min(minArea, p.area);
    maxArea = std::max(maxArea, p.area);
    worstAspect = std::max(worstAspect, patches.aspectRatio(p));
  }
  printField("scene", scene.name + " (" + cmd.mesh.scene + ")");
  printField("surfaces", std::to_string(scene.surfaces.size()));
  printField("materials", std::to_string(scene.materials.size()));
  printField("input faces", std::to_string(faces));
  printField("patches", std::to_string(patches.size()) + " (" + std::to_string(quads) + " quads, " +
                            std::to_string(patches.size() - quads) + " triangles)");
  printField("total area", number(patches.totalArea()) + " " + scene.units + "²");
  printField("patch area min/max",
             number(minArea) + " / " + number(maxArea) + " " + scene.units + "²");
  printField("worst aspect ratio", number(worstAspect) + " (1 = square or equilateral)");
  printField("wrote", cmd.out + "/patches.csv, patches.vtp");
}

}  // namespace

void addMeshCommand(CLI::App& app) {
  auto cmd = std::make_shared<MeshCommand>();
  CLI::App* sub = app.add_subcommand("mesh", "Load, validate and subdivide a scene into patches");
  addMeshOptions(*sub, cmd->mesh);
  sub->add_option("--out", cmd->out, "Output folder")->required();
  sub->callback([cmd] { runMesh(*cmd); });
}

}  // namespace radkit::app
