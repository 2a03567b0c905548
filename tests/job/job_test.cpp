// The library's main job (job/job.h): how settings resolve, what it refuses, the closed form of
// a furnace through both methods, and the all-or-nothing run folder.
#include "job/job.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "../common/read_json.h"
#include "../common/test_util.h"
#include "radiosity/presets.h"
#include "solvers/registry.h"
#include "util/errors.h"

namespace radkit {
namespace {

using test::TempDir;

/// data/furnace.json, a closed unit cube whose six faces emit E = 1 W/m², with reflectance
/// rho: every point sees only the cube, so B = E / (1 − rho) exactly (the furnace test).
std::string furnace(const TempDir& dir, double rho) {
  nlohmann::json scene = test::readJson(test::dataPath("furnace.json"));
  scene["materials"]["glow"]["reflectance"] = {rho, rho, rho};
  return dir.file("furnace.json", scene.dump());
}

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(Job, ResolvesThePresetThenTheGivenSettingsThenEachMethodsDefaults) {
  JobSettings s;
  s.scene = "any.json";
  JobSettings r = resolveJobSettings(s);
  EXPECT_EQ(*r.method, JobMethod::Dense);
  EXPECT_EQ(r.mesh->targetPatches, kDefaultRunPatches);
  EXPECT_EQ(r.formFactors.method, FormFactorSettings{}.method);
  EXPECT_EQ(r.formFactors.samples, defaultFormFactorSamples(FormFactorSettings{}.method));
  ASSERT_EQ(r.solvers.size(), 1u);
  EXPECT_EQ(r.solvers[0].name, "gauss-seidel");

  // A preset's K is for its own method: another method given takes its own default K.
  PipelineSettings draft;
  applyPreset("draft", draft);
  s.preset = "draft";
  r = resolveJobSettings(s);
  EXPECT_EQ(r.mesh->targetPatches, draft.mesh.targetPatches);
  EXPECT_EQ(r.stopping.tolerance, draft.stopping.tolerance);
  s.mesh = SubdivisionSettings{0, 123};
  s.formFactorMethod = "monte-carlo";
  s.tolerance = 1e-7;
  r = resolveJobSettings(s);
  EXPECT_EQ(r.mesh->targetPatches, 123);
  EXPECT_EQ(r.formFactors.samples, defaultFormFactorSamples("monte-carlo"));
  EXPECT_EQ(r.stopping.tolerance, 1e-7);
  s.formFactorSamples = 5;
  EXPECT_EQ(resolveJobSettings(s).formFactors.samples, 5);

  // `solvers` compares every registered solver past 1e-9; `formfactors` solves nothing and
  // keeps one patch per input face.
  JobSettings solvers;
  solvers.scene = "any.json";
  solvers.out = "x";
  solvers.kind = JobKind::Solvers;
  r = resolveJobSettings(solvers);
  EXPECT_EQ(r.solvers.size(), solverNames().size());
  EXPECT_EQ(r.stopping.tolerance, 1e-10);
  solvers.kind = JobKind::FormFactors;
  r = resolveJobSettings(solvers);
  EXPECT_TRUE(r.solvers.empty());
  EXPECT_EQ(r.mesh->targetPatches, 0);
  EXPECT_EQ(r.mesh->maxArea, 0);

  // The hierarchical preset picks the method, its own sweep limit and the machine's budget;
  // the seed and a given budget reach the hierarchy.
  JobSettings large;
  large.scene = "any.json";
  large.preset = "large";
  large.seed = 7;
  r = resolveJobSettings(large);
  EXPECT_EQ(*r.method, JobMethod::Hierarchical);
  EXPECT_EQ(r.hierarchical.stopping.maxIterations, kDefaultHierarchicalSweeps);
  EXPECT_EQ(r.hierarchical.memoryBudget, defaultHierarchicalMemoryBudget());
  EXPECT_EQ(r.hierarchical.seed, 7u);
  large.memoryBudget = std::size_t(1) << 30;
  large.maxIterations = 50;
  r = resolveJobSettings(large);
  EXPECT_EQ(r.hierarchical.memoryBudget, std::size_t(1) << 30);
  EXPECT_EQ(r.hierarchical.stopping.maxIterations, 50);
}

TEST(Job, RefusesSettingsThatDisagreeBeforeAnyWork) {
  TempDir dir;
  const std::string scene = furnace(dir, 0.5);
  auto refused = [&](JobSettings s, const std::string& words) {
    s.scene = scene;
    if (s.out.empty()) s.out = dir.path("out");
    try {
      runJob(s);
      ADD_FAILURE() << "accepted; expected: " << words;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
    EXPECT_FALSE(std::filesystem::exists(dir.path("out")));
  };
  JobSettings s;
  s.kind = JobKind::Solvers;
  s.preset = "large";
  refused(s, "only a run does");
  s = {};
  s.preset = "large";
  s.method = JobMethod::Dense;
  refused(s, "not the dense one");
  s = {};
  s.preset = "draft";
  s.method = JobMethod::Hierarchical;
  refused(s, "belongs to the dense method");
  s = {};
  s.method = JobMethod::Hierarchical;
  s.adaptive = AdaptiveSettings{};
  refused(s, "adaptive refinement belongs to the dense method");
  s = {};
  s.checkLinks = 3;
  refused(s, "checking links is for the hierarchical method");
  s = {};
  s.preset = "fast";
  refused(s, "unknown preset \"fast\"");
  s = {};
  s.formFactorMethod = "centroid";
  refused(s, "unknown form-factor method 'centroid'");
  s = {};
  s.method = JobMethod::Hierarchical;
  s.hierarchical.epsilon = 0;
  refused(s, "epsilon");
  JobSettings noOut;  // only a run names its own folder
  noOut.scene = scene;
  noOut.kind = JobKind::FormFactors;
  EXPECT_THROW(runJob(noOut), std::runtime_error);
}

TEST(Job, BothMethodsGiveTheFurnacesClosedFormAndWriteWhatTheyReport) {
  TempDir dir;
  // rho 0.95: B = 20, and an error d in a row sum moves B by about rho/(1 - rho) d = 19 d.
  const std::string scene = furnace(dir, 0.95);
  for (JobMethod method : {JobMethod::Dense, JobMethod::Hierarchical}) {
    SCOPED_TRACE(method == JobMethod::Dense ? "dense" : "hierarchical");
    JobSettings s;
    s.scene = scene;
    s.out = dir.path(method == JobMethod::Dense ? "dense" : "hierarchical");
    s.method = method;
    s.mesh = SubdivisionSettings{0, 216};
    s.hierarchical.epsilon = 1e-3;  // coarse links: the row-sum fill makes any leaf exact
    s.tolerance = 1e-12;
    s.render = false;
    int progressReports = 0;
    PipelineLog log;
    log.progress = [&](const std::string&, double) { ++progressReports; };
    const JobResult r = runJob(s, log);
    EXPECT_EQ(r.out, s.out);
    EXPECT_EQ(r.method, method);
    const std::vector<Vec3>& b =
        method == JobMethod::Dense ? r.dense->radiosity : r.hierarchical->radiosity;
    ASSERT_FALSE(b.empty());
    double worst = 0;
    for (const Vec3& v : b) worst = std::max(worst, std::abs(v.x / 20 - 1));
    // Dense: point-polygon rows of the closed cube sum to 1 within about 4e-9 (B within 8e-8
    // measured); hierarchical: leaves of a closed scene at rho >= 0.9 are normalised to row
    // sum 1 (B within 1e-12 measured).
    EXPECT_LT(worst, method == JobMethod::Dense ? 1e-6 : 1e-9);
    // report.json on disk is the report returned, and it names the method.
    const nlohmann::json onDisk = test::readJson(s.out + "/report.json");
    EXPECT_EQ(onDisk, r.report);
    EXPECT_EQ(onDisk.value("method", "dense"),
              method == JobMethod::Dense ? "dense" : "hierarchical");
    for (const char* file : {"patches.csv", "surfaces.csv", "radiosity.vtp", "convergence.csv"})
      EXPECT_TRUE(std::filesystem::exists(s.out + "/" + file)) << file;
    EXPECT_FALSE(std::filesystem::exists(s.out + "/render.png"));
    EXPECT_EQ(std::filesystem::exists(s.out + "/links.png"), method == JobMethod::Hierarchical);
    EXPECT_GT(progressReports, 0);  // the stages report to the log
  }
}

TEST(Job, ALoadedSceneGivesTheFilesItsPathGives) {
  TempDir dir;
  JobSettings s;
  s.scene = test::dataPath("cornell-box.json");
  s.mesh = SubdivisionSettings{0, 200};
  s.render = false;
  s.out = dir.path("by-path");
  const JobResult byPath = runJob(s);
  LoadReport loaded;
  Scene scene = loadJobScene(s.scene, {}, "", {}, &loaded);
  s.out = dir.path("loaded");
  const JobResult fromScene = runJob(std::move(scene), s, {}, loaded);
  for (const char* file : {"patches.csv", "surfaces.csv", "formfactors.bin"})
    EXPECT_EQ(readFile(dir.path("by-path/") + file), readFile(dir.path("loaded/") + file)) << file;
  EXPECT_EQ(byPath.report["load"], fromScene.report["load"]);
}

TEST(Job, BadInputNamesTheFileAndLeavesTheEarlierFolderAlone) {
  TempDir dir;
  JobSettings s;
  s.scene = furnace(dir, 0.5);
  s.mesh = SubdivisionSettings{0, 60};
  s.render = false;
  s.out = dir.path("out");
  runJob(s);
  const std::string before = readFile(dir.path("out/patches.csv"));
  ASSERT_FALSE(before.empty());
  s.scene = dir.file("bad.json", R"({"materials": {"m": {"reflectance": [1.2, 0.5, 0.5]}},
      "surfaces": [{"name": "floor", "material": "m",
                    "polygon": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]]}]})");
  try {
    runJob(s);
    ADD_FAILURE() << "a reflectance of 1.2 was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.json"), std::string::npos) << e.what();
  }
  EXPECT_EQ(readFile(dir.path("out/patches.csv")), before);
  // Nothing staged is left beside it.
  int entries = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir.path("")))
    entries += entry.path().filename().string().find("partial") != std::string::npos;
  EXPECT_EQ(entries, 0);
}

}  // namespace
}  // namespace radkit
