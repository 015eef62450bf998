#include "tests/raster/raster_harness.h"

#include <optional>

#include <algorithm>
#include <cstring>

#include "hmblur/buffer.h"
#include "hmblur/context.h"
#include "hmblur/error.h"
#include "kernels/raster/raster_layout.h"
#include "runtime/device_scene/gpu_scene.h"
#include "runtime/passes/gbuffer_stage.h"
#include "runtime/passes/image_layer.h"
#include "runtime/passes/rasterize_pass.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb::test {

float Visibility::depthAt(uint32_t x, uint32_t y) const {
  return gpu::depthOfKey(entries[size_t(y) * width + x].y);
}

void ClipTriangles::add(glm::vec4 a, glm::vec4 b, glm::vec4 c, bool isDoubleSided) {
  const auto base = static_cast<uint32_t>(clip.size());
  clip.insert(clip.end(), {a, b, c});
  triangles.push_back({base, base + 1, base + 2, static_cast<uint32_t>(doubleSided.size())});
  doubleSided.push_back(isDoubleSided);
}

namespace {

// The tile-lists scheme turned each pair's tile into its list's next pair: walks every tile's
// list and gives each pair its tile back, so the binning checks read the same pairs as for the
// other schemes. A pair no list reaches, or that two reach, keeps an impossible tile.
std::vector<glm::uvec2> pairsFromTileLists(const passes::RasterizePass& pass, std::vector<glm::uvec2> linked) {
  const std::vector<uint32_t> heads = pass.tileHeadBuffer().download<uint32_t>();
  std::vector<glm::uvec2> pairs(linked.size(), glm::uvec2(~0u));
  std::vector<uint32_t> visits(linked.size(), 0);
  for (uint32_t tile = 0; tile < heads.size(); ++tile) {
    size_t steps = 0;
    for (uint32_t p = heads[tile]; p != HMB_TILE_LIST_END && steps <= linked.size(); p = linked[p].y, ++steps) {
      if (p >= linked.size()) break;
      pairs[p] = ++visits[p] == 1 ? glm::uvec2(linked[p].x, tile) : glm::uvec2(~0u);
    }
  }
  return pairs;
}

}  // namespace

Visibility rasterizeClipTriangles(const vk::Context& context, const ClipTriangles& input, uint32_t width,
                                  uint32_t height, passes::VisibilityScheme scheme) {
  std::vector<gpu::GpuInstance> instances(std::max<size_t>(1, input.doubleSided.size()));
  for (size_t i = 0; i < input.doubleSided.size(); ++i)
    instances[i].flags = input.doubleSided[i] ? HMB_INSTANCE_DOUBLE_SIDED : 0u;
  const vk::Buffer clip = vk::uploadedBuffer(context, input.clip, "test clip positions");
  const vk::Buffer triangles = vk::uploadedBuffer(context, input.triangles, "test triangles");
  const vk::Buffer instanceBuffer = vk::uploadedBuffer(context, instances, "test instances");
  const vk::Buffer visibility(context, passes::RasterizePass::visibilityBytes(width, height), vk::MemoryUse::Device,
                              "test visibility");

  passes::RasterizePass pass(context, scheme);
  const auto triangleCount = static_cast<uint32_t>(input.triangles.size());
  pass.reserve(triangleCount, width, height);
  const passes::RasterInputs inputs{&triangles, &instanceBuffer, &clip, triangleCount};
  vk::FrameRecorder frame(context);
  passes::submitUntilRasterFits(frame, pass, [&](vk::FrameRecorder& f) {
    pass.record(f, inputs, visibility, width, height);
  });
  Visibility out{width, height, visibility.download<glm::uvec2>(), pass.stats(), {}, {}};
  out.entries.resize(size_t(width) * height);  // the buffer's padding to whole 16-byte records is no pixel
  out.setup = pass.setupBuffer().download<gpu::SetupTriangle>();
  out.setup.resize(out.stats.setupTriangles);
  out.pairs = pass.pairBuffer().download<glm::uvec2>();
  out.pairs.resize(out.stats.tilePairs);
  if (scheme == passes::VisibilityScheme::TileLists) out.pairs = pairsFromTileLists(pass, out.pairs);
  return out;
}

std::vector<oracle::OracleTriangle> oracleTriangles(const ClipTriangles& input) {
  return oracle::oracleTriangles(input.clip, input.triangles, input.doubleSided);
}

GBufferReadback renderGBuffer(const vk::Context& context, const scene::Scene& scene, float frameTime, uint32_t width,
                              uint32_t height, passes::VisibilityScheme scheme, bool shutterPaths) {
  GpuScene gpuScene(context, scene);
  gpuScene.setFrame(scene, frameTime, width, height);
  passes::GBufferStage stage(context, scheme);
  std::optional<passes::GBufferStage::ShutterPaths> paths;
  if (shutterPaths)
    paths = passes::GBufferStage::ShutterPaths{scene.settings.exposure, scene.settings.fps,
                                               shutterClips(scene, frameTime, scene.settings.exposure, width, height)};
  stage.prepare(gpuScene, width, height, paths);
  vk::FrameRecorder frame(context);
  passes::submitUntilRasterFits(frame, stage.rasterizer(), [&](vk::FrameRecorder& f) { stage.record(f, gpuScene); });

  GBufferReadback out;
  out.clipTriangles.clip = stage.clipCurrent().download<glm::vec4>();
  out.clipTriangles.clip.resize(gpuScene.instanceVertexCount());
  out.clipTriangles.triangles = gpuScene.triangles().download<gpu::GpuTriangle>();
  out.clipTriangles.triangles.resize(gpuScene.triangleCount());
  for (const scene::Instance& instance : scene.instances) {
    const uint32_t material = scene.meshes.at(instance.mesh).material;
    out.clipTriangles.doubleSided.push_back(material < scene.materials.size() && scene.materials[material].doubleSided);
  }
  out.visibility = {width, height, stage.visibility().download<glm::uvec2>(), stage.rasterizer().stats(), {}, {}};
  static_cast<LayerReadback&>(out) = readLayer(stage.layer(), uint64_t(width) * height);
  if (stage.shutterPaths()) {
    out.shutterPaths = stage.shutterPaths()->download<glm::uvec2>();
    out.shutterPaths.resize(size_t(width) * height);
  }
  return out;
}

double idAgreement(const Visibility& visibility, const oracle::OracleImage& oracle) {
  return oracle::idAgreement(visibility.entries, oracle);
}

}  // namespace hmb::test
