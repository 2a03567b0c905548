// The comparison harness on synthetic images with known noise: subtracting the reference's
// own noise recovers the image's true error, region by region; without it the error would be
// overstated.
#include "render/image_comparison.h"

#include <gtest/gtest.h>

#include <cmath>

#include "util/sampling.h"

namespace radkit {
namespace {

double gaussian(Rng& rng) {
  const double u = 1 - rng.uniform(), v = rng.uniform();
  return std::sqrt(-2 * std::log(u)) * std::cos(2 * M_PI * v);
}

RadianceImage blank(int w, int h) {
  RadianceImage img;
  img.width = w, img.height = h;
  img.radiance.assign(std::size_t(w) * h, Vec3{});
  return img;
}

TEST(ImageComparison, StatisticalSubtractsTheReferenceNoise) {
  // Truth t; image t + N(0, σ_x²), σ_x 0.1 on the left half and 0.3 on the right; two
  // references t + N(0, σ_r²), σ_r = 0.2. Per value d = (x − r̄)² − (r₁ − r₂)²/4 has mean σ_x²
  // and variance 2(σ_x² + σ_r²/2)² + σ_r⁴/2 (r̄ and r₁ − r₂ are independent), so the
  // estimated MSE must meet σ_x² within 4 standard errors √(Var d / values).
  const int w = 64, h = 64;
  const double sr = 0.2;
  RadianceImage image = blank(w, h), a = blank(w, h), b = blank(w, h);
  std::vector<int> region(std::size_t(w) * h);
  Rng rng(17, 0, 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t k = std::size_t(y) * w + x;
      region[k] = x < w / 2 ? 0 : 1;
      const double sx = region[k] == 0 ? 0.1 : 0.3;
      for (int c = 0; c < 3; ++c) {
        const double truth = 1 + 0.5 * std::sin(0.1 * x + c) * std::cos(0.2 * y);
        image.radiance[k][c] = truth + sx * gaussian(rng);
        a.radiance[k][c] = truth + sr * gaussian(rng);
        b.radiance[k][c] = truth + sr * gaussian(rng);
      }
    }
  const std::vector<RegionError> e = compareToReference(image, {a, b}, region, {"left", "right"});
  ASSERT_EQ(e.size(), 3u);
  EXPECT_EQ(e[0].name, "all");
  EXPECT_EQ(e[0].pixels, w * h);
  EXPECT_EQ(e[1].pixels, w * h / 2);
  for (int r : {1, 2}) {
    const double sx = r == 1 ? 0.1 : 0.3, values = 3.0 * e[r].pixels;
    const double se =
        std::sqrt((2 * std::pow(sx * sx + sr * sr / 2, 2) + std::pow(sr, 4) / 2) / values);
    EXPECT_NEAR(e[r].rmse * e[r].rmse, sx * sx, 4 * se) << e[r].name;
    EXPECT_NEAR(e[r].referenceNoise * e[r].referenceNoise, sr * sr / 2,
                4 * std::pow(sr, 2) / std::sqrt(2 * values));
    EXPECT_GT(e[r].rawRmse * e[r].rawRmse - sx * sx, 4 * se)
        << "the raw error must be visibly inflated";
  }
  EXPECT_NEAR(e[1].referenceMean, 1, 0.05);
  EXPECT_THROW(compareToReference(image, {blank(8, 8)}, region, {"left", "right"}),
               std::invalid_argument);
}

}  // namespace
}  // namespace radkit
