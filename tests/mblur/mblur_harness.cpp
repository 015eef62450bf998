#include "tests/mblur/mblur_harness.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <span>

#include <gtest/gtest.h>

#include "hmblur/buffer.h"
#include "kernels/gbuffer/gbuffer_layout.h"
#include "runtime/passes/gather_pass.h"
#include "runtime/passes/jimenez_gather_pass.h"
#include "runtime/passes/neighbor_max_pass.h"
#include "runtime/passes/post_process_stage.h"
#include "runtime/passes/tile_max_pass.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb::test::mblur {

namespace {

template <class T>
vk::Buffer deviceBuffer(vk::Context& context, const std::vector<T>& values, const char* name) {
  return vk::uploadedBuffer(context, values, name);
}

// Filled with NaN: a pixel no pass writes fails the finite check of expectMatchesReference.
vk::Buffer outputBuffer(vk::Context& context, size_t count, const char* name) {
  vk::Buffer buffer(context, std::max<size_t>(count, 1) * sizeof(glm::vec4), vk::MemoryUse::Device, name);
  const std::vector<glm::vec4> unwritten(std::max<size_t>(count, 1), glm::vec4(std::numeric_limits<float>::quiet_NaN()));
  buffer.upload(std::span<const glm::vec4>(unwritten));
  return buffer;
}

template <class T>
std::vector<T> downloadFirst(const vk::Buffer& buffer, size_t count) {
  std::vector<T> values = buffer.download<T>();
  values.resize(count);
  return values;
}

// The layer packed as the resolve packs it (kernels/shared/layer_layout.h).
struct LayerBuffers {
  vk::Buffer samples, surfaces, velocities, shutterPaths;
  passes::MotionBlurInputs inputs() const {
    return {&samples, &surfaces, &velocities, width, height, shutterPaths.handle() ? &shutterPaths : nullptr};
  }
  uint32_t width = 0, height = 0;
};

LayerBuffers upload(vk::Context& context, const Layer& layer) {
  LayerBuffers buffers{deviceBuffer(context, packedSamples(layer), "test samples"),
                       deviceBuffer(context, packedSurfaces(layer), "test surfaces"),
                       deviceBuffer(context, packedVelocities(layer), "test velocities"), {}, layer.width,
                       layer.height};
  if (!layer.shutterPaths.empty()) {
    std::vector<glm::uvec2> paths = layer.shutterPaths;
    paths.resize((paths.size() + 1) / 2 * 2);  // whole 16-byte records for the texel view
    buffers.shutterPaths = deviceBuffer(context, paths, "test shutter paths");
  }
  return buffers;
}

}  // namespace

std::vector<glm::uvec2> randomShutterPaths(const std::vector<glm::vec2>& velocity, std::mt19937& rng,
                                           float exposureFrames) {
  std::uniform_real_distribution<float> bend(-6.0f, 6.0f);
  std::uniform_int_distribution<int> pick(0, 19);
  std::vector<glm::uvec2> paths(velocity.size());
  for (size_t i = 0; i < velocity.size(); ++i) {
    const glm::vec2 open = velocity[i] * exposureFrames;
    glm::uvec2 record = packShutterPath(0.5f * open + glm::vec2(bend(rng), bend(rng)), open);
    switch (pick(rng)) {
      case 0: record = glm::uvec2(HMB_NO_SHUTTER_PATH); break;
      case 1: record = glm::uvec2(0x7c007c00u, 0x00007c00u); break;  // +inf halves
      case 2: record = packShutterPath({65504.0f, -65504.0f}, {65504.0f, 65504.0f}); break;
      case 3: record = glm::uvec2(0u); break;
      case 4: record = packShutterPath(open, glm::vec2(0.0f)); break;  // out and back
      default: break;
    }
    paths[i] = record;
  }
  return paths;
}

std::vector<glm::vec4> runTileMax(vk::Context& context, const std::vector<glm::vec2>& velocity, uint32_t width,
                                  uint32_t height, uint32_t tileSize, float velocityScale) {
  const passes::TileGrid grid = passes::tileGridFor(width, height, tileSize);
  Layer layer;
  layer.velocity = velocity;
  const vk::Buffer in = deviceBuffer(context, packedVelocities(layer), "test velocities");
  const vk::Buffer out = outputBuffer(context, grid.count(), "test tile max");
  const passes::TileMaxPass pass(context);
  vk::FrameRecorder frame(context);
  frame.begin();
  pass.record(frame, in, out, width, height, tileSize, velocityScale);
  frame.submitAndWait();
  return downloadFirst<glm::vec4>(out, grid.count());
}

std::vector<glm::vec4> runNeighborMax(vk::Context& context, const std::vector<glm::vec4>& tileMax,
                                      passes::TileGrid grid, uint32_t neighborhood) {
  const vk::Buffer in = deviceBuffer(context, tileMax, "test tile max");
  const vk::Buffer out = outputBuffer(context, grid.count(), "test neighbor max");
  const passes::NeighborMaxPass pass(context);
  vk::FrameRecorder frame(context);
  frame.begin();
  pass.record(frame, in, out, grid, neighborhood);
  frame.submitAndWait();
  return downloadFirst<glm::vec4>(out, grid.count());
}

