// Settings named in library messages (util/setting_names.h): the command line's flags by
// default, and a front end's own spelling once it installs one, in the messages of every floor.
#include <gtest/gtest.h>

#include <string>

#include "util/output_folder.h"
#include "util/setting_names.h"

namespace radkit {
namespace {

std::string keyword(const std::string& key) { return key + "="; }

std::string outputFolderMessage() {
  try {
    OutputFolder folder("");
  } catch (const std::exception& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(SettingNames, FlagsByDefaultAndTheFrontEndsSpellingOnceInstalled) {
  EXPECT_EQ(setting("max_area"), "--max-area");
  EXPECT_EQ(setting("tol"), "--tol");
  EXPECT_EQ(flagSpelling("hr_rays"), "--hr-rays");
  const std::string flags = outputFolderMessage();
  EXPECT_NE(flags.find("e.g. --out out/run1"), std::string::npos) << flags;

  setSettingSpeller(&keyword);
  EXPECT_EQ(setting("max_area"), "max_area=");
  const std::string keywords = outputFolderMessage();
  setSettingSpeller(nullptr);
  EXPECT_NE(keywords.find("e.g. out= out/run1"), std::string::npos) << keywords;
  EXPECT_EQ(keywords.find("--out"), std::string::npos) << keywords;
  EXPECT_EQ(setting("max_area"), "--max-area");
}

}  // namespace
}  // namespace radkit
