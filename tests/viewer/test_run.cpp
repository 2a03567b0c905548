#include "tests/viewer/test_run.h"

#include <cmath>
#include <fstream>

#include "geometry/patch_mesh.h"
#include "geometry/scene.h"
#include "output/run_files.h"

namespace radkit::viewer::test {

const Vec3 TestRun::kRadiosity[3] = {{0.9, 0.1, 0.08}, {0.6, 0.07, 0.05}, {0.1, 0.8, 0.12}};
const double TestRun::kFormFactors[3][3] = {
    {0, 0.25, 0.125}, {0.25, 0, 0.0625}, {0.125, 0.0625, 0}};

namespace {

Scene testScene() {
  Scene scene;
  scene.name = "two-walls";
  scene.materials = {makeMaterial("red", "lambert", "reflectance=0.63 0.065 0.05"),
                     makeMaterial("green", "lambert", "reflectance=0.14 0.45 0.091")};
  Surface left{"left wall", 0, {}, {}, "test"}, right{"right wall", 1, {}, {}, "test"};
  scene.surfaces = {left, right};
  scene.camera = Camera{{0, 0, TestRun::kCameraDistance}, {0, 0, 0}, {0, 1, 0}, TestRun::kFovDeg};
  return scene;
}

PatchMesh testMesh(bool rightFacesAway) {
  PatchMesh m;
  // Left surface: 6 shared vertices, two patches; right: one patch.
  m.vertices = {{-1, -0.5, 0}, {-0.05, -0.5, 0}, {-0.05, 0, 0}, {-1, 0, 0},  {-0.05, 0.5, 0},
                {-1, 0.5, 0},  {0.05, -0.5, 0},  {1, -0.5, 0},  {1, 0.5, 0}, {0.05, 0.5, 0}};
  auto add = [&](std::array<int, 4> v, int surface) {
    Patch p;
    p.vertex = v;
    p.vertexCount = 4;
    p.surface = surface;
    computePatchGeometry(m.vertices, p);
    m.patches.push_back(p);
  };
  add({0, 1, 2, 3}, 0);
  add({3, 2, 4, 5}, 0);
  add(rightFacesAway ? std::array<int, 4>{9, 8, 7, 6} : std::array<int, 4>{6, 7, 8, 9}, 1);
  m.surfaceBegin = {0, 2, 3};
  return m;
}

}  // namespace

void writeTestRun(const std::string& folder, bool rightFacesAway) {
  const Scene scene = testScene();
  const std::vector<Vec3> b(std::begin(TestRun::kRadiosity), std::end(TestRun::kRadiosity));
  writePatchesVtp(folder + "/radiosity.vtp", scene, testMesh(rightFacesAway), &b);
  std::ofstream(folder + "/report.json")
      << R"({"command": "run", "scene": {"name": "two-walls", "file": "two-walls.json", "units": "m",
            "surfaces": ["left wall", "right wall"],
            "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov_deg": 40}}})";
  std::ofstream mtx(folder + "/formfactors.mtx");
  mtx << "%%MatrixMarket matrix coordinate real general\n% test\n3 3 6\n";
  for (int j = 0; j < 3; ++j)  // column order: the reader must not rely on row order
    for (int i = 0; i < 3; ++i)
      if (TestRun::kFormFactors[i][j] > 0)
        mtx << i + 1 << ' ' << j + 1 << ' ' << TestRun::kFormFactors[i][j] << '\n';
  std::ofstream(folder + "/convergence.csv")
      << "solver,iteration,time_s,residual,unshot_power_W\n"
         "jacobi,0,0.001,0.5,0.2\njacobi,1,0.002,0.05,0.1\n"
         "jacobi,2,0.003,0.005,0.05\njacobi,3,0.004,0.0005,0.02\n"
         "gauss-seidel,0,0.001,0.3,0.2\ngauss-seidel,1,0.002,0.01,0.1\n"
         "gauss-seidel,2,0.003,0.0002,0.01\n";
  std::ofstream(folder + "/surfaces.csv")
      << "surface,area_m2,b_r_W_m2,b_g_W_m2,b_b_W_m2,luminance_cd_m2,illuminance_lux\n"
         "left wall,0.95,0.75,0.085,0.065,30.5,100.25\n"
         "\"right wall\",0.95,0.1,0.8,0.12,140,300\n";
}

void projectToPixel(const Vec3& p, int width, int height, double& x, double& y) {
  const double halfHeight = TestRun::kCameraDistance * std::tan(TestRun::kFovDeg * M_PI / 360);
  const double aspect = double(width) / height;
  x = (1 + p.x / (halfHeight * aspect)) / 2 * width;
  y = (1 - p.y / halfHeight) / 2 * height;
}

}  // namespace radkit::viewer::test
