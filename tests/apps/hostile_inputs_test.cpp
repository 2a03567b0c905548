// Inputs an attacker or a careless user gives: folders radkit must not touch, paths that are not
// regular files, names that try to leave out/, numbers a double cannot carry, comments the mesh
// reader choked on, media that would never finish, and scenes that are valid but wrong. Each
// run is refused with a message naming the input and a fix, or (for legal input) read right.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "tests/common/test_util.h"

namespace radkit {
namespace {

namespace fs = std::filesystem;
using test::dataPath;
using test::runRadkit;
using test::runRadkitWithin;

const char* kRoom = R"({"materials": {"grey": {"reflectance": [0.5,0.5,0.5]},
    "lamp": {"reflectance": [0,0,0], "emission": [EMISSION]}},
  "surfaces": [
    {"name": "floor", "material": "grey", "polygon": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]]},
    {"name": "lamp", "material": "lamp", "polygon": [[0,0,1],[0,1,1],[1,1,1],[1,0,1]]}]})";

std::string room(const std::string& emission = "1,1,1") {
  std::string s = kRoom;
  s.replace(s.find("EMISSION"), 8, emission);
  return s;
}

std::string fileText(const std::string& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(HostileInputs, AFolderWithAReportJsonIsNotRadkitsToDelete) {
  test::TempDir dir;
  const std::string scene = dir.file("room.json", room());
  fs::create_directories(dir.path("thesis"));
  dir.file("thesis/report.json", "{}");
  dir.file("thesis/thesis.tex", "three years of work");
  const auto r =
      runRadkit("run '" + scene + "' --patches 8 --no-render --out '" + dir.path("thesis") + "'");
  EXPECT_NE(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("did not mark"), std::string::npos) << r.output;
  EXPECT_EQ(fileText(dir.path("thesis/thesis.tex")), "three years of work");
  // The folder radkit writes is radkit's: a second run replaces it.
  ASSERT_EQ(runRadkit("run '" + scene + "' --patches 8 --no-render --out '" + dir.path("o") + "'")
                .exitCode,
            0);
  const auto again =
      runRadkit("run '" + scene + "' --patches 8 --no-render --out '" + dir.path("o") + "'");
  EXPECT_EQ(again.exitCode, 0) << again.output;
}

TEST(HostileInputs, ASceneNameStaysOnePathComponentUnderOut) {
  test::TempDir dir;
  const std::string work = dir.path("a/b");
  fs::create_directories(work);
  const std::string scene = dir.file("room.json", "{\"name\": \"../../x\", " + room().substr(1));
  const std::string cmd = "cd '" + work + "' && '" + RADKIT_BINARY + "' run '" + scene +
                          "' --patches 8 --no-render >/dev/null 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  EXPECT_FALSE(fs::exists(dir.path("x"))) << "wrote outside out/";
  EXPECT_TRUE(fs::exists(work + "/out/_._.._x/report.json"));
}

TEST(HostileInputs, OutputsOntoDevicesAndPipesAreRefused) {
  test::TempDir dir;
  const std::string scene = dir.file("room.json", room());
  fs::create_symlink("/dev/null", dir.path("null.png"));
  auto r = runRadkit("render '" + scene + "' --patches 8 --out '" + dir.path("null.png") + "'");
  EXPECT_NE(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("character device"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
  ASSERT_EQ(::mkfifo(dir.path("pipe.png").c_str(), 0600), 0);
  r = runRadkitWithin(60,
                      "render '" + scene + "' --patches 8 --out '" + dir.path("pipe.png") + "'");
  EXPECT_NE(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("named pipe"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::is_fifo(dir.path("pipe.png")));
}

TEST(HostileInputs, PipesGivenAsInputsAreRefusedNotWaitedOn) {
  test::TempDir dir;
  const std::string scene = dir.file("room.json", room());
  ASSERT_EQ(::mkfifo(dir.path("ref.pfm").c_str(), 0600), 0);
  auto r = runRadkitWithin(60, "render '" + scene + "' --patches 8 --reference '" +
                                   dir.path("ref.pfm") + "' --out '" + dir.path("i.pfm") + "'");
  EXPECT_NE(r.exitCode, 0) << r.output;
  EXPECT_NE(r.exitCode, 124) << "waited on the pipe";
  EXPECT_NE(r.output.find("not a regular file"), std::string::npos) << r.output;
  ASSERT_EQ(::mkfifo(dir.path("clouds.json").c_str(), 0600), 0);
  r = runRadkitWithin(
      60, "clouds --scene '" + dir.path("clouds.json") + "' --out '" + dir.path("c") + "'");
  EXPECT_NE(r.exitCode, 0) << r.output;
  EXPECT_NE(r.exitCode, 124) << "waited on the pipe";
  EXPECT_NE(r.output.find("not a regular file"), std::string::npos) << r.output;
}

/// A 4×2 colour PFM (little-endian) whose pixel (x, y) channel c holds `value`, 0.5 elsewhere.
std::string pfm(int x, int y, int c, float value) {
  std::string data = "PF\n4 2\n-1\n";
  for (int row = 1; row >= 0; --row)  // bottom row first
    for (int col = 0; col < 4; ++col)
      for (int ch = 0; ch < 3; ++ch) {
        const float v = (col == x && row == y && ch == c) ? value : 0.5f;
        char bytes[4];
        std::memcpy(bytes, &v, 4);
        data.append(bytes, 4);
      }
  return data;
}

TEST(HostileInputs, ANonFiniteOrNegativeReferencePixelIsNamed) {
  test::TempDir dir;
  const std::string scene = dir.file("room.json", room());
  const float bad[] = {std::numeric_limits<float>::quiet_NaN(),
                       std::numeric_limits<float>::infinity(), -1.0f};
  for (float v : bad) {
    const std::string ref = dir.file("ref.pfm", pfm(2, 1, 1, v));
    const auto r = runRadkit("render '" + scene + "' --patches 8 --reference '" + ref +
                             "' --out '" + dir.path("i.pfm") + "'");
    EXPECT_NE(r.exitCode, 0) << v << "\n" << r.output;
    EXPECT_NE(r.output.find("pixel (2, 1) channel 1"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir.path("i.pfm")));
  }
}

TEST(HostileInputs, AnOffCommentAfterTheHeaderIsRead) {
  test::TempDir dir;
  dir.file("quad.off",
           "OFF\n# written by a CAD exporter\n4 1 0\n# the corners\n0 0 0\n1 0 0 # first edge\n"
           "1 1 0\n0 1 0\n\n4 0 1 2 3\n");
  const std::string scene = test::lampMeshScene(dir, "quad.off");
  const auto r = runRadkitWithin(120, "mesh '" + scene + "' --out '" + dir.path("o") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("surfaces: 1"), std::string::npos) << r.output;
}

TEST(HostileInputs, MsvcNanTextIsNotReadAsOne) {
  test::TempDir dir;
  dir.file("t.obj", "v 0 0 0\nv 1.#QNAN 0 0\nv 0 1 0\nf 1 2 3\n");
  const std::string scene = test::lampMeshScene(dir, "t.obj");
  const auto r = runRadkit("mesh '" + scene + "' --out '" + dir.path("o") + "'");
  EXPECT_NE(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("1.#QNAN"), std::string::npos) << r.output;
}

TEST(HostileInputs, AnUnreadableMeshIsNotCalledEmpty) {
  if (::geteuid() == 0) GTEST_SKIP() << "root reads files whatever their permissions";
  test::TempDir dir;
  dir.file("t.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  ASSERT_EQ(::chmod(dir.path("t.off").c_str(), 0), 0);
  const std::string scene = test::lampMeshScene(dir, "t.off");
  const auto r = runRadkit("mesh '" + scene + "' --out '" + dir.path("o") + "'");
  EXPECT_NE(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("cannot be read"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("empty"), std::string::npos) << r.output;
}

TEST(HostileInputs, DenseCloudsBeyondTheTrackingBoundAreRefused) {
  test::TempDir dir;
  for (const char* extinction : {"1e300", "1e6"}) {
    const auto r = runRadkitWithin(60, std::string("clouds --extinction ") + extinction +
                                           " --samples 1 --out '" + dir.path("c") + "'");
    EXPECT_NE(r.exitCode, 0) << r.output;
    EXPECT_NE(r.exitCode, 124) << "delta tracking ran";
    EXPECT_NE(r.output.find("optical extent"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir.path("c")));
  }
}

TEST(HostileInputs, CoincidentFacesOfTwoSurfacesAreNamed) {
  test::TempDir dir;
  std::string s = room();
  s.insert(s.rfind(']'), R"(, {"name": "floor copy", "material": "grey",
                              "polygon": [[1,0,0],[1,1,0],[0,1,0],[0,0,0]]})");
  const std::string scene = dir.file("room.json", s);
  for (const char* method : {"dense", "hierarchical"}) {
    const auto r = runRadkit("run '" + scene + "' --method " + method +
                             (std::string(method) == "dense" ? " --patches 8" : "") +
                             " --no-render --out '" + dir.path("o") + "'");
    EXPECT_NE(r.output.find("\"floor\""), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("\"floor copy\""), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("coincident face"), std::string::npos) << r.output;
  }
  // Back to back is a two-sided panel, not a copy.
  s = room();
  s.insert(s.rfind(']'), R"(, {"name": "floor underside", "material": "grey",
                              "polygon": [[0,0,0],[0,1,0],[1,1,0],[1,0,0]]})");
  const auto r = runRadkit("mesh '" + dir.file("b.json", s) + "' --out '" + dir.path("m") + "'");
  EXPECT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(r.output.find("coincident"), std::string::npos) << r.output;
}

TEST(HostileInputs, NumbersADoubleCannotCarryAreRefused) {
  test::TempDir dir;
  for (const char* e : {"1e-320,0,0", "1e300,1e300,1e300"}) {
    const auto r = runRadkit("run '" + dir.file("room.json", room(e)) +
                             "' --patches 8 --no-render --out '" + dir.path("o") + "'");
    EXPECT_NE(r.exitCode, 0) << e << "\n" << r.output;
    EXPECT_NE(r.output.find("material \"lamp\": emission"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir.path("o")));
  }
  std::string sky = room("0,0,0");
  sky.insert(sky.rfind('}'), R"(, "sky": {"type": "uniform", "radiance": [1,1,1],
      "sun": {"elevation": 40, "irradiance": [1e308, 1e308, 1e308]}})");
  auto r = runRadkit("run '" + dir.file("sky.json", sky) + "' --patches 8 --no-render --out '" +
                     dir.path("o") + "'");
  EXPECT_NE(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("\"irradiance\" 1e+308"), std::string::npos) << r.output;
  r = runRadkit("sky --compare 1 --size 16 --out '" + dir.path("s") + "'");
  EXPECT_NE(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("standard error"), std::string::npos) << r.output;
}

TEST(HostileInputs, ALineBreakInASurfaceNameIsRefused) {
  test::TempDir dir;
  std::string s = room();
  s.replace(s.find("\"floor\""), 7, "\"flo\\nor\"");
  const auto r = runRadkit("run '" + dir.file("room.json", s) +
                           "' --patches 8 --no-render --out '" + dir.path("o") + "'");
  EXPECT_NE(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("control character"), std::string::npos) << r.output;
}

TEST(HostileInputs, AStudyTooShortToFitALadderWritesNoNan) {
  // One mesh rung in a 1 s budget: the fit had no value and study.md said "N^nan".
  test::TempDir dir;
  const auto r = runRadkit("study '" + dataPath("cornell-box.json") +
                           "' --max-seconds 1 --knob-patches 250 --epsilons 1e-2 --out '" +
                           dir.path("s") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const std::string md = fileText(dir.path("s/study.md"));
  EXPECT_EQ(md.find("nan"), std::string::npos) << md;
  EXPECT_NE(md.find("Mesh ladder fits"), std::string::npos) << md;
}

TEST(HostileInputs, PhotonsCompareAcceptsTheRunOfAMillimetreScene) {
  // surfaces.csv gives areas in m²; the check compared them with areas in scene units.
  test::TempDir dir;
  const std::string scene = dir.file("mm.json", R"({"units": "mm",
    "materials": {"grey": {"reflectance": [0.5,0.5,0.5]},
                  "lamp": {"reflectance": [0,0,0], "emission": [1,1,1]}},
    "surfaces": [
      {"name": "floor", "material": "grey", "polygon": [[0,0,0],[1000,0,0],[1000,1000,0],[0,1000,0]]},
      {"name": "lamp", "material": "lamp", "polygon": [[0,0,1000],[0,1000,1000],[1000,1000,1000],[1000,0,1000]]}]})");
  auto r = runRadkit("run '" + scene + "' --patches 8 --no-render --out '" + dir.path("run") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  r = runRadkit("photons '" + scene + "' --photons 2000 --no-image --bench-rays 0 --compare '" +
                dir.path("run") + "' --out '" + dir.path("p") + "'");
  EXPECT_EQ(r.exitCode, 0) << r.output;
}

}  // namespace
}  // namespace radkit
