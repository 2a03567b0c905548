#include "output/run_files.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "geometry/scene_loader.h"
#include "geometry/subdivision.h"
#include "tests/common/test_util.h"
#include "util/output_folder.h"

namespace radkit {
namespace {

TEST(CsvField, Exact) {
  EXPECT_EQ(csvField("floor"), "floor");
  EXPECT_EQ(csvField("a,b"), "\"a,b\"");
  EXPECT_EQ(csvField("say \"hi\""), "\"say \"\"hi\"\"\"");
  EXPECT_EQ(csvField("two\nlines"), "\"two\nlines\"");
}

TEST(PatchesCsv, SurfaceNamesWithCommasStayOneField) {
  test::TempDir dir;
  std::string file = dir.file("s.json", R"({"materials": {"m": {"emission": [1,1,1]}},
    "surfaces": [{"name": "wall, \"north\"", "material": "m", "polygon": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]]}]})");
  Scene scene = loadScene(file);
  PatchMesh mesh = subdivide(scene, {});
  writePatchesCsv(dir.path("p.csv"), scene, mesh, nullptr);
  std::ifstream in(dir.path("p.csv"));
  std::string header, row;
  std::getline(in, header);
  std::getline(in, row);
  EXPECT_EQ(row.rfind("0,\"wall, \"\"north\"\"\",", 0), 0u) << row;
}

// Units are in the headers, and lengths are metres whatever the scene's units: the same
// square written in millimetres and in metres gives the same numbers.
TEST(RunFilesUnits, LengthsInMetresWhateverTheSceneUnits) {
  test::TempDir dir;
  auto scene = [&](const char* units, double side) {
    const std::string s = std::to_string(side);
    return loadScene(dir.file(std::string(units) + ".json",
                              std::string(R"({"units": ")") + units +
                                  R"(", "materials": {"m": {"emission": [1,1,1]}},
      "surfaces": [{"name": "sq", "material": "m", "polygon": [[0,0,0],[)" +
                                  s + ",0,0],[" + s + "," + s + ",0],[0," + s + R"(,0]]}]})"));
  };
  auto rows = [&](const Scene& sc, const std::string& name) {
    PatchMesh mesh = subdivide(sc, {});
    const std::vector<Vec3> b(mesh.size(), Vec3{2, 3, 4});
    writePatchesCsv(dir.path(name), sc, mesh, &b);
    return test::readCsv(dir.path(name));
  };
  const auto mm = rows(scene("mm", 2000), "mm.csv"), m = rows(scene("m", 2), "m.csv");
  ASSERT_EQ(mm.size(), 1u);
  for (const char* col : {"area_m2", "cx_m", "cy_m", "cz_m", "b_r_W_m2", "e_g_W_m2"})
    EXPECT_EQ(mm[0].count(col), 1u) << col;
  EXPECT_DOUBLE_EQ(std::stod(mm[0].at("area_m2")), 4.0);  // 2000 mm square: 4 m²
  EXPECT_DOUBLE_EQ(std::stod(mm[0].at("cx_m")), 1.0);
  for (const auto& [col, value] : m[0])
    if (col != "surface") {
      EXPECT_DOUBLE_EQ(std::stod(value), std::stod(mm[0].at(col))) << col;
    }
  EXPECT_EQ(std::string(kPatchesCsvHeader).find(",area,"), std::string::npos);
}

// convergence.csv: one row per kept history row, its header with units, the unshot power in
// W (scene areas in mm² scaled by 1e-6).
TEST(RunFilesUnits, ConvergenceCsvRowsAndUnits) {
  test::TempDir dir;
  SolveResult r;
  r.solver = "jacobi";
  for (long k = 0; k < 5; ++k) r.history.push_back({k, 0.1 * k, std::pow(0.5, k), 1e6, double(k)});
  writeConvergenceCsv(dir.path("c.csv"), {r, r}, 1e-3);
  const auto rows = test::readCsv(dir.path("c.csv"));
  ASSERT_EQ(rows.size(), 10u);
  EXPECT_EQ(rows[3].at("solver"), "jacobi");
  EXPECT_EQ(rows[3].at("iteration"), "3");
  EXPECT_DOUBLE_EQ(std::stod(rows[3].at("sweeps")), 3.0);
  EXPECT_DOUBLE_EQ(std::stod(rows[3].at("time_s")), 0.30000000000000004);
  EXPECT_DOUBLE_EQ(std::stod(rows[3].at("residual")), 0.125);
  EXPECT_DOUBLE_EQ(std::stod(rows[3].at("unshot_power_W")), 1.0);
}

}  // namespace
}  // namespace radkit
