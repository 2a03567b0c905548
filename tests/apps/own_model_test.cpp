// A user's own model, as real files come: an MTL whose name has a space, an MTL value only a
// JSON material can fix, a mesh too large for the dense method, a bare OBJ, a CAD STL in
// millimetres. Each input has the shape of a public file that failed
// (docs/bring-your-own-model.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>

#include "tests/common/test_util.h"
#include "util/canvas.h"
#include "util/vec3.h"

namespace radkit {
namespace {

namespace fs = std::filesystem;
using test::runRadkit;

/// A box's six faces as OBJ text, side `s`, vertex numbers starting at `base` + 1.
std::string objBox(double s, int base) {
  std::ostringstream o;
  for (int k = 0; k < 8; ++k)
    o << "v " << (k & 1 ? s : 0.0) << " " << (k & 2 ? s : 0.0) << " " << (k & 4 ? s : 0.0) << "\n";
  const int f[6][4] = {{1, 3, 4, 2}, {5, 6, 8, 7}, {1, 2, 6, 5},
                       {3, 7, 8, 4}, {1, 5, 7, 3}, {2, 4, 8, 6}};
  for (const auto& q : f)
    o << "f " << q[0] + base << " " << q[1] + base << " " << q[2] + base << " " << q[3] + base
      << "\n";
  return o.str();
}

TEST(OwnModel, AnMtlNameWithASpaceIsRead) {
  // An exporter wrote "mtllib 247_House 15_obj.mtl": tinyobjloader splits at the space.
  test::TempDir dir;
  dir.file("247_House 15_obj.mtl",
           "newmtl wall\nKd 0.6 0.6 0.6\nnewmtl lamp\nKd 0 0 0\nKe 5 5 5\n");
  const std::string obj = dir.file(
      "247_House 15_obj.obj", "mtllib 247_House 15_obj.mtl\no house\nusemtl wall\n" + objBox(1, 0) +
                                  "o lamp\nusemtl lamp\nv 0.4 0.4 0.9\n" +
                                  "v 0.6 0.4 0.9\nv 0.6 0.6 0.9\nv 0.4 0.6 0.9\nf 9 10 11 12\n");
  auto r = runRadkit("mesh '" + obj + "' --out '" + dir.path("o") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("materials: 2"), std::string::npos) << r.output;
  // A missing MTL names the path it looked for.
  fs::remove(dir.path("247_House 15_obj.mtl"));
  r = runRadkit("mesh '" + obj + "' --out '" + dir.path("o2") + "'");
  EXPECT_NE(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("looked for"), std::string::npos) << r.output;
}

TEST(OwnModel, AJsonMaterialFixesAnMtlValueRadkitRefuses) {
  // Sponza's MTL gives a window Kd 1: refused as an MTL value, fixable from JSON.
  test::TempDir dir;
  dir.file("sponza.mtl", "newmtl stone\nKd 0.5 0.5 0.5\nnewmtl window\nKd 1 1 1\n");
  dir.file("sponza.obj", "mtllib sponza.mtl\no hall\nusemtl stone\n" + objBox(2, 0) +
                             "o glass\nusemtl window\nv 0.5 0.5 1\nv 1.5 0.5 1\nv 1.5 1.5 1\n"
                             "f 9 10 11\n");
  const std::string bare = dir.file(
      "bare.json", R"({"materials": {"lamp": {"reflectance": [0,0,0], "emission": [5,5,5]}},
        "surfaces": [{"include": "sponza.obj"},
          {"name": "lamp", "material": "lamp", "polygon": [[0.8,0.8,1.9],[1.2,0.8,1.9],[1.2,1.2,1.9],[0.8,1.2,1.9]]}]})");
  auto r = runRadkit("mesh '" + bare + "' --out '" + dir.path("a") + "'");
  EXPECT_NE(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("window"), std::string::npos) << r.output;
  const std::string fixed = dir.file(
      "fixed.json", R"({"materials": {"lamp": {"reflectance": [0,0,0], "emission": [5,5,5]},
                     "window": {"reflectance": [0.8,0.8,0.8]}},
        "surfaces": [{"include": "sponza.obj"},
          {"name": "lamp", "material": "lamp", "polygon": [[0.8,0.8,1.9],[1.2,0.8,1.9],[1.2,1.2,1.9],[0.8,1.2,1.9]]}]})");
  r = runRadkit("mesh '" + fixed + "' --out '" + dir.path("b") + "'");
  EXPECT_EQ(r.exitCode, 0) << r.output;
}

