// Every class of bad input: a non-zero exit, a message naming file, element and fix, and no
// output written. Run through the radkit binary as a user would.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "tests/common/test_util.h"

namespace radkit {
namespace {

namespace fs = std::filesystem;

const char* kMaterials = R"("materials": {"grey": {"reflectance": [0.5,0.5,0.5]},
                                          "lamp": {"reflectance": [0,0,0], "emission": [1,1,1]}})";
const char* kSquare = R"([[0,0,0],[1,0,0],[1,1,0],[0,1,0]])";

std::string sceneWith(const std::string& surfaces) {
  return std::string("{") + kMaterials + R"(, "surfaces": [)" + surfaces + "]}";
}

struct BadCase {
  const char* name;
  std::string sceneText;
  std::vector<std::string> mustMention;
  std::string extraFile, extraText;  // a mesh file the scene refers to
};

BadCase bad(const char* name, std::string sceneText, std::vector<std::string> mustMention,
            std::string extraFile = "", std::string extraText = "") {
  return BadCase{name, std::move(sceneText), std::move(mustMention), std::move(extraFile),
                 std::move(extraText)};
}

void PrintTo(const BadCase& c, std::ostream* os) { *os << c.name; }

class BadInput : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadInput, FailsCleanly) {
  const BadCase& c = GetParam();
  test::TempDir dir;
  if (!c.extraFile.empty()) dir.file(c.extraFile, c.extraText);
  std::string scene = dir.file("scene.json", c.sceneText);
  std::string out = dir.path("out");
  test::RunResult r = test::runRadkit("mesh '" + scene + "' --out '" + out + "'");
  EXPECT_NE(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("scene.json"), std::string::npos) << "message must name the file:\n"
                                                            << r.output;
  for (const std::string& word : c.mustMention)
    EXPECT_NE(r.output.find(word), std::string::npos) << "missing '" << word << "' in:\n"
                                                      << r.output;
  EXPECT_FALSE(fs::exists(out)) << "output folder written on error";
  for (const auto& entry : fs::directory_iterator(fs::path(out).parent_path()))
    EXPECT_EQ(entry.path().filename().string().find(".out.partial"), std::string::npos)
        << "staging left behind";
}

/// A binary PLY triangle whose second vertex has x = NaN (text formats cannot spell NaN
/// portably; binary ones carry it as it is).
std::string binaryPlyWithNan() {
  std::string ply =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n";
  const float v[9] = {0, 0, 0, std::numeric_limits<float>::quiet_NaN(), 0, 0, 0, 1, 0};
  ply.append(reinterpret_cast<const char*>(v), sizeof v);
  const unsigned char count = 3;
  const int idx[3] = {0, 1, 2};
  ply.append(reinterpret_cast<const char*>(&count), 1);
  ply.append(reinterpret_cast<const char*>(idx), sizeof idx);
  return ply;
}

std::string square(const char* name, const char* material, const std::string& polygon) {
  return std::string(R"({"name": ")") + name + R"(", "material": ")" + material +
         R"(", "polygon": )" + polygon + "}";
}

