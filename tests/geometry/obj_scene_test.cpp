// OBJ scenes (loadObjScene): grouping into surfaces after the fix for the quadratic costs that
// fuzzing found (docs/robustness.md, "Fuzzing"): a scan of the group's faces and of the
// surfaces so far for every face, and a table of every vertex cleared for every surface.
#include <gtest/gtest.h>

#include <string>

#include "geometry/scene_loader.h"
#include "tests/common/test_util.h"

namespace radkit {
namespace {

const char* kMtl = "newmtl a\nKd 0.5 0.5 0.5\nnewmtl b\nKd 0.2 0.2 0.2\nKe 1 1 1\n";

const Surface& surfaceNamed(const Scene& scene, const std::string& name) {
  for (const Surface& s : scene.surfaces)
    if (s.name == name) return s;
  throw std::runtime_error("no surface " + name);
}

TEST(ObjScene, GroupSwitchingMaterialIsSplitPerMaterial) {
  test::TempDir dir;
  dir.file("m.mtl", kMtl);
  // Two quads side by side in group "box" (materials a, b, a), and a group "lid" on its own.
  const std::string obj =
      dir.file("s.obj",
               "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\n"
               "v 0 0 1\nv 1 0 1\nv 1 1 1\n"
               "g box\nusemtl a\nf 1 2 3 4\nusemtl b\nf 2 5 6 3\n"
               "g lid\nusemtl b\nf 7 8 9\n");
  const Scene scene = loadScene(obj);
  ASSERT_EQ(scene.surfaces.size(), 3u);
  const Surface& a = surfaceNamed(scene, "box.a");
  const Surface& b = surfaceNamed(scene, "box.b");
  const Surface& lid = surfaceNamed(scene, "lid");
  EXPECT_EQ(scene.materials[a.material].name, "a");
  EXPECT_EQ(scene.materials[b.material].name, "b");
  EXPECT_EQ(scene.materials[lid.material].name, "b");
  ASSERT_EQ(a.faces.size(), 1u);
  ASSERT_EQ(b.faces.size(), 1u);
  // Each surface keeps only its own vertices, renumbered in first-use order.
  EXPECT_EQ(a.vertices.size(), 4u);
  EXPECT_EQ(b.vertices.size(), 4u);
  EXPECT_EQ(lid.vertices.size(), 3u);
  EXPECT_EQ(b.faces[0].vertices, (std::vector<int>{0, 1, 2, 3}));
  EXPECT_DOUBLE_EQ(b.vertices[1].x, 2.0);
  EXPECT_DOUBLE_EQ(lid.vertices[2].z, 1.0);
}

// Many one-face groups next to one large group, through the radkit binary. The old costs grew
// as faces² and groups × vertices: at this size that is a fraction of a second in Release, so
// this checks the grouping at scale; the 30 s limit is the suite's hang guard, not a timing.
TEST(ObjScene, ManyGroupsAndLargeGroupsLoad) {
  test::TempDir dir;
  dir.file("m.mtl", kMtl);
  const int groups = 1000, strip = 5000;
  std::string text = "mtllib m.mtl\nusemtl b\n";
  for (int i = 0; i < strip + 2; ++i)
    text += "v " + std::to_string(i) + " " + std::to_string(i % 2) + " 0\n";
  for (int i = 0; i < groups; ++i)
    text += "g g" + std::to_string(i) + "\nf " + std::to_string(i + 1) + " " +
            std::to_string(i + 2) + " " + std::to_string(i + 3) + "\n";
  text += "g strip\n";  // one group of 4 000 faces: a scan of the group per face was quadratic
  for (int i = groups; i < strip; ++i)
    text += "f " + std::to_string(i + 1) + " " + std::to_string(i + 2) + " " +
            std::to_string(i + 3) + "\n";
  dir.file("s.obj", text);
  const test::RunResult r =
      test::runRadkit("mesh '" + dir.path("s.obj") + "' --out '" + dir.path("out") + "'", 30);
  EXPECT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("surfaces: " + std::to_string(groups + 1)), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("input faces: " + std::to_string(strip)), std::string::npos) << r.output;
}

// A file name longer than the file system allows (fuzzing found it in "mtllib") is a missing
// file with a message, not a filesystem_error escaping the loader.
TEST(ObjScene, OverlongFileNamesAreMissingFiles) {
  test::TempDir dir;
  const std::string longName(300, 'm');
  const std::string obj = dir.file(
      "s.obj", "mtllib " + longName + ".mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n");
  const std::string materials = R"({"materials": {"a": {"emission": [1,1,1]}}, "surfaces": [)";
  const std::string mesh =
      dir.file("mesh.json", materials + R"({"name": "m", "material": "a", "mesh": ")" + longName +
                                R"(.off"}]})");
  const std::string include =
      dir.file("include.json", materials + R"({"include": ")" + longName + R"(.obj"}]})");
  for (const std::string& file : {obj, mesh, include}) {
    try {
      loadScene(file);
      ADD_FAILURE() << file << " loaded";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(longName), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("Fix:"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace radkit