TEST(OwnModel, ABareObjIsToldBothRoutes) {
  test::TempDir dir;
  const std::string obj = dir.file("scan.obj", objBox(1, 0));
  const auto r = runRadkit("mesh '" + obj + "' --out '" + dir.path("o") + "'");
  EXPECT_NE(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("usemtl"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("\"mesh\": \"scan.obj\""), std::string::npos) << r.output;
  // A bare STL, PLY or OFF given as the scene is told the same two ways, not "unknown format".
  for (const char* name : {"part.STL", "scan.ply", "model.off"}) {
    const std::string mesh = dir.file(name, "solid x\nendsolid x\n");
    const auto m = runRadkit("run '" + mesh + "' --out '" + dir.path("m") + "'");
    EXPECT_NE(m.exitCode, 0) << m.output;
    EXPECT_NE(m.output.find("without materials or lights"), std::string::npos) << m.output;
    EXPECT_NE(m.output.find("make_model_room.py"), std::string::npos) << m.output;
    EXPECT_FALSE(fs::exists(dir.path("m")));
  }
}

TEST(OwnModel, ADenseRunAtItsPatchFloorNamesTheHierarchicalMethod) {
  // Two 2 048-triangle grids facing each other: with 1 MiB for F, fewer patches cannot help.
  test::TempDir dir;
  std::ostringstream off;
  const int n = 32;
  off << "OFF\n" << (n + 1) * (n + 1) << " " << 2 * n * n << " 0\n";
  for (int y = 0; y <= n; ++y)
    for (int x = 0; x <= n; ++x) off << double(x) / n << " " << double(y) / n << " 0\n";
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const int a = y * (n + 1) + x, b = a + 1, c = a + n + 2, d = a + n + 1;
      off << "3 " << a << " " << b << " " << c << "\n3 " << a << " " << c << " " << d << "\n";
    }
  dir.file("grid.off", off.str());
  const std::string scene =
      dir.file("s.json", R"({"materials": {"grey": {"reflectance": [0.5,0.5,0.5]},
                                  "lamp": {"reflectance": [0,0,0], "emission": [1,1,1]}},
        "surfaces": [{"name": "floor", "material": "grey", "mesh": "grid.off"},
          {"name": "ceiling", "material": "grey", "mesh": "grid.off", "reverse": true,
           "transform": {"translate": [0, 0, 1]}},
          {"name": "lamp", "material": "lamp", "polygon": [[0.4,0.4,0.5],[0.6,0.4,0.5],[0.6,0.6,0.5],[0.4,0.6,0.5]]}]})");
  const auto r =
      runRadkit("run '" + scene + "' --patches 10 --memory-budget 1MiB --no-render --out '" +
                dir.path("o") + "'");
  EXPECT_NE(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("at its floor"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("--method hierarchical"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir.path("o")));
  // Split four ways (about 16 400 patches): fewer patches are offered only when the floor of
  // one patch per face (4 097 patches: F at least 64 MiB in float) fits the budget.
  auto refused = [&](const std::string& budget) {
    return runRadkit("run '" + scene + "' --max-area 1.3e-4 --memory-budget " + budget +
                     " --no-render --out '" + dir.path("o") + "'");
  };
  auto tight = refused("1MiB");
  EXPECT_NE(tight.exitCode, 0) << tight.output;
  EXPECT_NE(tight.output.find("cannot help enough"), std::string::npos) << tight.output;
  EXPECT_EQ(tight.output.find("use fewer patches"), std::string::npos) << tight.output;
  auto roomy = refused("100MiB");
  EXPECT_NE(roomy.exitCode, 0) << roomy.output;
  EXPECT_NE(roomy.output.find("Fewer patches help down to about 4097"), std::string::npos)
      << roomy.output;
}