INSTANTIATE_TEST_SUITE_P(
    Geometry, BadInput,
    ::testing::Values(
        bad("MalformedJson", "{\n  \"materials\": {},\n  \"surfaces\": [,]\n}",
            {"line 3", "column"}),
        bad("InfiniteCoordinate",
            sceneWith(square("floor", "lamp", "[[0,0,0],[1e999,0,0],[1,1,0]]")),
            {"number overflow", "Fix"}),
        bad("NanCoordinateInMesh",
            sceneWith(R"({"name": "m", "material": "lamp", "mesh": "m.ply"})"),
            {"\"m\"", "vertex 1", "NaN"}, "m.ply", binaryPlyWithNan()),
        // Text readers would read these as 0, a truncated number or a misleading parse error.
        bad("NanInTextOff", sceneWith(R"({"name": "m", "material": "lamp", "mesh": "n.off"})"),
            {"\"m\"", "n.off", "line 5", "'nan'", "Fix"}, "n.off",
            "OFF\n# a comment\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n"),
        bad("OverflowInTextOff", sceneWith(R"({"name": "m", "material": "lamp", "mesh": "n.off"})"),
            {"n.off", "line 3", "'1e999'"}, "n.off",
            "OFF 3 1 0\n0 0 0\n1 0 1e999\n0 1 0\n3 0 1 2\n"),
        bad("CommaDecimalInAsciiPly",
            sceneWith(R"({"name": "m", "material": "lamp", "mesh": "c.ply"})"),
            {"c.ply", "line 10", "'0,5'", "decimal"}, "c.ply",
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
            "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
            "0,5 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
        bad("InfinityInAsciiStl",
            sceneWith(R"({"name": "m", "material": "lamp", "mesh": "i.stl"})"),
            {"i.stl", "line 4", "'-inf'"}, "i.stl",
            "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 -inf\nvertex 1 0 0\nvertex 0 1 0\n"
            "endloop\nendfacet\nendsolid t\n"),
        bad("NanInObjMesh", sceneWith(R"({"name": "m", "material": "lamp", "mesh": "n.obj"})"),
            {"n.obj", "line 2", "'NaN'"}, "n.obj", "v 0 0 0\nv NaN 0 0\nv 0 1 0\nf 1 2 3\n"),
        bad("CollinearFace", sceneWith(square("sliver", "lamp", "[[0,0,0],[1,1,1],[2,2,2]]")),
            {"sliver", "face 0", "collinear", "Fix"}),
        bad("RepeatedVertex", sceneWith(square("dup", "lamp", "[[0,0,0],[1,0,0],[1,0,0],[0,1,0]]")),
            {"dup", "face 0", "repeats a vertex"}),
        bad("ZeroAreaMeshFace",
            sceneWith(R"({"name": "flat", "material": "lamp", "mesh": "f.off"})"),
            {"\"flat\"", "face 1", "collinear"}, "f.off",
            "OFF\n5 2 0\n0 0 0\n1 0 0\n0 1 0\n2 0 0\n3 0 0\n3 0 1 2\n3 1 3 4\n"),
        bad("DuplicateFace", sceneWith(R"({"name": "twice", "material": "lamp", "polygons": [
                  [[0,0,0],[1,0,0],[1,1,0]], [[1,0,0],[1,1,0],[0,0,0]] ]})"),
            {"\"twice\"", "face 1 repeats face 0", "Fix"}),
        bad("NonManifoldEdge", sceneWith(R"({"name": "fin", "material": "lamp", "polygons": [
                  [[0,0,0],[1,0,0],[0,1,0]], [[1,0,0],[0,0,0],[0,-1,0]], [[0,0,0],[1,0,0],[0,0,1]] ]})"),
            {"\"fin\"", "vertices 0 and 1", "shared by 3 faces", "Fix"}),
        // Six quads closing a loop with a half twist: no winding makes the edges consistent.
        bad("OneSidedSurface",
            sceneWith(R"({"name": "strip", "material": "lamp", "mesh": "m.off"})"),
            {"\"strip\"", "one side only", "Fix"}, "m.off",
            "OFF\n12 6 0\n0.7 0 0\n1.3 0 0\n0.38 0.66 -0.15\n0.65 1.12 0.15\n"
            "-0.42 0.73 -0.26\n-0.58 1.01 0.26\n-1 0 -0.3\n-1 0 0.3\n-0.58 -1.01 -0.26\n"
            "-0.42 -0.73 0.26\n0.65 -1.12 -0.15\n0.38 -0.66 0.15\n"
            "4 0 2 3 1\n4 2 4 5 3\n4 4 6 7 5\n4 6 8 9 7\n4 8 10 11 9\n4 10 1 0 11\n"),
        bad("ReflectanceOne",
            R"({"materials": {"white": {"reflectance": [1.0, 0.5, 0.5], "emission": [1,1,1]}},
                    "surfaces": [{"name": "a", "material": "white", "polygon": [[0,0,0],[1,0,0],[1,1,0]]}]})",
            {"material \"white\"", "reflectance", "[0, 1)"}),
        bad("NegativeReflectance",
            R"({"materials": {"w": {"reflectance": [0.5, -0.1, 0.5], "emission": [1,1,1]}},
                    "surfaces": [{"name": "a", "material": "w", "polygon": [[0,0,0],[1,0,0],[1,1,0]]}]})",
            {"material \"w\"", "reflectance"}),
        bad("NegativeEmission",
            R"({"materials": {"lamp": {"emission": [1, -2, 1]}},
                    "surfaces": [{"name": "a", "material": "lamp", "polygon": [[0,0,0],[1,0,0],[1,1,0]]}]})",
            {"material \"lamp\"", "emission", ">= 0"}),
        bad("UnknownMaterial", sceneWith(square("floor", "marble", kSquare)),
            {"floor", "unknown material \"marble\"", "grey", "lamp"}),
        bad("UnknownKey",
            sceneWith(
                R"({"name": "floor", "material": "grey", "polgon": [[0,0,0],[1,0,0],[1,1,0]]})"),
            {"floor", "polgon"}),
        bad("MissingMeshFile",
            sceneWith(R"({"name": "statue", "material": "grey", "mesh": "statue.ply"})"),
            {"statue.ply", "not found"}),
        bad("EmptyScene", std::string("{") + kMaterials + R"(, "surfaces": []})", {"no surfaces"}),
        bad("CoordinateBeyondRayTracer",
            sceneWith(square("sliver", "lamp", "[[0,0,0],[1e20,0,0],[1e20,1e-20,0],[0,1e-20,0]]")),
            {"\"sliver\"", "vertex 1", "1e+20", "Fix"}),
        bad("DuplicateSurfaceName",
            sceneWith(square("a", "lamp", kSquare) + "," + square("a", "grey", kSquare)),
            {"\"a\"", "used twice"})),
    [](const ::testing::TestParamInfo<BadCase>& param) { return std::string(param.param.name); });

