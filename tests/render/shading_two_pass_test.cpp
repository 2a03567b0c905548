// Two-pass shading: the lighting it reads from the radiosity solution and the model
// substitutions of its Phong and Cook-Torrance modes. Its images of the diffuse-only Cornell
// box are compared with the radiosity image in shading_cornell_test.cpp.
#include "render/shading.h"

#include <gtest/gtest.h>

#include "geometry/scene_loader.h"
#include "tests/common/test_util.h"

namespace radkit {
namespace {

class TwoPass : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    s_scene = new Scene(loadScene(test::dataPath("cornell-box.json")));
    PipelineSettings settings;
    settings.mesh.targetPatches = 100;
    s_result = new PipelineResult(runPipeline(*s_scene, settings));
  }
  static void TearDownTestSuite() {
    delete s_result;
    delete s_scene;
  }
  static Scene* s_scene;
  static PipelineResult* s_result;
};

Scene* TwoPass::s_scene = nullptr;
PipelineResult* TwoPass::s_result = nullptr;

TEST_F(TwoPass, Construct) {
  const RadiosityLighting l = radiosityLighting(*s_result);
  ASSERT_EQ(l.indirectIrradiance.size(), s_result->radiosity.size());
  // B = E + ρ H on every patch, and the indirect part never exceeds the whole.
  for (int i = 0; i < s_result->mesh.size(); ++i) {
    EXPECT_LE(l.indirectIrradiance[i].y, s_result->irradiance[i].y + 1e-12);
    EXPECT_GE(l.indirectIrradiance[i].y, 0);
  }
}

TEST_F(TwoPass, ConstructSubstitutions) {
  const Material ct =
      makeMaterial("ct", "cook-torrance", "roughness=0.5");  // α = 0.25: n = 2/α² − 2 = 30
  EXPECT_NE(makeShadingBsdf(ct, {}, GlossyModel::Phong)->describe().find("n=30"),
            std::string::npos);
  const Material phong = makeMaterial("phong", "phong", "shininess=30");  // α = √(2/32) = 0.25
  EXPECT_NE(makeShadingBsdf(phong, {}, GlossyModel::CookTorrance)->describe().find("alpha=0.25"),
            std::string::npos);
  EXPECT_NE(makeShadingBsdf(phong, {}, GlossyModel::AsDeclared)->describe().find("phong"),
            std::string::npos);
}

}  // namespace
}  // namespace radkit
