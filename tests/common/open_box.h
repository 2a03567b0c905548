// A 1 m box with one open side and a small light under its ceiling, as OBJ + MTL text: the
// shape of CornellBox-Original.obj, open toward +z or (mirrored) toward −z.
#pragma once

#include <string>

#include "tests/common/test_util.h"

namespace radkit::test {

/// Writes box.obj and box.mtl into `dir` and returns the OBJ's path. Walls face inward; the
/// left wall (x = 0) is red, the right one (x = 1) green.
inline std::string writeOpenBoxObj(const TempDir& dir, bool openTowardPlusZ,
                                   const std::string& name = "box") {
  const double s = openTowardPlusZ ? 1 : -1;  // z of the open side
  auto v = [&](double x, double y, double z) {
    return "v " + std::to_string(x) + " " + std::to_string(y) + " " + std::to_string(z * s) + "\n";
  };
  std::string obj = "mtllib " + name + ".mtl\n";
  // Corners: 1-4 at z = 0, 5-8 at the open side; light 9-12.
  obj += v(0, 0, 0) + v(1, 0, 0) + v(1, 1, 0) + v(0, 1, 0);
  obj += v(0, 0, 1) + v(1, 0, 1) + v(1, 1, 1) + v(0, 1, 1);
  obj += v(0.4, 0.99, 0.4) + v(0.6, 0.99, 0.4) + v(0.6, 0.99, 0.6) + v(0.4, 0.99, 0.6);
  // Counter-clockwise from inside for the +z box; mirroring z reverses every winding.
  auto f = [&](int a, int b, int c, int d) {
    return openTowardPlusZ ? "f " + std::to_string(a) + " " + std::to_string(b) + " " +
                                 std::to_string(c) + " " + std::to_string(d) + "\n"
                           : "f " + std::to_string(d) + " " + std::to_string(c) + " " +
                                 std::to_string(b) + " " + std::to_string(a) + "\n";
  };
  obj += "o back\nusemtl white\n" + f(1, 2, 3, 4);
  obj += "o floor\nusemtl white\n" + f(1, 5, 6, 2);
  obj += "o ceiling\nusemtl white\n" + f(4, 3, 7, 8);
  obj += "o left\nusemtl red\n" + f(1, 4, 8, 5);
  obj += "o right\nusemtl green\n" + f(2, 6, 7, 3);
  obj += "o light\nusemtl light\n" + f(9, 10, 11, 12);
  dir.file(
      name + ".mtl",
      "newmtl white\nKd 0.7 0.7 0.7\nnewmtl red\nKd 0.6 0.05 0.05\nnewmtl green\nKd 0.1 0.5 0.1\n"
      "newmtl light\nKd 0.5 0.5 0.5\nKe 20 20 20\n");
  return dir.file(name + ".obj", obj);
}

}  // namespace radkit::test