// An OBJ scene's MTL is read by the same readers: a NaN reflectance is named by MTL file and line.
TEST(BadInputCli, NanInObjSceneMaterial) {
  test::TempDir dir;
  dir.file("s.mtl", "newmtl lamp\nKd 0.5 0.5 0.5\nKe 1 nan 1\n");
  const std::string obj =
      dir.file("s.obj", "mtllib s.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl lamp\nf 1 2 3\n");
  test::RunResult r = test::runRadkit("mesh '" + obj + "' --out '" + dir.path("o") + "'");
  EXPECT_NE(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("s.mtl: line 3: 'nan'"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir.path("o")));
}

// The number check leaves binary STL alone even when its 80-byte header starts with "solid",
// and leaves names and comments in text files alone.
TEST(MeshCli, ReadsBinaryStlAndTextWithWordsThatAreNotNumbers) {
  test::TempDir dir;
  std::string stl(80, ' ');
  stl.replace(0, 12, "solid binary");
  const std::uint32_t count = 1;
  stl.append(reinterpret_cast<const char*>(&count), 4);
  const float tri[12] = {0, 0, 1, 0, 0, 0, 2, 0, 0, 0, 2, 0};  // normal, then three vertices
  stl.append(reinterpret_cast<const char*>(tri), sizeof tri);
  stl.append(2, '\0');
  dir.file("b.stl", stl);
  dir.file("t.off", "OFF # infinity is a word here\n3 1 0\n0 0 0\n2 0 0\n0 2 0\n3 0 1 2\n");
  dir.file("t.obj", "# nan\ng infinite_plane\nv 0 0 0\nv +2.0 0 0\nv 0 2E0 0\nf 1 2 3\n");
  const std::string scene =
      dir.file("scene.json", sceneWith(
                                 R"({"name": "b", "material": "lamp", "mesh": "b.stl"},
         {"name": "t", "material": "grey", "mesh": "t.off", "transform": {"translate": [0, 0, 1]}},
         {"name": "o", "material": "grey", "mesh": "t.obj", "transform": {"translate": [0, 0, 2]}})"));
  test::RunResult r = test::runRadkit("mesh '" + scene + "' --out '" + dir.path("o") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("total area: 6 m"), std::string::npos) << r.output;
}

/// Normals (nx,ny,nz) of every patch in a patches.csv.
std::vector<std::string> patchNormals(const std::string& csvPath) {
  std::ifstream csv(csvPath);
  std::vector<std::string> normals;
  std::string line;
  std::getline(csv, line);
  while (std::getline(csv, line)) {
    std::vector<std::string> field;
    std::stringstream fields(line);
    for (std::string f; std::getline(fields, f, ',');) field.push_back(f);
    normals.push_back(field.at(6) + "," + field.at(7) + "," + field.at(8));
  }
  return normals;
}

// A face wound against its neighbours is reversed with a warning naming it, in a JSON surface
// and in a mesh read by OpenMesh; each connected part keeps the winding most of its faces had.
TEST(MeshCli, RepairsFacesWoundAgainstTheirNeighbours) {
  test::TempDir dir;
  dir.file("o.off", "OFF\n4 2 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n3 0 1 2\n3 0 3 2\n");
  const std::string scene =
      dir.file("scene.json", sceneWith(
                                 R"({"name": "up", "material": "lamp", "polygons": [
           [[0,0,0],[1,0,0],[1,1,0]], [[0,0,0],[0,1,0],[1,1,0]], [[1,0,0],[2,0,0],[2,1,0],[1,1,0]]]},
         {"name": "down", "material": "grey", "polygons": [
           [[0,0,2],[1,0,2],[1,1,2]], [[0,0,2],[0,1,2],[1,1,2]], [[1,0,2],[1,1,2],[2,1,2],[2,0,2]]]},
         {"name": "m", "material": "grey", "mesh": "o.off"})"));
  test::RunResult r = test::runRadkit("mesh '" + scene + "' --out '" + dir.path("o") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(
      r.output.find(
          "(\"up\"): 1 face was wound against its neighbours and reversed to match them (face 1)"),
      std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("(\"down\"): 1 face was wound against its neighbours and reversed to "
                          "match them (face 0)"),
            std::string::npos)
      << "the two faces wound downwards outvote the first:\n"
      << r.output;
  EXPECT_NE(r.output.find("o.off): 1 face was wound"), std::string::npos) << r.output;
  const std::vector<std::string> normals = patchNormals(dir.path("o/patches.csv"));
  ASSERT_EQ(normals.size(), 8u);
  for (std::size_t p = 0; p < 3; ++p) EXPECT_EQ(normals[p], "0,0,1") << p;
  for (std::size_t p = 3; p < 6; ++p) EXPECT_EQ(normals[p], "0,0,-1") << p;
  for (std::size_t p = 6; p < 8; ++p) EXPECT_EQ(normals[p], "0,0,1") << p;
}

TEST(BadInputCli, MissingSceneFileAndBadOptions) {
  test::TempDir dir;
  test::RunResult r = test::runRadkit("mesh /nonexistent/scene.json --out '" + dir.path("o") + "'");
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.output.find("/nonexistent/scene.json"), std::string::npos) << r.output;
  r = test::runRadkit("mesh '" + test::dataPath("furnace.json") + "' --max-area -1 --out '" +
                      dir.path("o") + "'");
  EXPECT_NE(r.exitCode, 0);
  r = test::runRadkit("mesh '" + test::dataPath("furnace.json") +
                      "' --max-area 1 --patches 10 --out '" + dir.path("o") + "'");
  EXPECT_NE(r.exitCode, 0) << "--max-area and --patches exclude each other";
  EXPECT_FALSE(fs::exists(dir.path("o")));
}

