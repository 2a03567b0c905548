// Imported models as a first-time user brings them: meshes that need repair, coordinates in
// millimetres or feet, and meshes finer than the patch target. Through the radkit binary.
// Oracles: areas and powers worked out by hand from the files the tests write.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>

#include <nlohmann/json.hpp>

#include "tests/common/read_json.h"
#include "tests/common/test_util.h"

namespace radkit {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::readJson;

/// Sum of patch areas per surface in a patches.csv, and the patch counts.
struct SurfacePatches {
  std::map<std::string, double> area;
  std::map<std::string, int> count;
};
SurfacePatches surfacePatches(const std::string& csv) {
  SurfacePatches out;
  for (auto& row : test::readCsv(csv)) {
    out.area[row["surface"]] += std::stod(row["area_m2"]);
    out.count[row["surface"]] += 1;
  }
  return out;
}

const char* kLampAndGrey = R"("materials": {"grey": {"reflectance": [0.5,0.5,0.5]},
                                            "lamp": {"reflectance": [0,0,0], "emission": [1,1,1]}})";

/// A unit square in z = 0 as two triangles, the first listed twice, and a vertical fin
/// (0, 2, 4) on its diagonal: three faces on the edge 0–2.
const char* kSquareWithDuplicateAndFin =
    "OFF\n5 4 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0.5 0.5 1\n3 0 1 2\n3 0 2 3\n3 0 1 2\n3 0 2 4\n";

std::string repairScene(const test::TempDir& dir) {
  dir.file("scan.off", kSquareWithDuplicateAndFin);
  return dir.file("scene.json", std::string("{") + kLampAndGrey + R"(, "surfaces": [
      {"name": "scan", "material": "grey", "mesh": "scan.off"},
      {"name": "lamp", "material": "lamp", "polygon": [[0,0,2],[0,1,2],[1,1,2],[1,0,2]]}]})");
}