std::vector<glm::vec4> runGather(vk::Context& context, const Layer& layer, const std::vector<glm::vec4>& neighborMax,
                                 const passes::PostProcessSettings& settings) {
  const LayerBuffers buffers = upload(context, layer);
  const vk::Buffer tiles = deviceBuffer(context, neighborMax, "test neighbor max");
  const size_t pixels = size_t(layer.width) * layer.height;
  const vk::Buffer out = outputBuffer(context, pixels, "test output");
  const passes::GatherPass pass(context);
  vk::FrameRecorder frame(context);
  frame.begin();
  pass.record(frame, buffers.inputs(), tiles, out, settings);
  frame.submitAndWait();
  return downloadFirst<glm::vec4>(out, pixels);
}

std::vector<glm::vec4> runJimenezGather(vk::Context& context, const Layer& layer,
                                        const std::vector<glm::vec4>& neighborMax,
                                        const passes::PostProcessSettings& settings) {
  const LayerBuffers buffers = upload(context, layer);
  const vk::Buffer tiles = deviceBuffer(context, neighborMax, "test neighbor max");
  const size_t pixels = size_t(layer.width) * layer.height;
  const vk::Buffer out = outputBuffer(context, pixels, "test output");
  const passes::JimenezGatherPass pass(context);
  vk::FrameRecorder frame(context);
  frame.begin();
  pass.record(frame, buffers.inputs(), tiles, out, settings);
  frame.submitAndWait();
  return downloadFirst<glm::vec4>(out, pixels);
}

std::vector<glm::vec4> runStage(vk::Context& context, const Layer& layer, const passes::PostProcessSettings& settings) {
  const LayerBuffers buffers = upload(context, layer);
  const size_t pixels = size_t(layer.width) * layer.height;
  const vk::Buffer out = outputBuffer(context, pixels, "test output");
  passes::PostProcessStage stage(context, settings);
  stage.prepare(layer.width, layer.height);
  vk::FrameRecorder frame(context);
  frame.begin();
  stage.record(frame, buffers.inputs(), out);
  frame.submitAndWait();
  return downloadFirst<glm::vec4>(out, pixels);
}

Layer stillLayer(uint32_t width, uint32_t height) {
  const size_t pixels = size_t(width) * height;
  return {width, height, std::vector<glm::vec4>(pixels, glm::vec4(0.5f, 0.5f, 0.5f, 1.0f)),
          std::vector<glm::vec4>(pixels, glm::vec4(0.0f, 0.0f, 1.0f, 1.0f)),
          std::vector<glm::vec2>(pixels, glm::vec2(0.0f))};
}

Layer randomLayer(uint32_t width, uint32_t height, std::mt19937& rng) {
  Layer layer = stillLayer(width, height);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), drift(-1.0f, 1.0f), motion(-12.0f, 12.0f);
  for (size_t i = 0; i < layer.color.size(); ++i) {
    layer.color[i] = {unit(rng), unit(rng), unit(rng), 1.0f};
    layer.normalDepth[i].w = 10.0f + 0.01f * unit(rng);
    layer.velocity[i] = {drift(rng), drift(rng)};
  }
  for (int r = 0; r < 3; ++r) {
    const uint32_t x0 = uint32_t(unit(rng) * width), y0 = uint32_t(unit(rng) * height);
    const uint32_t x1 = std::min(width, x0 + 1 + uint32_t(unit(rng) * width / 2));
    const uint32_t y1 = std::min(height, y0 + 1 + uint32_t(unit(rng) * height / 2));
    const glm::vec2 v(motion(rng), motion(rng));
    const float depth = 1.0f + 4.0f * unit(rng);
    for (uint32_t y = y0; y < y1; ++y)
      for (uint32_t x = x0; x < x1; ++x) {
        layer.velocity[y * width + x] = v;
        layer.normalDepth[y * width + x].w = depth;  // equal depths across the rectangle
      }
  }
  return layer;
}

std::vector<glm::vec4> referenceTiles(const Layer& layer, const passes::PostProcessSettings& settings) {
  const uint32_t tileSize = settings.effectiveTileSize();
  const auto tiles = tileMax(layer.velocity, layer.width, layer.height, tileSize, settings.velocityScale());
  return neighborMax(tiles, passes::tileGridFor(layer.width, layer.height, tileSize), settings.neighborhood);
}

float maxAbsDifference(glm::vec4 a, glm::vec4 b) {
  float worst = 0.0f;
  for (int i = 0; i < 4; ++i) {
    if (!std::isfinite(a[i]) || !std::isfinite(b[i])) return std::numeric_limits<float>::infinity();
    worst = std::max(worst, std::abs(a[i] - b[i]));
  }
  return worst;
}

bool allFinite(const std::vector<glm::vec4>& values) {
  for (const glm::vec4& v : values)
    for (int i = 0; i < 4; ++i)
      if (!std::isfinite(v[i])) return false;
  return true;
}

void expectMatchesReference(const std::vector<glm::vec4>& device, const std::vector<glm::vec4>& reference,
                            float tolerance) {
  ASSERT_EQ(device.size(), reference.size());
  ASSERT_TRUE(allFinite(device));
  size_t off = 0;
  for (size_t i = 0; i < device.size(); ++i) {
    const float scale = std::max({1.0f, std::abs(reference[i].x), std::abs(reference[i].y), std::abs(reference[i].z),
                                  std::abs(reference[i].w)});
    if (maxAbsDifference(device[i], reference[i]) > tolerance * scale) ++off;
  }
  EXPECT_LE(off, device.size() / 200) << off << " of " << device.size() << " pixels differ from the reference";
}

}  // namespace hmb::test::mblur
