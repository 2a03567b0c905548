// The fast load path for large meshes (geometry/mesh_stream.cpp): the same vertices and faces as
// the full path (structure check, number check, OpenMesh) on every shipped mesh and on the
// layouts it covers, binary STL welding, and bad input named with its file, element and fix.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "geometry/mesh_reader.h"
#include "geometry/mesh_stream.h"
#include "geometry/scene_loader.h"
#include "tests/common/test_util.h"

namespace radkit {
namespace {

namespace fs = std::filesystem;

void expectSameMesh(const RawMesh& a, const RawMesh& b, const std::string& what) {
  ASSERT_EQ(a.vertices.size(), b.vertices.size()) << what;
  ASSERT_EQ(a.faces.size(), b.faces.size()) << what;
  EXPECT_EQ(a.droppedFaces, b.droppedFaces) << what;
  for (std::size_t v = 0; v < a.vertices.size(); ++v) {
    // Bit for bit (a -0 stays -0).
    ASSERT_EQ(std::memcmp(&a.vertices[v], &b.vertices[v], sizeof(Vec3)), 0)
        << what << ": vertex " << v << " (" << a.vertices[v].x << ", " << a.vertices[v].y << ", "
        << a.vertices[v].z << ") against (" << b.vertices[v].x << ", " << b.vertices[v].y << ", "
        << b.vertices[v].z << ")";
  }
  for (std::size_t f = 0; f < a.faces.size(); ++f)
    ASSERT_EQ(a.faces[f].vertices, b.faces[f].vertices) << what << ": face " << f;
}

/// Reads `path` both ways, requiring that the streaming reader covered it.
void expectStreamedAsFull(const std::string& path, bool repair = false) {
  ASSERT_TRUE(readMeshStreaming(path, repair).has_value()) << path << " took the full path";
  expectSameMesh(readMeshFile(path, repair, {}, true), readMeshFile(path, repair, {}, false), path);
}

TEST(LargeMesh, StreamingReaderMatchesFullReaderOnShippedMeshes) {
  int meshes = 0;
  for (const auto& entry : fs::recursive_directory_iterator(RADKIT_DATA_DIR)) {
    std::string ext = entry.path().extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (!entry.is_regular_file() || (ext != ".off" && ext != ".ply" && ext != ".stl")) continue;
    SCOPED_TRACE(entry.path().string());
    expectStreamedAsFull(entry.path().string());
    ++meshes;
  }
  EXPECT_GE(meshes, 3);
}

// ------------------------------------------------------------------------------ file writers

/// A grid of n×n cells, two triangles a cell, z a gentle wave (no two vertices at a position).
struct Grid {
  int n;
  int vertices() const { return (n + 1) * (n + 1); }
  int faces() const { return 2 * n * n; }
  Vec3 vertex(int k) const {
    const int i = k % (n + 1), j = k / (n + 1);
    const double x = 10.0 * i / n, y = 10.0 * j / n;
    return {x, y, 0.3 * std::sin(0.9 * x) * std::cos(0.7 * y)};
  }
  std::array<int, 3> face(int f) const {
    const int cell = f / 2, i = cell % n, j = cell / n;
    const int a = j * (n + 1) + i, b = a + 1, c = a + n + 2, d = a + n + 1;
    return f % 2 == 0 ? std::array<int, 3>{a, b, c} : std::array<int, 3>{a, c, d};
  }
};

std::string offText(const Grid& g, int nanVertex = -1) {
  std::ostringstream out;
  out.precision(9);
  out << "OFF\n" << g.vertices() << " " << g.faces() << " 0\n";
  for (int v = 0; v < g.vertices(); ++v) {
    const Vec3 p = g.vertex(v);
    if (v == nanVertex)
      out << p.x << " nan " << p.z << "\n";
    else
      out << p.x << " " << p.y << " " << p.z << "\n";
  }
  for (int f = 0; f < g.faces(); ++f) {
    const auto t = g.face(f);
    out << "3 " << t[0] << " " << t[1] << " " << t[2] << "\n";
  }
  return out.str();
}

template <class T>
void put(std::string& out, T value, bool big) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  if (big) std::reverse(bytes, bytes + sizeof(T));
  out.append(bytes, sizeof(T));
}

/// A binary PLY of the grid; `headerVertices`/`headerFaces` override the counts the header
/// declares; double coordinates when `doubles`.
std::string plyBinary(const Grid& g, bool big = false, bool doubles = false, int nanVertex = -1,
                      int headerVertices = -1, int headerFaces = -1) {
  const char* type = doubles ? "double" : "float";
  std::string out =
      std::string("ply\nformat ") + (big ? "binary_big_endian" : "binary_little_endian") +
      " 1.0\ncomment test grid\nelement vertex " +
      std::to_string(headerVertices >= 0 ? headerVertices : g.vertices()) + "\nproperty " + type +
      " x\nproperty " + type + " y\nproperty " + type + " z\nproperty uchar red\nelement face " +
      std::to_string(headerFaces >= 0 ? headerFaces : g.faces()) +
      "\nproperty list uchar int vertex_indices\nend_header\n";
  for (int v = 0; v < g.vertices(); ++v) {
    Vec3 p = g.vertex(v);
    if (v == nanVertex) p.y = std::numeric_limits<double>::quiet_NaN();
    for (double c : {p.x, p.y, p.z}) {
      if (doubles)
        put<double>(out, c, big);
      else
        put<float>(out, float(c), big);
    }
    put<std::uint8_t>(out, 200, big);
  }
  for (int f = 0; f < g.faces(); ++f) {
    put<std::uint8_t>(out, 3, big);
    for (int v : g.face(f)) put<std::int32_t>(out, v, big);
  }
  return out;
}

std::string plyAscii(const Grid& g) {
  std::ostringstream out;
  out.precision(17);
  out << "ply\nformat ascii 1.0\nelement vertex " << g.vertices()
      << "\nproperty double x\nproperty double y\nproperty double z\nelement face " << g.faces()
      << "\nproperty list uchar int vertex_indices\nproperty uchar flags\nend_header\n";
  for (int v = 0; v < g.vertices(); ++v) {
    const Vec3 p = g.vertex(v);
    out << p.x << " " << p.y << " " << p.z << "\n";
  }
  for (int f = 0; f < g.faces(); ++f) {
    const auto t = g.face(f);
    out << "3 " << t[0] << " " << t[1] << " " << t[2] << " 7\n";
  }
  return out.str();
}

/// A binary STL of the grid's triangles: every corner written again, as STL does.
std::string stlBinary(const Grid& g) {
  std::string out(80, ' ');
  put<std::uint32_t>(out, std::uint32_t(g.faces()), false);
  for (int f = 0; f < g.faces(); ++f) {
    for (int k = 0; k < 3; ++k) put<float>(out, 0.0f, false);  // the normal, unread
    for (int v : g.face(f)) {
      const Vec3 p = g.vertex(v);
      for (double c : {p.x, p.y, p.z}) put<float>(out, float(c), false);
    }
    put<std::uint16_t>(out, 0, false);
  }
  return out;
}

TEST(LargeMesh, StreamingReaderMatchesFullReaderOnEachLayout) {
  test::TempDir dir;
  const Grid g{30};
  expectStreamedAsFull(dir.file("g.off", offText(g)));
  expectStreamedAsFull(dir.file("le.ply", plyBinary(g)));
  expectStreamedAsFull(dir.file("be.ply", plyBinary(g, true)));
  expectStreamedAsFull(dir.file("d.ply", plyBinary(g, false, true)));
  expectStreamedAsFull(dir.file("a.ply", plyAscii(g)));
  expectStreamedAsFull(dir.file("g.stl", stlBinary(g)));
  // Comments, blank lines, CRLF and per-face colours (which the full path rewrites for
  // OpenMesh), and quads.
  expectStreamedAsFull(dir.file("c.off",
                                "OFF\r\n# a comment\n\n5 2 0\n0 0 0\n1 0 0 # corner\n1 1 0\n0 1 0\n"
                                "2 0.5 0\n4 0 1 2 3 255 0 0\n3 1 4 2\n"));
  // A mesh the streaming reader leaves to the full path still reads the same.
  const std::string bowtie =
      dir.file("dup.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n1 0 0\n3 0 1 2\n3 0 2 3\n");
  EXPECT_FALSE(readMeshStreaming(bowtie, false).has_value());
  expectSameMesh(readMeshFile(bowtie), readMeshFile(bowtie, false, {}, false), bowtie);
}

TEST(LargeMesh, RepeatedVertexFacesDropAsBeforeWithRepair) {
  test::TempDir dir;
  const std::string path =
      dir.file("r.off", "OFF\n4 3 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 2\n3 0 2 3\n");
  expectStreamedAsFull(path, true);
  EXPECT_EQ(readMeshFile(path, true).droppedFaces, 1u);
  try {
    readMeshFile(path);
    FAIL() << "a face repeating a vertex was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("repeats a vertex"), std::string::npos) << e.what();
  }
}

TEST(LargeMesh, BinaryStlCornersAreWelded) {
  test::TempDir dir;
  const Grid g{40};
  const std::string path = dir.file("w.stl", stlBinary(g));
  const RawMesh raw = readMeshFile(path);
  // Each grid vertex once, numbered by first use; faces as the grid's.
  EXPECT_EQ(raw.vertices.size(), std::size_t(g.vertices()));
  ASSERT_EQ(raw.faces.size(), std::size_t(g.faces()));
  EXPECT_EQ(raw.faces[0].vertices, (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(raw.faces[1].vertices, (std::vector<int>{0, 2, 3}));
  for (std::size_t f = 0; f < raw.faces.size(); ++f) {
    const auto t = g.face(int(f));
    for (int k = 0; k < 3; ++k) {
      const Vec3 want = g.vertex(t[k]);
      const Vec3 got = raw.vertices[raw.faces[f].vertices[k]];
      ASSERT_EQ(got.x, double(float(want.x))) << "face " << f;
      ASSERT_EQ(got.y, double(float(want.y))) << "face " << f;
      ASSERT_EQ(got.z, double(float(want.z))) << "face " << f;
    }
  }
  expectStreamedAsFull(path);
  // -0 and +0 are one position, as OpenMesh's reader welds them.
  std::string signedZero(80, ' ');
  put<std::uint32_t>(signedZero, 2, false);
  const float tris[2][9] = {{0, 0, 0, 1, 0, 0, 0, 1, 0}, {-0.0f, 1, 0, 1, 0, 0, 1, 1, 0}};
  for (const auto& t : tris) {
    for (int k = 0; k < 3; ++k) put<float>(signedZero, 0.0f, false);
    for (float c : t) put<float>(signedZero, c, false);
    put<std::uint16_t>(signedZero, 0, false);
  }
  const std::string zeroPath = dir.file("z.stl", signedZero);
  EXPECT_EQ(readMeshFile(zeroPath).vertices.size(), 4u);
  expectStreamedAsFull(zeroPath);
}

std::string loadError(const std::string& scene);

/// The self-intersection check (a warning) can be skipped for a mesh known to be clean: by the
/// surface's "check_self_intersections": false or LoadOptions::selfIntersections
/// (--skip-self-intersections).
TEST(LargeMesh, SelfIntersectionCheckCanBeSkipped) {
  test::TempDir dir;
  dir.file("x.off",
           "OFF\n6 2 0\n0 0 0\n2 0 0\n0 2 0\n0.5 0.3 -1\n0.5 0.3 1\n0.6 0.8 0\n"
           "3 0 1 2\n3 3 5 4\n");
  auto crossingWarnings = [](const std::string& scene, const LoadOptions& options) {
    LoadReport report;
    loadScene(scene, &report, options);
    int found = 0;
    for (const std::string& w : report.warnings)
      found += w.find("intersects itself") != std::string::npos;
    return found;
  };
  const std::string checked = test::lampMeshScene(dir, "x.off");
  EXPECT_EQ(crossingWarnings(checked, {}), 1);
  LoadOptions skip;
  skip.selfIntersections = false;
  EXPECT_EQ(crossingWarnings(checked, skip), 0);
  const std::string trusted = dir.file(
      "t.json", R"({"materials": {"lamp": {"reflectance": [0.5,0.5,0.5], "emission": [1,1,1]}},
      "surfaces": [{"name": "m", "material": "lamp", "mesh": "x.off",
                    "check_self_intersections": false}]})");
  EXPECT_EQ(crossingWarnings(trusted, {}), 0);
  const std::string wrong = dir.file(
      "w.json", R"({"materials": {"lamp": {"reflectance": [0.5,0.5,0.5], "emission": [1,1,1]}},
      "surfaces": [{"name": "m", "material": "lamp", "mesh": "x.off",
                    "check_self_intersections": "no"}]})");
  EXPECT_NE(loadError(wrong).find("check_self_intersections"), std::string::npos);
}

// ------------------------------------------------------------------------------- bad input

std::string loadError(const std::string& scene) {
  try {
    loadScene(scene);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

void expectMentions(const std::string& message, const std::vector<std::string>& words) {
  EXPECT_FALSE(message.empty()) << "no error";
  for (const std::string& w : words)
    EXPECT_NE(message.find(w), std::string::npos) << "missing '" << w << "' in: " << message;
}

TEST(LargeMesh, TruncatedBinaryPlyIsNamed) {
  test::TempDir dir;
  std::string ply = plyBinary(Grid{50});
  ply.resize(ply.size() - 1000);
  dir.file("t.ply", ply);
  expectMentions(loadError(test::lampMeshScene(dir, "t.ply")), {"t.ply", "truncated", "Fix"});
}

TEST(LargeMesh, PlyPromisingMoreFacesThanItHoldsIsNamed) {
  test::TempDir dir;
  const Grid g{20};
  dir.file("f.ply", plyBinary(g, false, false, -1, -1, g.faces() + 5));
  expectMentions(loadError(test::lampMeshScene(dir, "f.ply")), {"f.ply", "face", "Fix"});
}

TEST(LargeMesh, PlyPromisingMoreVerticesThanItHoldsIsNamed) {
  test::TempDir dir;
  const Grid g{20};
  dir.file("v.ply", plyBinary(g, false, false, -1, g.vertices() + 40));
  expectMentions(loadError(test::lampMeshScene(dir, "v.ply")), {"v.ply", "Fix"});
}

// An ASCII PLY face row that claims more indices than the file could hold (found by fuzzing:
// the count was reserved before it was checked, 600 GB): an error naming the file, no
// allocation without bound.
TEST(LargeMesh, AsciiPlyFaceClaimingBillionsOfIndicesIsNamed) {
  test::TempDir dir;
  dir.file("n.ply",
           "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
           "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
           "end_header\n0 0 0\n1 0 0\n0 1 0\n152000000000 0 1 2\n");
  expectMentions(loadError(test::lampMeshScene(dir, "n.ply")), {"n.ply", "Fix"});
}

/// A million-face mesh with a NaN coordinate half-way: the error names the file, the vertex and
/// the fix; through the command line the run fails and leaves no output folder.
TEST(LargeMesh, NanVertexInAMillionFacesIsNamed) {
  test::TempDir dir;
  const Grid g{708};  // 1 002 528 faces
  ASSERT_GE(g.faces(), 1000000);
  const int bad = g.vertices() / 2;
  dir.file("big.off", offText(g, bad));
  const std::string scene = test::lampMeshScene(dir, "big.off");
  expectMentions(loadError(scene), {"big.off", "'nan'", "vertex " + std::to_string(bad), "Fix"});
  const std::string out = dir.path("out");
  const test::RunResult r = test::runRadkit("run '" + scene +
                                                "' --method hierarchical "
                                                "--no-render --out '" +
                                                out + "'",
                                            300);
  EXPECT_NE(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("vertex " + std::to_string(bad)), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out)) << "output folder left behind";

  // Binary: the coordinate is read, and validation names the vertex.
  fs::remove(dir.path("big.off"));
  dir.file("big.ply", plyBinary(g, false, false, bad));
  expectMentions(loadError(test::lampMeshScene(dir, "big.ply", "", "p.json")),
                 {"big.ply", "vertex " + std::to_string(bad), "NaN", "Fix"});
}

}  // namespace
}  // namespace radkit
