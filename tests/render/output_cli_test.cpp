// radkit render end to end: the image formats, and photon-map's --spp.
#include <gtest/gtest.h>

#include <filesystem>

#include "render/exr_io.h"
#include "render/hdr_io.h"
#include "tests/common/test_util.h"

namespace radkit {
namespace {

TEST(RenderFormats, ExrHoldsThePfmsValues) {
  test::TempDir dir;
  const std::string common = "render --shading path-trace --spp 2 --size 12x8 --seed 3 --out ";
  test::RunResult r = test::runRadkit(common + dir.path("a.pfm"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  r = test::runRadkit(common + dir.path("a.exr"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const RadianceImage pfm = readPfm(dir.path("a.pfm")), exr = readExr(dir.path("a.exr"));
  ASSERT_EQ(exr.width, 12);
  ASSERT_EQ(exr.height, 8);
  ASSERT_EQ(exr.radiance.size(), pfm.radiance.size());
  for (std::size_t k = 0; k < pfm.radiance.size(); ++k)
    EXPECT_EQ(exr.radiance[k], pfm.radiance[k]) << k;
  EXPECT_GT(exr.meanRadiance(), 0);
  EXPECT_FALSE(std::filesystem::exists(dir.path("a.exr.tmp")));
}

TEST(RenderFormats, UnsupportedExtensionIsRefusedBeforeRendering) {
  test::TempDir dir;
  for (const char* name : {"x.jpg", "x.tiff", "x"}) {
    test::RunResult r = test::runRadkit("render --spp 1 --size 8x8 --out " + dir.path(name));
    EXPECT_NE(r.exitCode, 0) << name;
    EXPECT_NE(r.output.find("Fix: end the name in .png"), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir.path(name))) << name;
  }
}

TEST(RenderFormats, PhotonMapTakesSpp) {
  // --spp given: passes of one jittered ray per pixel, averaged; not given: one pass as before.
  test::TempDir dir;
  const std::string common =
      "render --shading photon-map --patches 60 --photons 2000 --size 8x8 --out ";
  ASSERT_EQ(test::runRadkit(common + dir.path("default.pfm")).exitCode, 0);
  ASSERT_EQ(test::runRadkit(common + dir.path("one.pfm") + " --spp 1").exitCode, 0);
  ASSERT_EQ(test::runRadkit(common + dir.path("four.pfm") + " --spp 4").exitCode, 0);
  const RadianceImage d = readPfm(dir.path("default.pfm")), one = readPfm(dir.path("one.pfm")),
                      four = readPfm(dir.path("four.pfm"));
  EXPECT_EQ(d.radiance, one.radiance);
  EXPECT_NE(one.radiance, four.radiance) << "--spp 4 must average four passes";
}

}  // namespace
}  // namespace radkit