/// An ASCII STL of an axis-aligned box `w` long in x (a bolt's bounding shape).
std::string stlBox(double w) {
  std::ostringstream o;
  o << "solid bolt\n";
  const double v[8][3] = {{0, 0, 0}, {w, 0, 0}, {0, 8, 0}, {w, 8, 0},
                          {0, 0, 8}, {w, 0, 8}, {0, 8, 8}, {w, 8, 8}};
  const int t[12][3] = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                        {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  for (const auto& f : t) {
    o << "facet normal 0 0 0\nouter loop\n";
    for (int k : f) o << "vertex " << v[k][0] << " " << v[k][1] << " " << v[k][2] << "\n";
    o << "endloop\nendfacet\n";
  }
  return o.str() + "endsolid bolt\n";
}

TEST(OwnModel, ACadStlInMillimetresIsNamedWhenReadAsMetres) {
  test::TempDir dir;
  dir.file("bolt.stl", stlBox(31));  // 31 × 8 × 8 mm
  const std::string room =
      dir.file("room.json", R"({"materials": {"steel": {"reflectance": [0.5,0.5,0.5]},
                                     "lamp": {"reflectance": [0,0,0], "emission": [1,1,1]}},
        "surfaces": [{"name": "bolt", "material": "steel", "mesh": "bolt.stl"},
          {"name": "lamp", "material": "lamp", "polygon": [[0,0,3],[0,4,3],[4,4,3],[4,0,3]]},
          {"name": "floor", "material": "steel", "polygon": [[0,0,0],[4,0,0],[4,4,0],[0,4,0]]}]})");
  auto r = runRadkit("mesh '" + room + "' --out '" + dir.path("a") + "'");
  EXPECT_NE(r.output.find("bolt.stl"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("\"scale\": 0.001"), std::string::npos) << r.output;
  // Scaled to millimetres it is a bolt, and nothing is said.
  const std::string fixedRoom =
      dir.file("fixed.json", R"({"materials": {"steel": {"reflectance": [0.5,0.5,0.5]},
                                     "lamp": {"reflectance": [0,0,0], "emission": [1,1,1]}},
        "surfaces": [{"name": "bolt", "material": "steel", "mesh": "bolt.stl", "transform": {"scale": 0.001}},
          {"name": "lamp", "material": "lamp", "polygon": [[0,0,3],[0,4,3],[4,4,3],[4,0,3]]},
          {"name": "floor", "material": "steel", "polygon": [[0,0,0],[4,0,0],[4,4,0],[0,4,0]]}]})");
  r = runRadkit("mesh '" + fixedRoom + "' --out '" + dir.path("b") + "'");
  EXPECT_EQ(r.output.find("carry no unit"), std::string::npos) << r.output;
  // Alone in its scene, the fix is --units mm.
  const std::string lone = test::lampMeshScene(dir, "bolt.stl", "", "lone.json");
  r = runRadkit("mesh '" + lone + "' --out '" + dir.path("c") + "'");
  EXPECT_NE(r.output.find("--units mm"), std::string::npos) << r.output;
  // A 310 mm part read as 310 m is also beyond the scene-wide check's 200 m: one warning,
  // the one naming the file, says it.
  dir.file("bolt.stl", stlBox(310));
  r = runRadkit("mesh '" + lone + "' --out '" + dir.path("c2") + "'");
  EXPECT_NE(r.output.find("bolt.stl"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("the scene spans"), std::string::npos) << r.output;
  dir.file("bolt.stl", stlBox(31));
  r = runRadkit("mesh '" + lone + "' --units mm --out '" + dir.path("d") + "'");
  EXPECT_EQ(r.output.find("carry no unit"), std::string::npos) << r.output;
}

