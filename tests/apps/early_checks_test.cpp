// Checks that must come before the work: an --out that cannot be written, a mesh whose form
// factors cannot fit memory, a --compare folder of another scene. Each fails with a Fix:
// before any stage has started (no stage's progress line in the output).
#include <gtest/gtest.h>

#include <filesystem>

#include "tests/common/test_util.h"

namespace radkit {
namespace {

namespace fs = std::filesystem;
using test::dataPath;
using test::runRadkit;

TEST(EarlyChecks, OutThatIsAFileIsRefusedBeforeTheWork) {
  test::TempDir dir;
  const std::string taken = dir.file("taken", "a file the user keeps\n");
  auto r = runRadkit("run '" + dataPath("cornell-box.json") +
                     "' --patches 200 --no-render --out '" + taken + "'");
  EXPECT_NE(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find(taken), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("Fix:"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("form factors"), std::string::npos) << "refused only after the work:\n"
                                                              << r.output;
  EXPECT_TRUE(fs::is_regular_file(taken));
  r = runRadkit("run '" + dataPath("furnace.json") + "' --method hierarchical --no-render --out '" +
                taken + "'");
  EXPECT_NE(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find(taken), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("%"), std::string::npos) << "refused only after the work:\n" << r.output;
}

// 30 000 patches need 6.7 GiB dense in double and more sparse: a 1 GiB budget cannot hold F,
// which a sample of pairs shows without the n²/2 facing tests.
TEST(EarlyChecks, FormFactorsBeyondTheBudgetAreRefusedFromASample) {
  test::TempDir dir;
  auto r = runRadkit("formfactors '" + dataPath("cornell-box.json") +
                     "' --patches 30000 --memory-budget 1GiB --out '" + dir.path("o") + "'");
  EXPECT_NE(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("estimated from 200000 sampled pairs"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("Fix:"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir.path("o")));
}

TEST(EarlyChecks, PhotonsCompareRefusesARunOfAnotherScene) {
  test::TempDir dir;
  const char* body = R"("materials": {"grey": {"reflectance": [0.5,0.5,0.5]},
                                      "lamp": {"reflectance": [0,0,0], "emission": [1,1,1]}},
      "surfaces": [{"name": "floor", "material": "grey", "polygon": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]]},
                   {"name": "lamp", "material": "lamp", "polygon": [[0,0,1],[0,1,1],[1,1,1],[1,0,1]]}]})";
  const std::string a = dir.file("a.json", std::string("{\"name\": \"room-a\", ") + body);
  const std::string b = dir.file("b.json", std::string("{\"name\": \"room-b\", ") + body);
  auto r = runRadkit("run '" + a + "' --patches 8 --no-render --out '" + dir.path("run-a") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  r = runRadkit("photons '" + b + "' --photons 2000 --no-image --bench-rays 0 --compare '" +
                dir.path("run-a") + "' --out '" + dir.path("p") + "'");
  EXPECT_NE(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("room-a"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("Fix:"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("trace"), std::string::npos) << "refused only after tracing:\n"
                                                       << r.output;
  EXPECT_FALSE(fs::exists(dir.path("p")));
  // The same scene is accepted.
  r = runRadkit("photons '" + a + "' --photons 2000 --no-image --bench-rays 0 --compare '" +
                dir.path("run-a") + "' --out '" + dir.path("q") + "'");
  EXPECT_EQ(r.exitCode, 0) << r.output;
}

// Usage errors exited with CLI11's own codes (105, 106, 109) and other errors with 1.
TEST(EarlyChecks, UsageErrorsExitOneLikeEveryError) {
  test::TempDir dir;
  const std::string scene = "'" + dataPath("furnace.json") + "'";
  for (const std::string& args :
       {"mesh " + scene + " --no-such-option --out '" + dir.path("o") + "'",
        "formfactors " + scene + " --ff-samples 0 --out '" + dir.path("o") + "'", "mesh " + scene,
        "mesh " + scene + " --units furlong --out '" + dir.path("o") + "'"}) {
    auto r = runRadkit(args);
    EXPECT_EQ(r.exitCode, 1) << args << "\n" << r.output;
  }
  EXPECT_EQ(runRadkit("--help").exitCode, 0);
  EXPECT_FALSE(fs::exists(dir.path("o")));
}

}  // namespace
}  // namespace radkit
