// Output folders (issue 20, point 11): published by one rename of the staged folder, an
// earlier output replaced whole, stale staging of killed processes removed, and a folder
// radkit did not write left alone.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "tests/common/test_util.h"
#include "util/output_folder.h"

namespace radkit {
namespace {

namespace fs = std::filesystem;

ino_t inode(const fs::path& p) {
  struct stat st {};
  EXPECT_EQ(::stat(p.c_str(), &st), 0) << p;
  return st.st_ino;
}

std::vector<std::string> hiddenEntries(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string()[0] == '.') names.push_back(e.path().filename().string());
  return names;
}

TEST(OutputFolder, PublishesTheStagedFolderWithOneRename) {
  test::TempDir dir;
  OutputFolder folder(dir.path("out"));
  std::ofstream(folder.path("a.csv")) << "a";
  std::ofstream(folder.path("report.json")) << "{}";
  const fs::path staging = fs::path(folder.path("a.csv")).parent_path();
  const ino_t staged = inode(staging);
  folder.commit();
  EXPECT_EQ(inode(dir.path("out")), staged) << "the staged folder itself becomes the destination";
  EXPECT_TRUE(fs::exists(dir.path("out/a.csv")));
  EXPECT_TRUE(hiddenEntries(dir.path("")).empty());
}

TEST(OutputFolder, ReplacesAnEarlierOutputWhole) {
  test::TempDir dir;
  fs::create_directories(dir.path("out"));
  dir.file("out/report.json", "{\"old\": 1}");
  dir.file("out/solution-jacobi.csv", "old");
  OutputFolder folder(dir.path("out"));
  std::ofstream(folder.path("report.json")) << "{}";
  folder.commit();
  EXPECT_FALSE(fs::exists(dir.path("out/solution-jacobi.csv"))) << "files of two runs mixed";
  std::ifstream report(dir.path("out/report.json"));
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(report), {}), "{}");
  EXPECT_TRUE(hiddenEntries(dir.path("")).empty()) << "the old folder was not removed";
}

TEST(OutputFolder, RemovesStagingOfProcessesThatAreGone) {
  test::TempDir dir;
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  ASSERT_GT(child, 0);
  ASSERT_EQ(::waitpid(child, nullptr, 0), child);  // reaped: that PID names no process now
  const std::string dead = std::to_string(child), alive = std::to_string(::getppid());
  for (const std::string& name : {".out.partial-" + dead, ".out.old-" + dead,
                                  ".out.partial-" + alive, ".other.partial-" + dead}) {
    fs::create_directories(dir.path(name));
    dir.file(name + "/patches.csv", "x");
  }
  {
    OutputFolder folder(dir.path("out"));
    std::ofstream(folder.path("patches.csv")) << "new";
    folder.commit();
  }
  EXPECT_FALSE(fs::exists(dir.path(".out.partial-" + dead)));
  EXPECT_FALSE(fs::exists(dir.path(".out.old-" + dead)));
  EXPECT_TRUE(fs::exists(dir.path(".out.partial-" + alive)))
      << "a running process's staging was removed";
  EXPECT_TRUE(fs::exists(dir.path(".other.partial-" + dead)))
      << "another destination's staging was removed";
}

TEST(OutputFolder, RefusesAFolderRadkitDidNotWrite) {
  test::TempDir dir;
  fs::create_directories(dir.path("mine"));
  dir.file("mine/notes.txt", "keep me");
  EXPECT_THROW(OutputFolder(dir.path("mine")), std::runtime_error);
  EXPECT_TRUE(fs::exists(dir.path("mine/notes.txt")));
  EXPECT_TRUE(hiddenEntries(dir.path("")).empty());
}

}  // namespace
}  // namespace radkit