TEST(OwnModel, FacesOpenMeshCannotJoinAreReportedInRadkitsWords) {
  // A closed fan around a vertex and one more face touching only that vertex: OpenMesh printed
  // "PolyMeshT::add_face: complex vertex" with no file or face.
  test::TempDir dir;
  dir.file("fan.obj",
           "v 0 0 0\nv 1 0 0\nv 0 1 0\nv -1 0 0\nv 0 -1 0\nv 0 0.3 1\nv 0.3 0 1\n"
           "f 1 2 3\nf 1 3 4\nf 1 4 5\nf 1 5 2\nf 1 7 6\n");
  const std::string scene =
      dir.file("s.json", R"({"materials": {"grey": {"reflectance": [0.5,0.5,0.5]},
                                  "lamp": {"reflectance": [0,0,0], "emission": [1,1,1]}},
        "surfaces": [{"name": "fan", "material": "grey", "mesh": "fan.obj"},
          {"name": "lamp", "material": "lamp", "polygon": [[-1,-1,4],[-1,1,4],[1,1,4],[1,-1,4]]}]})");
  const auto r = runRadkit("mesh '" + scene + "' --out '" + dir.path("o") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(r.output.find("PolyMeshT"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("fan.obj): 1 of its 5 faces (the first is face 4)"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("input faces: 6"), std::string::npos) << "a face was lost\n" << r.output;
}

TEST(OwnModel, ADiffuseTextureGivesItsMeanLinearColour) {
  // A 2×2 binary PPM: red, green, blue and sRGB grey 128 (linear 0.2158605).
  test::TempDir dir;
  const unsigned char px[12] = {255, 0, 0, 0, 255, 0, 0, 0, 255, 128, 128, 128};
  dir.file("tex.ppm", "P6\n2 2\n255\n" + std::string(reinterpret_cast<const char*>(px), 12));
  dir.file("m.mtl",
           "newmtl painted\nKd 0.5 0.5 0.5\nmap_Kd tex.ppm\n"
           "newmtl lost\nKd 0.25 0.25 0.25\nmap_Kd textures\\missing.png\n"
           "newmtl lamp\nKd 0 0 0\nKe 1 1 1\n");
  const std::string obj =
      dir.file("m.obj",
               "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 3 0 0\nv 3 1 0\n"
               "v 0 0 1\nv 0 1 1\nv 1 1 1\n"
               "o painted\nusemtl painted\nf 1 2 3 4\no lost\nusemtl lost\nf 5 6 7\n"
               "o lamp\nusemtl lamp\nf 8 10 9\n");
  const auto r = runRadkit("mesh '" + obj + "' --out '" + dir.path("o") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("map_Kd tex.ppm read as its mean linear colour"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("missing.png cannot be read"), std::string::npos) << r.output;
  const double grey = 0.2158605001138992;  // ((128/255 + 0.055)/1.055)^2.4
  const double mean = (1 + grey) / 4;
  bool painted = false, lost = false;
  for (auto& row : test::readCsv(dir.path("o/patches.csv"))) {
    if (row["surface"] == "painted") {
      painted = true;
      EXPECT_NEAR(std::stod(row["rho_r"]), mean, 1e-12);
      EXPECT_NEAR(std::stod(row["rho_g"]), mean, 1e-12);
      EXPECT_NEAR(std::stod(row["rho_b"]), mean, 1e-12);
    } else if (row["surface"] == "lost") {
      lost = true;
      EXPECT_EQ(std::stod(row["rho_r"]), 0.25);  // Kd kept
    }
  }
  EXPECT_TRUE(painted && lost);
}

/// A PLY whose surface is given as triangle strips (as Stanford's igea.ply): 8 vertices, one
/// row "3 0 4 1 5 2 -1 6 3 7" (two strips), in ASCII or binary little-endian.
std::string stripPly(bool binary) {
  const float v[8][3] = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0},
                         {1, 1, 0}, {2, 1, 0}, {0, 3, 0}, {1, 3, 0}};
  const int strip[10] = {3, 0, 4, 1, 5, 2, -1, 6, 3, 7};
  std::string out = std::string("ply\nformat ") + (binary ? "binary_little_endian" : "ascii") +
                    " 1.0\nelement vertex 8\nproperty float x\nproperty float y\n"
                    "property float z\nelement tristrips 1\nproperty list int int "
                    "vertex_indices\nend_header\n";
  if (!binary) {
    std::ostringstream o;
    for (const auto& p : v) o << p[0] << " " << p[1] << " " << p[2] << "\n";
    o << 10;
    for (int i : strip) o << " " << i;
    return out + o.str() + "\n";
  }
  out.append(reinterpret_cast<const char*>(v), sizeof v);  // x86: little-endian already
  const int count = 10;
  out.append(reinterpret_cast<const char*>(&count), 4);
  out.append(reinterpret_cast<const char*>(strip), sizeof strip);
  return out;
}

TEST(OwnModel, TriangleStripsOfAPlyAreRead) {
  // OpenMesh reads no "tristrips" element: igea.ply loaded as a mesh without faces.
  for (bool binary : {false, true}) {
    SCOPED_TRACE(binary ? "binary" : "ascii");
    test::TempDir dir;
    dir.file("strip.ply", stripPly(binary));
    const std::string scene = test::lampMeshScene(dir, "strip.ply");
    const auto r = runRadkit("mesh '" + scene + "' --out '" + dir.path("o") + "'");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    // Four triangles of 0.5 m² from the first strip, one of 1 m² from the second, one winding.
    EXPECT_NE(r.output.find("input faces: 5"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("total area: 3 m²"), std::string::npos) << r.output;
    for (auto& row : test::readCsv(dir.path("o/patches.csv"))) EXPECT_EQ(row["nz"], "1");
  }
}

TEST(OwnModel, TransformTurnsAZUpModelAndRotates) {
  // The floor of a z-up CAD model (a quad facing +z) stands in radkit's y-up room with
  // "up": "z"; "rotate" and "euler_deg" then turn it about radkit's axes.
  test::TempDir dir;
  dir.file("floor.obj", "v 0 0 0\nv 2 0 0\nv 2 1 0\nv 0 1 0\nf 1 2 3 4\n");
  const std::pair<std::string, std::array<double, 3>> cases[] = {
      {R"({"up": "z"})", {0, 1, 0}},
      {R"({"rotate": {"axis": [0, 1, 0], "degrees": 90}})", {1, 0, 0}},
      {R"({"euler_deg": [0, 90, 0]})", {1, 0, 0}},
      {R"({"up": "z", "euler_deg": [0, 0, 90]})", {-1, 0, 0}},
      {R"({"up": "z", "scale": [1, -1, 1]})", {0, -1, 0}}};  // the front side is mirrored too
  for (const auto& [transform, normal] : cases) {
    SCOPED_TRACE(transform);
    const std::string scene = test::lampMeshScene(dir, "floor.obj", transform);
    fs::remove_all(dir.path("o"));
    const auto r = runRadkit("mesh '" + scene + "' --out '" + dir.path("o") + "'");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    for (auto& row : test::readCsv(dir.path("o/patches.csv"))) {
      EXPECT_NEAR(std::stod(row["nx"]), normal[0], 1e-12);
      EXPECT_NEAR(std::stod(row["ny"]), normal[1], 1e-12);
      EXPECT_NEAR(std::stod(row["nz"]), normal[2], 1e-12);
    }
  }
  const std::string bad = test::lampMeshScene(dir, "floor.obj", R"({"up": "w"})", "bad.json");
  const auto r = runRadkit("mesh '" + bad + "' --out '" + dir.path("b") + "'");
  EXPECT_NE(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("z-up model"), std::string::npos) << r.output;
}

TEST(OwnModel, AClosedRoomIsDrawnFromInsideAndABlackPictureIsNamed) {
  test::TempDir dir;
  const std::string scene =
      dir.file("room.json", R"({"materials": {"wall": {"reflectance": [0.6,0.6,0.6]},
                                     "lamp": {"reflectance": [0,0,0], "emission": [10,10,10]}},
        "surfaces": [
          {"name": "floor", "material": "wall", "polygon": [[0,0,0],[0,0,5],[4,0,5],[4,0,0]]},
          {"name": "ceiling", "material": "wall", "polygon": [[0,3,0],[4,3,0],[4,3,5],[0,3,5]]},
          {"name": "west", "material": "wall", "polygon": [[0,0,0],[0,3,0],[0,3,5],[0,0,5]]},
          {"name": "east", "material": "wall", "polygon": [[4,0,0],[4,0,5],[4,3,5],[4,3,0]]},
          {"name": "south", "material": "wall", "polygon": [[0,0,0],[4,0,0],[4,3,0],[0,3,0]]},
          {"name": "north", "material": "wall", "polygon": [[0,0,5],[0,3,5],[4,3,5],[4,0,5]]},
          {"name": "lamp", "material": "lamp", "polygon": [[1.5,2.9,2],[2.5,2.9,2],[2.5,2.9,3],[1.5,2.9,3]]}]})");
  auto r =
      runRadkit("run '" + scene + "' --patches 200 --size 32x24 --out '" + dir.path("a") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(r.output.find("is black"), std::string::npos) << r.output;
  const Canvas png = readPng(dir.path("a/render.png"));
  double sum = 0;
  for (int y = 0; y < png.height(); ++y)
    for (int x = 0; x < png.width(); ++x) sum += png.at(x, y).r;
  EXPECT_GT(sum / (png.width() * png.height()), 20) << "a dark picture of the room";
  // A camera outside, looking away: black, and said.
  r = runRadkit("run '" + scene +
                "' --patches 200 --size 32x24 --camera 2,1.5,-10,2,1.5,-20 --out '" +
                dir.path("b") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("render.png is black"), std::string::npos) << r.output;
}

/// Width and height from a PNG's IHDR chunk.
std::pair<int, int> pngSize(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  unsigned char h[24] = {};
  in.read(reinterpret_cast<char*>(h), 24);
  auto be = [&](int at) {
    return (h[at] << 24) | (h[at + 1] << 16) | (h[at + 2] << 8) | h[at + 3];
  };
  return {be(16), be(20)};
}

TEST(OwnModel, RunTakesRendersSizeSpellingAndKeepsTheOldOne) {
  test::TempDir dir;
  const std::string box = test::dataPath("cornell-box.json");
  auto r = runRadkit("run '" + box + "' --patches 60 --size 40x24 --out '" + dir.path("a") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(pngSize(dir.path("a/render.png")), std::make_pair(40, 24));
  r = runRadkit("run '" + box + "' --patches 60 --image-size 32 --out '" + dir.path("b") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("--image-size is deprecated: use --size 32x32"), std::string::npos)
      << r.output;
  EXPECT_EQ(pngSize(dir.path("b/render.png")), std::make_pair(32, 32));
  r = runRadkit("run '" + box + "' --patches 60 --size 40x24 --image-size 32 --out '" +
                dir.path("c") + "'");
  EXPECT_NE(r.exitCode, 0) << r.output;
}

}  // namespace
}  // namespace radkit

