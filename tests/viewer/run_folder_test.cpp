// RunFolder: values read back equal what was written; missing or malformed files are named.
#include "viewer/run_folder.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "output/run_files.h"
#include "radiosity/surface_form_factors.h"
#include "tests/common/test_util.h"
#include "tests/viewer/test_run.h"
#include "util/errors.h"

namespace radkit::viewer {
namespace {

using test::TestRun;

/// The message of the InputError `f` throws ("" when it throws none).
template <class F>
std::string inputError(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

class RunFolderTest : public ::testing::Test {
 protected:
  void SetUp() override { test::writeTestRun(m_dir.path("")); }
  std::string folder() const { return m_dir.path(""); }
  std::string file(const std::string& name) const { return m_dir.path(name); }
  void overwrite(const std::string& name, const std::string& text) const { m_dir.file(name, text); }
  radkit::test::TempDir m_dir;
};

TEST_F(RunFolderTest, ReadsBackPatches) {
  const RunFolder run = readRunFolder(folder());
  const PatchData& p = run.patches;
  ASSERT_EQ(p.size(), 3);
  ASSERT_EQ(p.points.size(), 10u);
  EXPECT_EQ(p.points[4], (Vec3{-0.05, 0.5, 0}));
  EXPECT_EQ(p.polygons[1], (std::vector<int>{3, 2, 4, 5}));  // shares points 2, 3 with patch 0
  EXPECT_EQ(p.surface, (std::vector<int>{0, 0, 1}));
  EXPECT_NEAR(p.area[0], 0.95 * 0.5, 1e-15);
  EXPECT_NEAR(p.area[2], 0.95, 1e-15);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(p.radiosity[i], TestRun::kRadiosity[i]) << "patch " << i;
  EXPECT_EQ(p.reflectance[2], (Vec3{0.14, 0.45, 0.091}));
  EXPECT_EQ(p.emission[0], (Vec3{0, 0, 0}));
  EXPECT_EQ(run.surfaceName(1), "left wall");
  EXPECT_EQ(run.surfaceName(2), "right wall");
}

TEST_F(RunFolderTest, ReadsBackReportMatrixHistoryAndSurfaces) {
  const RunFolder run = readRunFolder(folder());
  EXPECT_EQ(run.report.sceneName, "two-walls");
  EXPECT_EQ(run.report.units, "m");
  ASSERT_TRUE(run.report.camera);
  EXPECT_EQ(run.report.camera->position, (Vec3{0, 0, 3}));
  EXPECT_EQ(run.report.camera->fovDeg, 40);

  ASSERT_TRUE(run.formFactors);
  EXPECT_EQ(run.formFactors->n, 3);
  EXPECT_EQ(run.formFactors->nonZeros(), 6);
  for (int i = 0; i < 3; ++i) {
    std::vector<double> row = run.formFactors->row(i);
    for (int j = 0; j < 3; ++j) EXPECT_EQ(row[j], TestRun::kFormFactors[i][j]) << i << "," << j;
  }
  EXPECT_EQ(run.formFactors->maxValue(), 0.25);

  ASSERT_EQ(run.convergence.size(), 2u);
  EXPECT_EQ(run.convergence[0].solver, "jacobi");
  EXPECT_EQ(run.convergence[0].iteration, (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(run.convergence[1].solver, "gauss-seidel");
  EXPECT_EQ(run.convergence[1].residual.back(), 0.0002);

  ASSERT_EQ(run.surfaces.size(), 2u);
  EXPECT_EQ(run.surfaces[1].name, "right wall");  // quoted in the file
  EXPECT_EQ(run.surfaces[1].radiosity, (Vec3{0.1, 0.8, 0.12}));
  EXPECT_EQ(run.surfaces[0].illuminance, 100.25);
}

TEST_F(RunFolderTest, SameSolverTwiceIsTwoRuns) {
  overwrite("convergence.csv",
            "solver,iteration,time_s,residual,unshot_power_W\n"
            "sor,0,0,1,1\nsor,1,0,0.1,1\nsor,0,0,1,1\nsor,1,0,0.2,1\nsor,2,0,0.02,1\n");
  const auto runs = readConvergenceCsv(file("convergence.csv"));
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_EQ(runs[1].iteration.size(), 3u);
}

TEST_F(RunFolderTest, OptionalFilesMayBeMissing) {
  std::filesystem::remove(file("formfactors.mtx"));
  std::filesystem::remove(file("convergence.csv"));
  const RunFolder run = readRunFolder(folder());
  EXPECT_FALSE(run.formFactors);
  EXPECT_NE(run.formFactorsMissing.find("formfactors.bin"), std::string::npos);
  EXPECT_TRUE(run.convergence.empty());
  EXPECT_NE(run.convergenceMissing.find("convergence.csv"), std::string::npos);
}

TEST_F(RunFolderTest, MissingRequiredFilesAreNamed) {
  EXPECT_NE(inputError([&] { readRunFolder(file("nowhere")); }).find("nowhere: no such run folder"),
            std::string::npos);
  std::filesystem::remove(file("radiosity.vtp"));
  EXPECT_NE(inputError([&] { readRunFolder(folder()); }).find("radiosity.vtp: missing"),
            std::string::npos);
  std::filesystem::remove(file("report.json"));
  EXPECT_NE(inputError([&] { readRunFolder(folder()); }).find("report.json: cannot be opened"),
            std::string::npos);
}

TEST_F(RunFolderTest, MalformedFilesNameFileAndLine) {
  auto errorAfter = [&](const std::string& name, const std::string& text) {
    overwrite(name, text);
    std::string e = inputError([&] { readRunFolder(folder()); });
    test::writeTestRun(folder());  // repair for the next case
    return e;
  };
  EXPECT_NE(errorAfter("formfactors.mtx",
                       "%%MatrixMarket matrix coordinate real general\n3 3 1\n4 1 0.5\n")
                .find("formfactors.mtx:3: expected 'row column value'"),
            std::string::npos);
  EXPECT_NE(errorAfter("formfactors.mtx", "%%MatrixMarket matrix coordinate real general\n2 2 0\n")
                .find("is 2×2 but radiosity.vtp has 3 patches"),
            std::string::npos);
  EXPECT_NE(errorAfter("formfactors.mtx", "hello\n").find("formfactors.mtx:1"), std::string::npos);
  EXPECT_NE(errorAfter("convergence.csv",
                       "solver,iteration,time_s,residual,unshot_power_W\njacobi,0,0,x,1\n")
                .find("convergence.csv:2: column 'residual': 'x' is not a number"),
            std::string::npos);
  EXPECT_NE(errorAfter("convergence.csv", "solver,iteration\n")
                .find("convergence.csv: header has no column 'time_s'"),
            std::string::npos);
  EXPECT_NE(errorAfter("surfaces.csv", "surface,area_m2,b_r_W_m2,b_g_W_m2,b_b_W_m2\nfloor,1,2\n")
                .find("surfaces.csv:2: 3 fields"),
            std::string::npos);
  EXPECT_NE(errorAfter("report.json", "{\"scene\": ").find("report.json: is not valid JSON"),
            std::string::npos);
  EXPECT_NE(errorAfter("report.json", "{}").find("report.json: has no \"scene\" object"),
            std::string::npos);
  EXPECT_NE(
      errorAfter("report.json", R"({"scene": {"surfaces": ["only one"]}})").find("surface index 1"),
      std::string::npos);
  EXPECT_NE(errorAfter("radiosity.vtp", "<VTKFile type=\"PolyData\"><broken")
                .find("radiosity.vtp: not a readable"),
            std::string::npos);
}

// Found by data/tools/hostile_options.py (issue 20): a size line beyond the file allocated
// before reading (4000000000 entries: 64 GB), and an iteration of NaN or 1e20 was converted to int.
TEST_F(RunFolderTest, HostileCountsAreRefusedBeforeAllocating) {
  auto errorAfter = [&](const std::string& name, const std::string& text) {
    overwrite(name, text);
    std::string e = inputError([&] { readRunFolder(folder()); });
    test::writeTestRun(folder());
    return e;
  };
  for (const char* size : {"3 3 4000000000", "2000000000 2000000000 1", "3 3 10"}) {
    const std::string e = errorAfter(
        "formfactors.mtx",
        std::string("%%MatrixMarket matrix coordinate real general\n") + size + "\n1 1 0.5\n");
    EXPECT_NE(e.find("formfactors.mtx:2: the size line says"), std::string::npos)
        << size << ": " << e;
  }
  for (const char* iteration : {"nan", "1e20", "-1"}) {
    const std::string e = errorAfter("convergence.csv",
                                     std::string("solver,iteration,time_s,residual,unshot_power_W\n"
                                                 "jacobi,") +
                                         iteration + ",0,1,1\n");
    EXPECT_NE(e.find("convergence.csv:2: column 'iteration': '" + std::string(iteration) +
                     "' is not an iteration count >= 0"),
              std::string::npos)
        << e;
  }
}

TEST_F(RunFolderTest, MeshOutputWithoutRadiosityIsRefused) {
  std::ifstream in(file("radiosity.vtp"));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto at = text.find("<DataArray type=\"Float64\" Name=\"radiosity\"");
  ASSERT_NE(at, std::string::npos);
  text.erase(at, text.find("</DataArray>", at) + 12 - at);
  overwrite("radiosity.vtp", text);
  const std::string e = inputError([&] { readRunFolder(folder()); });
  EXPECT_NE(e.find("radiosity.vtp: no cell array 'radiosity'"), std::string::npos) << e;
}

}  // namespace
}  // namespace radkit::viewer

namespace radkit::viewer {
namespace {

// formfactors.bin, written by every run, holds what the .mtx holds (in float precision):
// sparse rows, dense rows and empty rows alike; a truncated file is refused by name.
TEST(FormFactorBinary, RoundTripsAndPrefersTheBinary) {
  radkit::test::TempDir dir;
  const int n = 5;
  DenseMatrix<double> m(n);
  m(0, 3) = 0.25;                                       // sparse row
  for (int j = 0; j < n; ++j) m(2, j) = 0.1 * (j + 1);  // dense row
  m(4, 0) = 1.0 / 3;                                    // row 1 and 3 empty
  const FormFactorMatrix f = m;
  writeFormFactorBinary(dir.path("formfactors.bin"), f);
  writeMatrixMarket(dir.path("formfactors.mtx"), f, {"test"});
  const FormFactorRows bin = readFormFactorsBin(dir.path("formfactors.bin"));
  const FormFactorRows mtx = readFormFactorsMtx(dir.path("formfactors.mtx"));
  ASSERT_EQ(bin.n, n);
  ASSERT_EQ(bin.rowStart, mtx.rowStart);
  ASSERT_EQ(bin.column, mtx.column);
  for (std::size_t k = 0; k < bin.value.size(); ++k)
    EXPECT_FLOAT_EQ(float(bin.value[k]), float(mtx.value[k]));
  EXPECT_EQ(bin.row(2)[4], float(0.5));
  EXPECT_FALSE(std::filesystem::exists(dir.path("formfactors.bin.tmp")));

  const auto size = std::filesystem::file_size(dir.path("formfactors.bin"));
  std::filesystem::resize_file(dir.path("formfactors.bin"), size - 3);
  try {
    readFormFactorsBin(dir.path("formfactors.bin"));
    ADD_FAILURE() << "a truncated file was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("formfactors.bin: ends inside"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("Fix:"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace radkit::viewer
