// The compute rasterizer against the graphics-pipeline oracle on the same device: the same
// clip-space triangles (the transform kernel's output) must give the same triangle at
// (almost) every pixel, on every reference scene, with both visibility schemes.
#include <ostream>
#include <string>

#include <gtest/gtest.h>

#include "hmblur/load_scene.h"
#include "scenes/reference_scenes.h"
#include "tests/raster/raster_harness.h"
#include "tests/support/vulkan_test.h"

namespace hmb::test {
namespace {

struct AgreementCase {
  std::string scene;
  passes::VisibilityScheme scheme;
};

void PrintTo(const AgreementCase& c, std::ostream* os) {
  *os << c.scene << " / " << passes::visibilitySchemeName(c.scheme);
}

class OracleAgreementTest : public VulkanTest, public ::testing::WithParamInterface<AgreementCase> {};

TEST_P(OracleAgreementTest, ComputeVisibilityMatchesGraphicsPipeline) {
  const AgreementCase& param = GetParam();
  const scene::Scene scene = scene::loadScene(param.scene);
  constexpr uint32_t kWidth = 320, kHeight = 180;
  const GBufferReadback gbuffer =
      renderGBuffer(context(), scene, scene.settings.frameTime, kWidth, kHeight, param.scheme);
  const oracle::OracleImage expected = oracle::rasterizeWithGraphicsPipeline(
      context(), kWidth, kHeight, oracleTriangles(gbuffer.clipTriangles));

  size_t covered = 0;
  for (uint32_t id : expected.ids) covered += id != 0;
  ASSERT_GT(covered, size_t(kWidth) * kHeight / 4) << "the camera should see the scene";
  const double agreement = idAgreement(gbuffer.visibility, expected);
  RecordProperty("id_agreement", std::to_string(agreement));
  EXPECT_GE(agreement, 0.995);
}

std::vector<AgreementCase> agreementCases() {
  std::vector<AgreementCase> cases;
  for (const std::string& name : scene::referenceSceneNames())
    for (auto scheme : {passes::VisibilityScheme::Int64Atomics, passes::VisibilityScheme::Depth32TwoPass,
                       passes::VisibilityScheme::TileLists})
      cases.push_back({name, scheme});
  return cases;
}

INSTANTIATE_TEST_SUITE_P(ReferenceScenes, OracleAgreementTest, ::testing::ValuesIn(agreementCases()),
                         [](const ::testing::TestParamInfo<AgreementCase>& info) {
                           std::string name = info.param.scene + "_" +
                                              passes::visibilitySchemeName(info.param.scheme);
                           for (char& c : name)
                             if (c == '-') c = '_';
                           return name;
                         });

}  // namespace
}  // namespace hmb::test