TEST(MeshCli, WritesPatchesAndSummary) {
  test::TempDir dir;
  test::RunResult r = test::runRadkit("mesh '" + test::dataPath("cornell-box.json") +
                                      "' --patches 500 --out '" + dir.path("o") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("worst aspect ratio"), std::string::npos);
  EXPECT_NE(r.output.find("warning"), std::string::npos) << "the non-planar wall is reported";
  std::ifstream csv(dir.path("o/patches.csv"));
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(
      header,
      "id,surface,area_m2,cx_m,cy_m,cz_m,nx,ny,nz,rho_r,rho_g,rho_b,e_r_W_m2,e_g_W_m2,e_b_W_m2,"
      "b_r_W_m2,b_g_W_m2,b_b_W_m2");
  int rows = 0;
  for (std::string line; std::getline(csv, line);) ++rows;
  EXPECT_GT(rows, 400);
  EXPECT_LT(rows, 600);
  EXPECT_TRUE(fs::exists(dir.path("o/patches.vtp")));
  r = test::runRadkit("--version");
  EXPECT_EQ(r.exitCode, 0);
  EXPECT_NE(r.output.find("radkit "), std::string::npos);
}

// Issue 20, point 3: a polygon of extreme aspect (1e20 x 1e-20) made Embree's ray.valid()
// assertion abort `run` and leave its staging folder; it is refused while loading now, and a
// thin but representable one (1e6 x 1e-6) still runs.
TEST(BadInputCli, ExtremeAspectPolygonInRun) {
  test::TempDir dir;
  const std::string huge = dir.file(
      "huge.json",
      sceneWith(square("sliver", "lamp", "[[0,0,0],[1e20,0,0],[1e20,1e-20,0],[0,1e-20,0]]") + "," +
                square("floor", "grey", "[[0,0,-1],[0,1,-1],[1,1,-1],[1,0,-1]]")));
  test::RunResult r = test::runRadkitWithin(
      300, "run '" + huge + "' --patches 10 --no-render --out '" + dir.path("out") + "'");
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("vertex 1 has a coordinate of 1e+20"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir.path("out")));
  for (const auto& entry : fs::directory_iterator(dir.path("")))
    EXPECT_EQ(entry.path().filename().string().find(".out."), std::string::npos)
        << "staging left behind";
  const std::string thin =
      dir.file("thin.json",
               sceneWith(square("sliver", "lamp", "[[0,0,0],[1e6,0,0],[1e6,1e-6,0],[0,1e-6,0]]") +
                         "," + square("floor", "grey", "[[0,0,-1],[0,1,-1],[1,1,-1],[1,0,-1]]")));
  r = test::runRadkitWithin(
      300, "run '" + thin + "' --patches 10 --no-render --out '" + dir.path("thin") + "'");
  EXPECT_EQ(r.exitCode, 0) << r.output;
}

}  // namespace
}  // namespace radkit