namespace radkit {
namespace {

/// Mean sRGB colour of a PNG's pixels in [x0, x1) × [y0, y1), as fractions of the size.
Vec3 meanPng(const Canvas& c, double x0, double x1, double y0, double y1) {
  Vec3 sum;
  int n = 0;
  for (int y = int(y0 * c.height()); y < int(y1 * c.height()); ++y)
    for (int x = int(x0 * c.width()); x < int(x1 * c.width()); ++x, ++n)
      sum += Vec3{double(c.at(x, y).r), double(c.at(x, y).g), double(c.at(x, y).b)};
  return sum / std::max(1, n);
}

// docs/bring-your-own-model.md's walkthrough files (data/tools/make_own_models.py): an
// OBJ + MTL room with textures given directly, and a CAD STL in mm, z up, in a JSON scene.
TEST(OwnModel, TheWalkthroughModelsGiveLitPicturesFromSensibleCameras) {
  test::TempDir dir;
  ASSERT_EQ(std::system(("python3 '" + test::dataPath("tools/make_own_models.py") + "' '" +
                         dir.path("own") + "' > /dev/null")
                            .c_str()),
            0);
  // The room: no camera in an OBJ, so radkit puts one inside, looking down the room's long
  // axis at the north wall, where the painting (its texture's mean: blue-green) hangs.
  auto r = runRadkit("run '" + dir.path("own/textured-room/room.obj") +
                         "' --patches 800 --size 64x64 --out '" + dir.path("room") + "'",
                     600);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("map_Kd textures/planks.png read as its mean linear colour"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find("is black"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("repeat the position"), std::string::npos) << r.output;
  const Canvas room = readPng(dir.path("room/render.png"));
  const Vec3 whole = meanPng(room, 0, 1, 0, 1), middle = meanPng(room, 0.45, 0.55, 0.4, 0.5);
  EXPECT_GT(whole.x + whole.y + whole.z, 3 * 60) << "a dark picture of the room";
  EXPECT_GT(middle.y, middle.x + 20) << "the painting should be in the middle of the picture";
  EXPECT_GT(middle.z, middle.x + 20) << "the painting should be in the middle of the picture";
  // The bracket: with "up" and "scale" it stands 60 mm tall in the light box, lit, and no
  // unit warning is given; without the scale it is named as an 80 m part in a 0.6 m box.
  r = runRadkit("run '" + dir.path("own/workshop.json") + "' --patches 800 --size 64x64 --out '" +
                    dir.path("ws") + "'",
                600);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(r.output.find("carry no unit"), std::string::npos) << r.output;
  bool bracketLit = false;
  for (const auto& row : test::readCsv(dir.path("ws/surfaces.csv")))
    if (row.at("surface") == "bracket") bracketLit = std::stod(row.at("b_g_W_m2")) > 0.5;
  EXPECT_TRUE(bracketLit);
  std::ifstream in(dir.path("own/workshop.json"));
  std::string text((std::istreambuf_iterator<char>(in)), {});
  const std::string scale = "\"scale\": 0.001";
  ASSERT_NE(text.find(scale), std::string::npos);
  text.replace(text.find(scale), scale.size(), "\"scale\": 1");
  const std::string unscaled = dir.file("own/unscaled.json", text);
  r = runRadkit("mesh '" + unscaled + "' --out '" + dir.path("unscaled") + "'", 300);
  EXPECT_NE(r.output.find("bracket.stl"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("\"scale\": 0.001"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace radkit

namespace radkit {
namespace {

// data/tools/make_model_room.py reads every mesh radkit reads (here a binary PLY and an ASCII
// STL), stands a z-up model upright with --up z, and refuses a point cloud before writing.
TEST(OwnModel, TheRoomToolReadsBinaryPlyAndAsciiStlAndStandsAZUpModelUp) {
  test::TempDir dir;
  // A 1 × 1 × 3 block, tall along z, as a binary little-endian PLY of 12 triangles.
  const double v[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                          {0, 0, 3}, {1, 0, 3}, {1, 1, 3}, {0, 1, 3}};
  const int f[12][3] = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                        {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
  std::string ply =
      "ply\nformat binary_little_endian 1.0\nelement vertex 8\nproperty float x\n"
      "property float y\nproperty float z\nelement face 12\n"
      "property list uchar int vertex_indices\nend_header\n";
  for (const auto& p : v)
    for (double c : p) {
      const float x = float(c);
      ply.append(reinterpret_cast<const char*>(&x), 4);
    }
  for (const auto& t : f) {
    ply.push_back(3);
    ply.append(reinterpret_cast<const char*>(t), 12);
  }
  dir.file("tall.ply", ply);
  std::string stl = "solid tall\n";
  for (const auto& t : f) {
    stl += "facet normal 0 0 0\nouter loop\n";
    for (int k : t)
      stl += "vertex " + std::to_string(v[k][0]) + " " + std::to_string(v[k][1]) + " " +
             std::to_string(v[k][2]) + "\n";
    stl += "endloop\nendfacet\n";
  }
  dir.file("tall.stl", stl + "endsolid tall\n");
  auto room = [&](const std::string& model, const std::string& up) {
    const std::string scene = dir.path(model + up + ".json");
    const int rc = std::system(("python3 '" + test::dataPath("tools/make_model_room.py") + "' '" +
                                dir.path(model) + "' --out '" + scene + "'" +
                                (up.empty() ? "" : " --up " + up) + " > /dev/null 2>&1")
                                   .c_str());
    return std::make_pair(rc, scene);
  };
  // The model's height: the largest y of its patch centroids (its top is at 1.2 m upright).
  auto height = [&](const std::string& scene) {
    const auto r = runRadkit("mesh '" + scene + "' --out '" + scene + ".out'", 300);
    EXPECT_EQ(r.exitCode, 0) << r.output;
    double top = 0;
    for (const auto& row : test::readCsv(scene + ".out/patches.csv"))
      if (row.at("surface") == "model") top = std::max(top, std::stod(row.at("cy_m")));
    return top;
  };
  for (const std::string model : {"tall.ply", "tall.stl"}) {
    SCOPED_TRACE(model);
    const auto [rcUp, upright] = room(model, "z");
    ASSERT_EQ(rcUp, 0);
    EXPECT_NEAR(height(upright), 1.2, 1e-6) << "stood up: 3 (its largest side) scaled to 1.2 m";
    const auto [rcFlat, flat] = room(model, "");
    ASSERT_EQ(rcFlat, 0);
    EXPECT_NEAR(height(flat), 0.4, 1e-6) << "lying as written: its y side, 1 of 3, is 0.4 m";
  }
  // A point cloud (vertices, no faces) is refused by the tool, with nothing written.
  dir.file("cloud.ply",
           "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
           "property float z\nend_header\n0 0 0\n1 0 0\n0 1 0\n");
  const auto [rcCloud, cloud] = room("cloud.ply", "");
  EXPECT_NE(rcCloud, 0);
  EXPECT_FALSE(fs::exists(cloud));
}

}  // namespace
}  // namespace radkit
