#include "geometry/patch_io.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace radkit