TEST(MeshRepair, RefusedWithoutRepairNamingTheFlag) {
  test::TempDir dir;
  const std::string scene = repairScene(dir);
  test::RunResult r = test::runRadkit("mesh '" + scene + "' --out '" + dir.path("o") + "'");
  EXPECT_NE(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("scan.off"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("--repair"), std::string::npos) << "the error must name the way out:\n"
                                                          << r.output;
  EXPECT_FALSE(fs::exists(dir.path("o")));
}

TEST(MeshRepair, DuplicateFaceAndFinAreRepairedReportedAndRun) {
  test::TempDir dir;
  const std::string scene = repairScene(dir);
  test::RunResult r =
      test::runRadkit("mesh '" + scene + "' --repair --out '" + dir.path("m") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("removed 1 duplicate face"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("cut 1 non-manifold edge"), std::string::npos) << r.output;
  // The fin cut off at the diagonal touches the square there and nowhere else.
  EXPECT_EQ(r.output.find("intersects itself"), std::string::npos) << r.output;
  // Unit square plus the fin: a triangle of base √2 (the diagonal) and height 1.
  const SurfacePatches p = surfacePatches(dir.path("m/patches.csv"));
  EXPECT_NEAR(p.area.at("scan"), 1 + std::sqrt(2.0) / 2, 1e-12);
  EXPECT_EQ(p.count.at("scan"), 3) << "one patch per kept face without a target";

  r = test::runRadkit("run '" + scene + "' --repair --patches 60 --no-render --out '" +
                      dir.path("r") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const json load = readJson(dir.path("r/report.json"))["load"];
  ASSERT_EQ(load["repairs"].size(), 1u) << load.dump(2);
  const json& repair = load["repairs"][0];
  EXPECT_NE(repair["surface"].get<std::string>().find("scan.off"), std::string::npos);
  EXPECT_EQ(repair["duplicate_faces_removed"], 1);
  EXPECT_EQ(repair["non_manifold_edges_cut"], 1);
  EXPECT_EQ(repair["degenerate_faces_removed"], 0);
  bool warned = false;
  for (const json& w : load["warnings"])
    warned |= w.get<std::string>().find("repaired:") != std::string::npos;
  EXPECT_TRUE(warned) << "load warnings reach report.json:\n" << load.dump(2);
}

// An OBJ whose faces each carry their own copies of the vertices (as exporters write them)
// shares no edge: no face crosses another, so no self-intersection may be reported.
TEST(MeshRepair, UnweldedObjIsNotSelfIntersectingAndRepairWeldsIt) {
  test::TempDir dir;
  dir.file("box.mtl", "newmtl grey\nKd 0.5 0.5 0.5\nnewmtl lamp\nKd 0 0 0\nKe 1 1 1\n");
  const std::string obj = dir.file("box.obj",
                                   "mtllib box.mtl\n"
                                   "o floor\nusemtl grey\n"
                                   "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 0 0\nv 1 1 0\nv 0 1 0\n"
                                   "f 1 2 3\nf 4 5 6\n"
                                   "o lamp\nusemtl lamp\n"
                                   "v 0 0 1\nv 0 1 1\nv 1 1 1\nv 1 0 1\nf 7 8 9 10\n");
  test::RunResult r = test::runRadkit("mesh '" + obj + "' --out '" + dir.path("a") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(r.output.find("intersects itself"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("2 vertices repeat the position of another"), std::string::npos)
      << r.output;
  r = test::runRadkit("mesh '" + obj + "' --repair --out '" + dir.path("b") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("welded 2 duplicate vertices"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("vertices repeat"), std::string::npos) << r.output;
}

/// A 1000 × 1000 floor with a lamp of the same size 1000 above it, in the OBJ's own units.
std::string objRoom(const test::TempDir& dir) {
  dir.file("room.mtl", "newmtl grey\nKd 0.5 0.5 0.5\nnewmtl lamp\nKd 0 0 0\nKe 1 1 1\n");
  return dir.file(
      "room.obj",
      "mtllib room.mtl\n"
      "o floor\nusemtl grey\nv 0 0 0\nv 1000 0 0\nv 1000 1000 0\nv 0 1000 0\nf 1 2 3 4\n"
      "o lamp\nusemtl lamp\nv 0 0 1000\nv 0 1000 1000\nv 1000 1000 1000\nv 1000 0 1000\nf 5 6 7 "
      "8\n");
}

TEST(Units, MillimetreObjReportsSquareMetresAndWatts) {
  test::TempDir dir;
  const std::string obj = objRoom(dir);
  // Read as metres the room is a kilometre across: the load says so and names --units.
  test::RunResult r =
      test::runRadkit("run '" + obj + "' --patches 8 --no-render --out '" + dir.path("m") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("--units"), std::string::npos) << r.output;
  r = test::runRadkit("run '" + obj + "' --units mm --patches 8 --no-render --out '" +
                      dir.path("mm") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(r.output.find("--units"), std::string::npos) << "a 1 m room is plausible:\n"
                                                         << r.output;
  const json report = readJson(dir.path("mm/report.json"));
  EXPECT_EQ(report["scene"]["units"], "mm");
  // The lamp: 1 m² emitting 1 W/m² in each channel.
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(report["energy_balance"]["emitted_W"][c].get<double>(), 1.0, 1e-9);
  for (const json& s : report["surfaces"])
    EXPECT_NEAR(s["area_m2"].get<double>(), 1.0, 1e-9) << s.dump();
}

TEST(Units, FeetAndInchesAndAConflictWithTheSceneFile) {
  test::TempDir dir;
  const std::string obj = objRoom(dir);
  test::RunResult r = test::runRadkit(
      "run '" + obj + "' --units ft --patches 8 --no-render --out '" + dir.path("ft") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  // 1000 ft = 304.8 m: emitted 304.8² W.
  EXPECT_NEAR(readJson(dir.path("ft/report.json"))["energy_balance"]["emitted_W"][0].get<double>(),
              304.8 * 304.8, 1e-6);
  const std::string scene =
      dir.file("in.json", std::string("{\"units\": \"in\", ") + kLampAndGrey + R"(, "surfaces": [
      {"name": "floor", "material": "grey", "polygon": [[0,0,0],[10,0,0],[10,10,0],[0,10,0]]},
      {"name": "lamp", "material": "lamp", "polygon": [[0,0,10],[0,10,10],[10,10,10],[10,0,10]]}]})");
  r = test::runRadkit("run '" + scene + "' --patches 8 --no-render --out '" + dir.path("in") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  // 10 in = 0.254 m.
  EXPECT_NEAR(readJson(dir.path("in/report.json"))["energy_balance"]["emitted_W"][0].get<double>(),
              0.254 * 0.254, 1e-12);
  r = test::runRadkit("mesh '" + scene + "' --units mm --out '" + dir.path("x") + "'");
  EXPECT_NE(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("in.json"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("Fix:"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir.path("x")));
}

/// A 10 × 10 floor and lamp around a 1 × 1 OFF mesh of 20 × 20 × 2 triangles: the mesh's 800
/// faces alone exceed a 400-patch target.
std::string fineMeshScene(const test::TempDir& dir) {
  std::string off = "OFF\n441 800 0\n";
  for (int j = 0; j <= 20; ++j)
    for (int i = 0; i <= 20; ++i)
      off += std::to_string(4.5 + i / 20.0) + " " + std::to_string(4.5 + j / 20.0) + " 0.5\n";
  for (int j = 0; j < 20; ++j)
    for (int i = 0; i < 20; ++i) {
      const int a = j * 21 + i, b = a + 1, c = a + 22, d = a + 21;
      off += "3 " + std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(c) + "\n";
      off += "3 " + std::to_string(a) + " " + std::to_string(c) + " " + std::to_string(d) + "\n";
    }
  dir.file("fine.off", off);
  return dir.file("scene.json", std::string("{") + kLampAndGrey + R"(, "surfaces": [
      {"name": "floor", "material": "grey", "polygon": [[0,0,0],[10,0,0],[10,10,0],[0,10,0]]},
      {"name": "lamp", "material": "lamp", "polygon": [[4,4,3],[4,6,3],[6,6,3],[6,4,3]]},
      {"name": "fine", "material": "grey", "mesh": "fine.off"}]})");
}

TEST(PatchBudget, AFineMeshDoesNotLeaveTheFloorWhole) {
  test::TempDir dir;
  const std::string scene = fineMeshScene(dir);
  test::RunResult r =
      test::runRadkit("mesh '" + scene + "' --patches 400 --out '" + dir.path("o") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const SurfacePatches p = surfacePatches(dir.path("o/patches.csv"));
  // The floor is 100 of the 105 m² of surface: its area's share of 400 patches is 381.
  EXPECT_GE(p.count.at("floor"), 381 * 3 / 4) << r.output;
  EXPECT_EQ(p.count.at("fine"), 800);
  EXPECT_NEAR(p.area.at("floor"), 100, 1e-9);
  // The warning blames the mesh, not the floor or visibility.
  EXPECT_NE(r.output.find("fine.off"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("800 faces"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("Fix:"), std::string::npos) << r.output;
  // Without a fine mesh the target is met as before: no warning.
  r = test::runRadkit("mesh '" + test::dataPath("cornell-box.json") + "' --patches 400 --out '" +
                      dir.path("c") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(r.output.find("share"), std::string::npos) << r.output;
}

// A ball of 320 small faces beside whole walls: rows of F sum above 1 because a wall patch is
// larger than its distance from the ball, and the warning says so rather than blaming the rays.
TEST(PatchBudget, RowSumWarningNamesThePatchTooLargeForItsDistance) {
  test::TempDir dir;
  const std::string cornell = test::dataPath("cornell-box.json");
  std::ifstream in(cornell);
  json scene = json::parse(in);
  scene["surfaces"].push_back({{"name", "ball"},
                               {"material", "white"},
                               {"mesh", test::dataPath("sphere-interior.off")},
                               {"transform", {{"scale", -100}, {"translate", {420, 100.5, 120}}}}});
  const std::string path = dir.file("ball.json", scene.dump());
  test::RunResult r =
      test::runRadkit("formfactors '" + path + "' --max-area 1e9 --out '" + dir.path("o") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const json report = readJson(dir.path("o/report.json"));
  ASSERT_GT(report["form_factors"]["row_sum"]["max"].get<double>(), 1.01)
      << "the case this test is about";
  EXPECT_NE(r.output.find("of \"ball\" sees patch"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("the mesh, not visibility noise"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("Fix: split"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace radkit
