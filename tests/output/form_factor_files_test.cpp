// formfactors.mtx, surface_formfactors.csv and formfactors.png.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "geometry/ray_scene.h"
#include "output/run_files.h"
#include "radiosity/form_factor_heat_map.h"
#include "radiosity/form_factors.h"
#include "radiosity/surface_form_factors.h"
#include "tests/radiosity/test_scenes.h"

namespace radkit {
namespace {
std::string tempPath(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("radkit_ff_" + name)).string();
}
std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}
/// Width and height from a PNG's IHDR chunk.
std::pair<int, int> pngSize(const std::string& bytes) {
  auto be32 = [&](std::size_t o) {
    return (int((unsigned char)bytes[o]) << 24) | (int((unsigned char)bytes[o + 1]) << 16) |
           (int((unsigned char)bytes[o + 2]) << 8) | int((unsigned char)bytes[o + 3]);
  };
  return {be32(16), be32(20)};
}
}  // namespace

TEST(FormFactorWriters, ExactMatrixMarket) {
  test::MeshBuilder b = test::cubeInterior(1);
  RayScene scene(b.mesh());
  FormFactorResult r = computeFormFactors(b.mesh(), scene, FormFactorSettings{});
  std::string path = tempPath("f.mtx");
  writeMatrixMarket(path, r.matrix, {"radkit formfactors: unit cube", r.diagnostics.description});
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
  std::istringstream in(slurp(path));
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "%%MatrixMarket matrix coordinate real general");
  while (in.peek() == '%') std::getline(in, line);
  int rows, cols, nnz;
  in >> rows >> cols >> nnz;
  EXPECT_EQ(rows, 6);
  EXPECT_EQ(nnz, 30);  // every face sees the five others
  for (int k = 0; k < nnz; ++k) {
    int i, j;
    double f;
    in >> i >> j >> f;
    EXPECT_EQ(f, formFactorAt(r.matrix, i - 1, j - 1));  // shortest round-trip text: exact
  }
}

TEST(FormFactorWriters, ExactSurfaceCsv) {
  test::MeshBuilder b = test::cubeInterior(2);
  RayScene scene(b.mesh());
  FormFactorResult r = computeFormFactors(b.mesh(), scene, FormFactorSettings{});
  std::string path = tempPath("s.csv");
  writeSurfaceFormFactors(path, b.mesh(), b.names(), r.matrix);
  std::istringstream in(slurp(path));
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "from,to,F");
  int lines = 0;
  while (std::getline(in, line)) {
    ++lines;
    if (line.rfind("bottom,top,", 0) == 0) {
      EXPECT_NEAR(std::stod(line.substr(11)), 0.1998249, 1e-4);
    }
    if (line.rfind("bottom,bottom,", 0) == 0) {
      EXPECT_EQ(std::stod(line.substr(14)), 0.0);
    }
  }
  EXPECT_EQ(lines, 36);
  EXPECT_THROW(writeSurfaceFormFactors(path, b.mesh(), {"only-one"}, r.matrix),
               std::invalid_argument);
}

// 100 patches: one 8-pixel cell per patch; 10 000 patches (sparse, banded): block means.
TEST(FormFactorWriters, ConstructHeatMap) {
  test::MeshBuilder b = test::cubeInterior(4);  // 96 patches
  RayScene scene(b.mesh());
  FormFactorResult r = computeFormFactors(b.mesh(), scene, FormFactorSettings{});
  std::string path = tempPath("small.png");
  writeFormFactorHeatMap(path, b.mesh(), b.names(), r.matrix, {800, 6, 2, "unit cube"});
  std::string png = slurp(path);
  ASSERT_GT(png.size(), 8u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
  auto [w, h] = pngSize(png);
  EXPECT_GE(h, 96 * 8);
  EXPECT_LT(w, 1400);

  // A banded 10 000-patch matrix on 4 surfaces.
  const int n = 10000;
  PatchMesh big;
  big.surfaceBegin = {0, 2500, 5000, 7500, 10000};
  big.patches.resize(n);
  std::vector<std::int64_t> start{0};
  std::vector<int> column;
  std::vector<double> value;
  for (int i = 0; i < n; ++i) {
    big.patches[i].surface = i / 2500;
    big.patches[i].area = 1;
    for (int j = std::max(0, i - 50); j < std::min(n, i + 50); ++j)
      if (j != i) column.push_back(j), value.push_back(1e-3 / (1 + std::abs(i - j)));
    start.push_back(std::int64_t(column.size()));
  }
  FormFactorMatrix f = CsrMatrix<double>(n, start, column, value);
  path = tempPath("big.png");
  writeFormFactorHeatMap(path, big, {"floor", "ceiling", "walls", "statue"}, f);
  auto [bw, bh] = pngSize(slurp(path));
  EXPECT_LE(bh, 1000);
  EXPECT_GE(bh, 800);
  EXPECT_LE(bw, 1300);
}

}  // namespace radkit
