// Labels with characters stb_easy_font lacks (issue 20, point 4): drawn as '?', one per UTF-8
// code point, instead of reading outside the font's glyph table.
#include <gtest/gtest.h>

#include <filesystem>

#include "tests/common/test_util.h"
#include "util/canvas.h"

namespace radkit {
namespace {

bool samePixels(const Canvas& a, const Canvas& b) {
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x) {
      const Rgb8 p = a.at(x, y), q = b.at(x, y);
      if (p.r != q.r || p.g != q.g || p.b != q.b) return false;
    }
  return true;
}

TEST(CanvasText, ReplacesWhatTheFontLacks) {
  const std::pair<std::string, std::string> cases[] = {
      {"caf\xC3\xA9", "caf?"},  // é: two bytes, one code point
      {"Raum \xC3\xBC", "Raum ?"},
      {"\xE2\x82\xAC 5", "? 5"},    // €: three bytes
      {"\xF0\x9F\x98\x80!", "?!"},  // an emoji: four bytes
      {"a\x7F\x01"
       "b",
       "a??b"},               // DEL and a control character
      {"\xA9x\xC3", "?x?"}};  // stray continuation, truncated lead byte
  for (const auto& [text, shown] : cases) {
    EXPECT_EQ(Canvas::textWidth(text, 2), Canvas::textWidth(shown, 2)) << shown;
    Canvas a(120, 20), b(120, 20);
    a.text(2, 2, text, 2);
    b.text(2, 2, shown, 2);
    EXPECT_TRUE(samePixels(a, b)) << shown;
    Canvas v(20, 120), w(20, 120);
    v.text(2, 2, text, 2, {0, 0, 0}, true);
    w.text(2, 2, shown, 2, {0, 0, 0}, true);
    EXPECT_TRUE(samePixels(v, w)) << shown;
  }
}

// End to end: UTF-8 scene and surface names label formfactors.png.
TEST(CanvasText, FormFactorImageWithUtf8Names) {
  test::TempDir dir;
  const std::string scene = dir.file("raum.json", R"({"name": "Raum \u00fc",
      "materials": {"grey": {"reflectance": [0.5,0.5,0.5]}, "lamp": {"emission": [1,1,1]}},
      "surfaces": [{"name": "caf\u00e9", "material": "grey", "polygon": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]]},
                   {"name": "\u20ac \ud83d\ude00", "material": "lamp", "polygon": [[0,0,1],[0,1,1],[1,1,1],[1,0,1]]}]})");
  const test::RunResult r = test::runRadkitWithin(
      300, "formfactors '" + scene + "' --patches 8 --out '" + dir.path("o") + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_TRUE(std::filesystem::exists(dir.path("o/formfactors.png")));
}

}  // namespace
}  // namespace radkit
