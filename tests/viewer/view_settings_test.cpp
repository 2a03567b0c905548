// Colour maths against the standards it implements (sRGB, 683 lm/W, Rec. 709), mode parsing,
// matrix downsampling, and input checks that must fail before any window opens.
#include "viewer/view_settings.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "tests/common/test_util.h"
#include "tests/viewer/test_run.h"
#include "util/errors.h"
#include "viewer/viewer.h"

namespace radkit::viewer {
namespace {

TEST(ViewSettings, ParsesModesAndChannels) {
  EXPECT_EQ(parseMode("radiosity").mode, ViewMode::Radiosity);
  EXPECT_EQ(parseMode("false-colour").mode, ViewMode::FalseColour);
  EXPECT_EQ(parseMode("matrix").mode, ViewMode::Matrix);
  EXPECT_EQ(parseMode("convergence").mode, ViewMode::Convergence);
  const ModeChoice row = parseMode("formfactors-row:17");
  EXPECT_EQ(row.mode, ViewMode::FormFactorRow);
  EXPECT_EQ(row.row, 17);
  EXPECT_THROW(parseMode("formfactors-row:"), InputError);
  EXPECT_THROW(parseMode("formfactors-row:-1"), InputError);
  EXPECT_THROW(parseMode("heatmap"), InputError);
  EXPECT_EQ(parseChannel("g"), Channel::Green);
  EXPECT_EQ(parseChannel("luminance"), Channel::Luminance);
  EXPECT_THROW(parseChannel("y"), InputError);
}

TEST(ViewSettings, TrueColourIsExposedSrgbOfRadiance) {
  // L = B/π; sRGB (IEC 61966-2-1): 1 -> 255, 0.5 -> 0.7354 -> 188, 0.002 (linear part) -> 0.02584
  // -> 7.
  EXPECT_EQ(trueColour({M_PI, M_PI / 2, 0.002 * M_PI}, 1),
            (std::array<std::uint8_t, 3>{255, 188, 7}));
  EXPECT_EQ(trueColour({M_PI, M_PI, M_PI}, 0.5), trueColour({M_PI / 2, M_PI / 2, M_PI / 2}, 1));
  EXPECT_EQ(trueColour({100, 0, 0}, 1)[0], 255);  // clamped
}

TEST(ViewSettings, PhotometricLuminanceIs683TimesYOverPi) {
  const Vec3 white{M_PI, M_PI, M_PI};  // L = 1 W/(m² sr) in every channel
  EXPECT_NEAR(channelValue(white, Channel::Luminance, true), 683.0, 1e-9);
  const Vec3 green{0, M_PI, 0};
  EXPECT_NEAR(channelValue(green, Channel::Luminance, true), 683.0 * 0.7152, 1e-9);
  EXPECT_NEAR(channelValue(green, Channel::Luminance, false), 0.7152 * M_PI, 1e-12);
  EXPECT_EQ(channelValue({1, 2, 3}, Channel::Blue, false), 3);
  EXPECT_NE(channelLabel(Channel::Luminance, true).find("cd/m²"), std::string::npos);
  EXPECT_NE(channelLabel(Channel::Red, false).find("W/m²"), std::string::npos);
}

PatchData strip(const std::vector<double>& luminance, const std::vector<double>& area) {
  PatchData p;
  for (std::size_t i = 0; i < luminance.size(); ++i) {
    p.polygons.push_back({});
    p.area.push_back(area[i]);
    p.radiosity.push_back(Vec3{1, 1, 1} * (luminance[i] * M_PI));  // Y(B)/π = luminance
    p.emission.push_back({});
    p.surface.push_back(0);
    p.reflectance.push_back({});
  }
  return p;
}

TEST(ViewSettings, AutoExposureMapsAreaWeighted95thPercentileTo08) {
  // 94% of the area at luminance 1, 6% at 10: the 95th percentile by area is 10.
  EXPECT_NEAR(autoExposure(strip({1, 10}, {0.94, 0.06})), 0.08, 1e-12);
  EXPECT_NEAR(autoExposure(strip({1, 10}, {0.96, 0.04})), 0.8, 1e-12);
  PatchData withLamp = strip({1, 1000}, {0.5, 0.5});
  withLamp.emission[1] = {5, 5, 5};  // emitters do not count
  EXPECT_NEAR(autoExposure(withLamp), 0.8, 1e-12);
}

TEST(ViewSettings, FalseColourTopIsArea99thPercentileOfNonEmitters) {
  std::vector<double> lum, area(100, 1.0);
  for (int i = 1; i <= 100; ++i) lum.push_back(i);
  PatchData p = strip(lum, area);
  EXPECT_DOUBLE_EQ(falseColourTop(p, lum), 99);  // the hottest 1 % of the area is above
  p.emission[98] = {1, 1, 1};                    // an emitter no longer counts
  EXPECT_DOUBLE_EQ(falseColourTop(p, lum), 100);
  EXPECT_NEAR(falseColourTop(strip({0.01234}, {1}), {0.01234}), 0.013, 1e-15);  // two digits, up
}

TEST(MatrixCells, BlockMeansCoverShortTiles) {
  // 5×5 with F_ij = i + 10 j; at most 2 cells: blocks of 3, the last tile 2 wide.
  FormFactorRows f;
  f.n = 5;
  f.rowStart = {0};
  for (int i = 0; i < 5; ++i) {
    for (int j = 0; j < 5; ++j) {
      f.column.push_back(j);
      f.value.push_back(i + 10.0 * j);
    }
    f.rowStart.push_back(f.nonZeros());
  }
  const MatrixCells m = downsampleMatrix(f, 2);
  ASSERT_EQ(m.cells, 2);
  EXPECT_EQ(m.block, 3);
  EXPECT_DOUBLE_EQ(m.value[0], 1 + 10 * 1);      // rows 0..2, columns 0..2: mean i 1, mean j 1
  EXPECT_DOUBLE_EQ(m.value[1], 1 + 10 * 3.5);    // columns 3..4
  EXPECT_DOUBLE_EQ(m.value[3], 3.5 + 10 * 3.5);  // rows 3..4, columns 3..4
  EXPECT_EQ(downsampleMatrix(f, 5).block, 1);
}

TEST(Viewer, ParsesSize) {
  int w = 0, h = 0;
  parseSize("640x480", w, h);
  EXPECT_EQ(w, 640);
  EXPECT_EQ(h, 480);
  EXPECT_THROW(parseSize("640", w, h), InputError);
  EXPECT_THROW(parseSize("8x8", w, h), InputError);
  EXPECT_THROW(parseSize("640x-1", w, h), InputError);
}

/// Bad input fails before the display is needed, names what is wrong, and writes nothing.
TEST(Viewer, BadInputFailsWithoutWriting) {
  radkit::test::TempDir dir;
  test::writeTestRun(dir.path(""));
  auto failure = [&](ViewerOptions o) {
    o.screenshot = dir.path("shot.png");
    try {
      runViewer(o);
    } catch (const InputError& e) {
      EXPECT_FALSE(std::filesystem::exists(o.screenshot));
      EXPECT_FALSE(std::filesystem::exists(o.screenshot + ".tmp"));
      return std::string(e.what());
    }
    return std::string("no error");
  };
  ViewerOptions ok;
  ok.runFolder = dir.path("");
  ViewerOptions o = ok;
  o.mode = "heat";
  EXPECT_NE(failure(o).find("unknown mode"), std::string::npos);
  o = ok;
  o.mode = "formfactors-row:3";
  EXPECT_NE(failure(o).find("no such patch; ids are 0..2"), std::string::npos);
  o = ok;
  o.width = 4;
  EXPECT_NE(failure(o).find("16..8192"), std::string::npos);
  o = ok;
  o.channel = "r";
  o.photometric = true;
  EXPECT_NE(failure(o).find("--photometric"), std::string::npos);
  o = ok;
  o.runFolder = dir.path("missing");
  EXPECT_NE(failure(o).find("no such run folder"), std::string::npos);
  std::filesystem::remove(dir.path("formfactors.mtx"));
  o = ok;
  o.mode = "matrix";
  EXPECT_NE(failure(o).find("formfactors.bin"), std::string::npos);
}

/// `radkit view` on bad input: non-zero exit, a message naming what and how to fix it, no
/// file. Skips until apps/ registers the view command in the radkit binary.
TEST(ViewCommand, BadInputExitsNonZeroWithoutWriting) {
  if (!std::filesystem::exists(RADKIT_BINARY) ||
      radkit::test::runRadkit("view --help").exitCode != 0)
    GTEST_SKIP() << "radkit binary without the view command";
  radkit::test::TempDir dir;
  test::writeTestRun(dir.path(""));
  const std::string shot = " --screenshot '" + dir.path("shot.png") + "'";
  const std::string run = "'" + dir.path("") + "'";
  struct Case {
    std::string args, message;
  };
  for (const Case& c :
       {Case{"view '" + dir.path("nope") + "'" + shot, "no such run folder"},
        Case{"view " + run + shot + " --mode sideways", "unknown mode"},
        Case{"view " + run + shot + " --mode formfactors-row:99", "no such patch"},
        Case{"view " + run + shot + " --size 100", "WIDTHxHEIGHT"},
        Case{"view " + run + shot + " --channel q --mode false-colour", "unknown channel"}}) {
    const radkit::test::RunResult r = radkit::test::runRadkit(c.args);
    EXPECT_NE(r.exitCode, 0) << c.args;
    EXPECT_NE(r.output.find(c.message), std::string::npos) << c.args << "\n" << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir.path("shot.png"))) << c.args;
  }
}

}  // namespace
}  // namespace radkit::viewer
