#include "tests/raster/raster_harness.h"

#include <algorithm>
#include <cstring>

#include "kernels/raster/raster_layout.h"
#include "runtime/error.h"
#include "runtime/gpu_scene.h"
#include "runtime/passes/gbuffer_stage.h"
#include "runtime/vulkan/buffer.h"
#include "runtime/vulkan/context.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb::test {
namespace {

template <class T>
vk::Buffer uploaded(const vk::Context& context, std::vector<T> values, const char* name) {
  if (values.empty()) values.emplace_back();
  vk::Buffer buffer(context, values.size() * sizeof(T), vk::MemoryUse::Device, name);
  buffer.upload(std::span<const T>(values));
  return buffer;
}

// Records until the rasterizer's buffers fit the frame.
template <class Record>
void runUntilItFits(const vk::Context& context, Record&& record, passes::RasterizePass& pass) {
  vk::FrameRecorder frame(context);
  for (int attempt = 0; attempt < 3; ++attempt) {
    frame.begin();
    record(frame);
    frame.submitAndWait();
    if (!pass.growIfOverflowed()) return;
  }
  throw Error("rasterizer buffers still overflow after 3 attempts");
}

}  // namespace

float Visibility::depthAt(uint32_t x, uint32_t y) const {
  const uint32_t bits = entries[size_t(y) * width + x].y;
  float depth;
  std::memcpy(&depth, &bits, sizeof(depth));
  return depth;
}

void ClipTriangles::add(glm::vec4 a, glm::vec4 b, glm::vec4 c, bool isDoubleSided) {
  const auto base = static_cast<uint32_t>(clip.size());
  clip.insert(clip.end(), {a, b, c});
  triangles.push_back({base, base + 1, base + 2, static_cast<uint32_t>(doubleSided.size())});
  doubleSided.push_back(isDoubleSided);
}

Visibility rasterizeClipTriangles(const vk::Context& context, const ClipTriangles& input, uint32_t width,
                                  uint32_t height, passes::VisibilityScheme scheme) {
  std::vector<gpu::GpuInstance> instances(std::max<size_t>(1, input.doubleSided.size()));
  for (size_t i = 0; i < input.doubleSided.size(); ++i)
    instances[i].flags = input.doubleSided[i] ? HMB_INSTANCE_DOUBLE_SIDED : 0u;
  const vk::Buffer clip = uploaded(context, input.clip, "test clip positions");
  const vk::Buffer triangles = uploaded(context, input.triangles, "test triangles");
  const vk::Buffer instanceBuffer = uploaded(context, instances, "test instances");
  const vk::Buffer visibility(context, uint64_t(width) * height * sizeof(uint64_t), vk::MemoryUse::Device,
                              "test visibility");

  passes::RasterizePass pass(context, scheme);
  const auto triangleCount = static_cast<uint32_t>(input.triangles.size());
  pass.reserve(triangleCount, width, height);
  const passes::RasterInputs inputs{&triangles, &instanceBuffer, &clip, triangleCount};
  runUntilItFits(context, [&](vk::FrameRecorder& frame) { pass.record(frame, inputs, visibility, width, height); },
                 pass);
  Visibility out{width, height, visibility.download<glm::uvec2>(), pass.stats(), {}, {}};
  out.setup = pass.setupBuffer().download<gpu::SetupTriangle>();
  out.setup.resize(out.stats.setupTriangles);
  out.pairs = pass.pairBuffer().download<glm::uvec2>();
  out.pairs.resize(out.stats.tilePairs);
  return out;
}

std::vector<oracle::OracleTriangle> oracleTriangles(const ClipTriangles& input) {
  std::vector<oracle::OracleTriangle> out;
  out.reserve(input.triangles.size());
  for (size_t t = 0; t < input.triangles.size(); ++t) {
    const gpu::GpuTriangle& tri = input.triangles[t];
    oracle::OracleTriangle o;
    o.clip[0] = input.clip[tri.v0];
    o.clip[1] = input.clip[tri.v1];
    o.clip[2] = input.clip[tri.v2];
    o.id = static_cast<uint32_t>(t);
    o.doubleSided = input.doubleSided[tri.instance];
    out.push_back(o);
  }
  return out;
}

GBufferReadback renderGBuffer(const vk::Context& context, const scene::Scene& scene, float frameTime, uint32_t width,
                              uint32_t height, passes::VisibilityScheme scheme) {
  GpuScene gpuScene(context, scene);
  gpuScene.setFrame(scene, frameTime, width, height);
  passes::GBufferStage stage(context, scheme);
  stage.prepare(gpuScene, width, height);
  vk::FrameRecorder frame(context);
  for (int attempt = 0;; ++attempt) {
    frame.begin();
    stage.record(frame, gpuScene);
    frame.submitAndWait();
    if (!stage.growIfOverflowed()) break;
    if (attempt == 2) throw Error("rasterizer buffers still overflow after 3 attempts");
  }

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
  out.color = stage.color().download<glm::vec4>();
  out.normalDepth = stage.normalDepth().download<glm::vec4>();
  out.velocity = stage.velocity().download<glm::vec2>();
  out.objectId = stage.objectId().download<uint32_t>();
  return out;
}

double idAgreement(const Visibility& visibility, const oracle::OracleImage& oracle) {
  size_t same = 0;
  const size_t pixels = size_t(visibility.width) * visibility.height;
  for (size_t i = 0; i < pixels; ++i) {
    const uint32_t compute = visibility.entries[i].x;
    const uint32_t expected = oracle.ids[i] == 0 ? HMB_VIS_EMPTY : oracle.ids[i] - 1;
    same += compute == expected;
  }
  return pixels == 0 ? 1.0 : double(same) / double(pixels);
}

}  // namespace hmb::test
