// Output folders: published by one rename of the staged folder, an
// earlier output replaced whole, stale staging of killed processes removed, and a folder
// radkit did not write left alone.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

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

/// Writes an output folder as a run would, with `files` in it.
void writeRun(const std::string& destination, const std::vector<std::string>& files) {
  OutputFolder folder(destination);
  for (const std::string& f : files) std::ofstream(folder.path(f)) << "old";
  folder.commit();
}

std::string readText(const std::string& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(OutputFolder, ReplacesAnEarlierOutputWhole) {
  test::TempDir dir;
  writeRun(dir.path("out"), {"report.json", "solution-jacobi.csv"});
  ASSERT_TRUE(fs::exists(dir.path("out/") + kOutputMarker));
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

TEST(OutputFolder, AReportJsonDoesNotMakeAFolderRadkits) {
  // Only radkit's marker does: a file named report.json let a run delete a user's thesis.
  test::TempDir dir;
  fs::create_directories(dir.path("thesis"));
  dir.file("thesis/report.json", "{}");
  dir.file("thesis/thesis.tex", "keep me");
  dir.file("thesis/scene.json", "{}");
  try {
    OutputFolder folder(dir.path("thesis"));
    FAIL() << "a folder radkit did not mark was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(kOutputMarker), std::string::npos) << e.what();
  }
  EXPECT_EQ(readText(dir.path("thesis/thesis.tex")), "keep me");
  EXPECT_TRUE(fs::exists(dir.path("thesis/scene.json")));
  // A marker that is not radkit's (wrong content) does not either.
  dir.file(std::string("thesis/") + kOutputMarker, "report.json\nthesis.tex\nscene.json\n");
  EXPECT_THROW(OutputFolder(dir.path("thesis")), std::runtime_error);
  EXPECT_EQ(readText(dir.path("thesis/thesis.tex")), "keep me");
}

TEST(OutputFolder, AMarkedFolderWithAUsersFileIsNotReplaced) {
  test::TempDir dir;
  writeRun(dir.path("out"), {"report.json", "patches.csv"});
  dir.file("out/notes.txt", "keep me");
  try {
    OutputFolder folder(dir.path("out"));
    FAIL() << "a run folder holding a user's file was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("notes.txt"), std::string::npos) << e.what();
  }
  // Saved into the folder while a run works: commit() checks again.
  fs::remove(dir.path("out/notes.txt"));
  OutputFolder folder(dir.path("out"));
  std::ofstream(folder.path("report.json")) << "{}";
  dir.file("out/notes.txt", "keep me");
  EXPECT_THROW(folder.commit(), std::runtime_error);
  EXPECT_EQ(readText(dir.path("out/notes.txt")), "keep me");
  EXPECT_EQ(readText(dir.path("out/report.json")), "old");
}

TEST(OutputFolder, AFileRegisteredInTheMarkerIsRadkits) {
  // A viewer screenshot saved into a run folder does not stop the next run.
  test::TempDir dir;
  writeRun(dir.path("out"), {"report.json"});
  dir.file("out/view.png", "png");
  registerOutputFile(dir.path("out/view.png"));
  registerOutputFile(dir.path("elsewhere.png"));  // no marked folder: nothing happens
  EXPECT_FALSE(fs::exists(dir.path("") + kOutputMarker));
  writeRun(dir.path("out"), {"report.json"});
  EXPECT_FALSE(fs::exists(dir.path("out/view.png")));
}

TEST(OutputFolder, WritesRefuseDevicesAndPipesAndFollowSymlinksToFiles) {
  test::TempDir dir;
  ASSERT_EQ(::mkfifo(dir.path("pipe").c_str(), 0600), 0);
  EXPECT_THROW(writeFileAtomically(dir.path("pipe"), "x"), std::runtime_error);
  EXPECT_TRUE(fs::is_fifo(dir.path("pipe"))) << "the pipe was replaced by a file";
  fs::create_symlink("/dev/null", dir.path("null-link"));
  try {
    writeFileAtomically(dir.path("null-link"), "x");
    FAIL() << "a symlink to a device was written";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("character device"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
  EXPECT_TRUE(fs::is_symlink(dir.path("null-link")));
  EXPECT_THROW(writeFileAtomically(dir.path(""), "x"), std::runtime_error) << "a folder";
  // A symlink to a regular file: the target is replaced, the link stays a link.
  dir.file("target.json", "old");
  fs::create_symlink(dir.path("target.json"), dir.path("link.json"));
  writeFileAtomically(dir.path("link.json"), "new");
  EXPECT_TRUE(fs::is_symlink(dir.path("link.json")));
  EXPECT_EQ(readText(dir.path("target.json")), "new");
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
