// The benchmark runs on a small scene and reports both rates and their ratio.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "experiments/ff_benchmark.h"
#include "tests/radiosity/test_scenes.h"

namespace radkit {

TEST(FormFactorBenchmark, Construct) {
  test::MeshBuilder b = test::cubeInterior(3);
  b.addRectangle("blocker", {0.3, 0.3, 0.5}, {0.4, 0, 0}, {0, 0.4, 0}, 2, 2);
  RayScene scene(b.mesh());
  FormFactorBenchmarkSettings s;
  s.referenceRays = 20000;
  FormFactorBenchmark r = benchmarkFormFactors(b.mesh(), scene, s);
  EXPECT_GT(r.raysCast, 0);
  EXPECT_GT(r.raysPerSecond, 0);
  EXPECT_GT(r.referenceRaysPerSecond, 0);
  EXPECT_GT(r.ratio, 0);
  EXPECT_EQ(r.referenceRays, 20000);
  nlohmann::json j = toJson(r);
  EXPECT_EQ(j["benchmark"], "formfactors");
  EXPECT_TRUE(j.contains("ratio"));
  EXPECT_GT(j["peak_resident_bytes"].get<double>(), 0);
}

}  // namespace radkit
