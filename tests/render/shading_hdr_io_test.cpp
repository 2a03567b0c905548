// HDR output: PFM round trip and byte layout, the filmic curve's fixed points.
#include "render/hdr_io.h"

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>

#include "tests/common/test_util.h"

namespace radkit {
namespace {

TEST(HdrIo, ExactPfmRoundTrip) {
  test::TempDir dir;
  RadianceImage img;
  img.width = 3;
  img.height = 2;
  img.radiance = {{0, 1, 2}, {0.5, 1e-3, 1e4}, {3, 4, 5},
                  {6, 7, 8}, {0.25, 0.125, 9}, {1e-8, 100, 0}};
  writePfm(dir.path("a.pfm"), img);
  RadianceImage back = readPfm(dir.path("a.pfm"));
  ASSERT_EQ(back.width, 3);
  ASSERT_EQ(back.height, 2);
  for (std::size_t k = 0; k < img.radiance.size(); ++k)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(back.radiance[k][c], float(img.radiance[k][c]));
  // The format stores the bottom row first: the first float after the header is pixel (0, 1).
  std::ifstream in(dir.path("a.pfm"), std::ios::binary);
  std::string header((std::istreambuf_iterator<char>(in)), {});
  ASSERT_EQ(header.rfind("PF\n3 2\n-1.0\n", 0), 0u);
  float first;
  std::memcpy(&first, header.data() + 12, 4);
  EXPECT_EQ(first, 6.0f);
  EXPECT_THROW(readPfm(dir.file("bad.pfm", "P6\n1 1\n255\nabc")), std::runtime_error);
  EXPECT_THROW(readPfm(dir.file("short.pfm", "PF\n2 2\n-1.0\n1234")), std::runtime_error);
}

TEST(HdrIo, ExactFilmicCurve) {
  EXPECT_EQ(acesFilmic(0), 0);
  EXPECT_NEAR(acesFilmic(1), (2.51 + 0.03) / (2.43 + 0.59 + 0.14), 1e-15);  // 0.80380...
  EXPECT_EQ(acesFilmic(1e6), 1);                                            // clamped
  double previous = 0;
  for (double x = 0.01; x < 7; x *= 1.3) {  // monotone below its clamp at x ≈ 7.24
    EXPECT_GT(acesFilmic(x), previous);
    previous = acesFilmic(x);
  }
  RadianceImage img;
  img.width = img.height = 1;
  img.radiance = {{0.2, 0.5, 3}};
  img.patch = {0};
  Canvas srgb = toneMapCurve(img, 1, ToneCurve::Srgb), ref = toneMap(img, 1);
  EXPECT_EQ(srgb.at(0, 0).r, ref.at(0, 0).r);
  EXPECT_EQ(toneMapCurve(img, 1, ToneCurve::Filmic).at(0, 0).b,
            std::lround(255 * srgbEncode(acesFilmic(3))));
}

}  // namespace
}  // namespace radkit
