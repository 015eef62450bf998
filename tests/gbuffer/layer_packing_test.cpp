// The image layer's packing (kernels/shared/layer_layout.h) on the device against the same
// functions on the host, on random and adversarial pixels: the kernels pack what the resolve and
// the reveal write, the host packs the tests' inputs and unpacks every readback, so the two must
// agree bit for bit (but for the octahedral normal's rounding, within one step). Also what the
// packing promises: colour within 2^-14 relative (0 for negative, subnormal and NaN, at most
// HMB_LAYER_MAX_COLOR), depth kept bit for bit, velocity bit for bit in the surface and in half
// floats keeping its direction in the sample, normals within 1e-4 radians, object ids exact.
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include "hmblur/buffer.h"
#include "kernels/debug/pack_layer.h"
#include "kernels/manifest.h"
#include "kernels/shared/layer_layout.h"
#include "runtime/vulkan/compute_kernel.h"
#include "runtime/vulkan/frame_recorder.h"
#include "tests/support/vulkan_test.h"

namespace hmb::test {
namespace {

using gpu::LayerPixel;

constexpr float kInf = std::numeric_limits<float>::infinity();
const float kNaN = std::numeric_limits<float>::quiet_NaN();

uint32_t bitsOf(float x) {
  uint32_t b;
  std::memcpy(&b, &x, sizeof(b));
  return b;
}

float withBits(uint32_t b) {
  float x;
  std::memcpy(&x, &b, sizeof(x));
  return x;
}

std::vector<LayerPixel> pixels() {
  std::vector<LayerPixel> out;
  auto add = [&](glm::vec3 color, float depth, glm::vec3 normal, glm::vec2 velocity, uint32_t id) {
    out.push_back({glm::vec4(color, depth), glm::vec4(normal, 0.0f), velocity, glm::vec2(0.0f), id, 0u, 0u, 0u});
  };
  // Adversarial colours, depths and velocities.
  const float colors[] = {0.0f,  -0.0f,  -1.0f,    withBits(1u), 1e-40f, 1e-30f, 6e-5f, 0.1f, 0.5f, 1.0f,
                          3.75f, 65504, 65505.0f, 1e30f,        kInf,   -kInf,  kNaN,  withBits(0x3f800200u),
                          withBits(0x3f8001ffu), withBits(0x3f800600u)};  // ties and near-ties of the rounding
  const glm::vec2 velocities[] = {{0.0f, 0.0f},      {-0.0f, 0.0f},     {1e-8f, -1e-8f},   {0.25f, -40.0f},
                                  {65504.0f, 1.0f},  {70000.0f, 7.0f},  {1e30f, -1e29f},   {kInf, 1.0f},
                                  {kNaN, 2.0f},      {-3.3f, 1e-5f},    {-65520.0f, 0.0f}, {1.0f / 3.0f, 2.0f / 3.0f}};
  const float depths[] = {0.0f, 1e-3f, 7.0f, 1e6f, 3e38f, kInf, kNaN, -1.0f};
  const glm::vec3 normals[] = {{0, 0, 1},    {0, 0, -1},         {1, 0, 0},      {0, -1, 0},       {0, 0, 0},
                               {kNaN, 0, 1}, {kInf, 0, 0},       {1e-38f, 0, 0}, {0.6f, 0.0f, -0.8f},
                               {0.0f, 1e-7f, -1.0f}, {-0.577f, 0.577f, -0.577f}};
  uint32_t id = 0;
  for (const float c : colors)
    for (size_t k = 0; k < 4; ++k)
      add(glm::vec3(c, colors[(k * 7 + 3) % std::size(colors)], 0.5f), depths[k % std::size(depths)],
          normals[k % std::size(normals)], velocities[k % std::size(velocities)], id++);
  for (const glm::vec2 v : velocities) add(glm::vec3(0.25f), 2.0f, glm::vec3(0, 0, 1), v, 5u);
  for (const float d : depths) add(glm::vec3(0.25f), d, glm::vec3(0, 0, 1), glm::vec2(1.0f), 5u);
  for (const glm::vec3 n : normals) add(glm::vec3(0.25f), 2.0f, n, glm::vec2(1.0f), 0xFFFFFFFFu);
  add(glm::vec3(0.25f), 2.0f, glm::vec3(0, 1, 0), glm::vec2(1.0f), 0u);  // the background: no normal
  // Random ones, over many magnitudes.
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f), exponent(-12.0f, 6.0f);
  for (int i = 0; i < 4000; ++i) {
    const glm::vec3 color(std::exp2(exponent(rng)), std::exp2(exponent(rng)), std::abs(unit(rng)));
    const glm::vec3 normal = glm::normalize(glm::vec3(unit(rng), unit(rng), unit(rng)) + glm::vec3(0.0f, 0.0f, 1e-3f));
    const glm::vec2 velocity(unit(rng) * std::exp2(exponent(rng) + 4.0f), unit(rng) * 50.0f);
    add(color, std::exp2(exponent(rng) * 2.0f), normal, velocity, uint32_t(rng()));
  }
  return out;
}

class LayerPackingTest : public VulkanTest {};

TEST_F(LayerPackingTest, DeviceAndHostPackAndUnpackTheSameBits) {
  const std::vector<LayerPixel> in = pixels();
  const auto count = uint32_t(in.size());
  const vk::Buffer inputs = vk::uploadedBuffer(context(), in, "test pixels");
  const vk::Buffer samples(context(), count * sizeof(glm::uvec4), vk::MemoryUse::Device, "test samples");
  const vk::Buffer surfaces(context(), count * sizeof(glm::uvec4), vk::MemoryUse::Device, "test surfaces");
  const vk::Buffer decoded(context(), count * sizeof(LayerPixel), vk::MemoryUse::Device, "test decoded");
  const vk::ComputeKernel kernel(context(), kernels::kernel("debug/pack_layer"));
  vk::FrameRecorder frame(context());
  frame.begin();
  frame.dispatch("pack-layer", kernel,
                 {{HMB_PACK_LAYER_BINDING_INPUTS, &inputs},
                  {HMB_PACK_LAYER_BINDING_SAMPLES, &samples},
                  {HMB_PACK_LAYER_BINDING_SURFACES, &surfaces},
                  {HMB_PACK_LAYER_BINDING_DECODED, &decoded}},
                 gpu::PackLayerParams{count, 0, 0, 0}, vk::foldedGroups(vk::groupsFor(count, HMB_PACK_LAYER_GROUP)));
  frame.submitAndWait();
  const std::vector<glm::uvec4> deviceSamples = samples.download<glm::uvec4>();
  const std::vector<glm::uvec4> deviceSurfaces = surfaces.download<glm::uvec4>();
  const std::vector<LayerPixel> deviceDecoded = decoded.download<LayerPixel>();

  size_t mismatches = 0;
  for (uint32_t i = 0; i < count; ++i) {
    const LayerPixel& p = in[i];
    const glm::vec3 color(p.colorDepth);
    const glm::uvec4 sample = gpu::packLayerSample(color, p.colorDepth.w, p.velocity);
    const glm::uvec4 surface = gpu::packLayerSurface(glm::vec3(p.normal), p.objectId, p.colorDepth.w, p.velocity);
    const LayerPixel& d = deviceDecoded[i];
    const glm::vec3 hostNormal = gpu::surfaceNormal(surface);
    // The octahedral word may differ by one step in either half: GLSL lets a division round to
    // 2.5 ULP (the normal divided by its L1 norm), so a value next to a step's midpoint may
    // round to either side. Every other word is the same bits.
    const auto step = [](uint32_t a, uint32_t b, uint32_t shift) {
      return std::abs(int(int16_t((a >> shift) & 0xFFFFu)) - int(int16_t((b >> shift) & 0xFFFFu))) <= 1;
    };
    const glm::uvec4 got = deviceSurfaces[i];
    bool same = deviceSamples[i] == sample && got.y == surface.y && got.z == surface.z && got.w == surface.w &&
                step(got.x, surface.x, 0) && step(got.x, surface.x, 16);
    // The device's words decoded on the host as on the device; normalize() may round its last
    // bit differently: within 2e-7 per component.
    const glm::vec3 hostDecodedColor = gpu::sampleColor(deviceSamples[i]);
    const glm::vec3 hostDecodedNormal = gpu::surfaceNormal(got);
    for (int c = 0; c < 3; ++c) same = same && bitsOf(d.colorDepth[c]) == bitsOf(hostDecodedColor[c]);
    same = same && bitsOf(d.colorDepth.w) == bitsOf(gpu::sampleDepth(deviceSamples[i]));
    same = same && d.sampleVelocity == gpu::sampleVelocity(deviceSamples[i]);
    same = same && bitsOf(d.velocity.x) == bitsOf(gpu::surfaceVelocity(got).x) &&
           bitsOf(d.velocity.y) == bitsOf(gpu::surfaceVelocity(got).y) && d.objectId == gpu::surfaceObjectId(got);
    same = same && bitsOf(d.surfaceDepth) == bitsOf(gpu::surfaceDepth(got));
    for (int c = 0; c < 3; ++c) same = same && std::abs(d.normal[c] - hostDecodedNormal[c]) <= 2e-7f;
    if (!same && mismatches++ < 8)
      ADD_FAILURE() << "pixel " << i << ": colour (" << color.x << ", " << color.y << ", " << color.z << ") depth "
                    << p.colorDepth.w << " velocity (" << p.velocity.x << ", " << p.velocity.y << ") normal ("
                    << p.normal.x << ", " << p.normal.y << ", " << p.normal.z << "): device sample " << std::hex
                    << deviceSamples[i].x << " " << deviceSamples[i].y << " " << deviceSamples[i].w << " surface "
                    << deviceSurfaces[i].x << ", host " << sample.x << " " << sample.y << " " << sample.w << " surface "
                    << surface.x << std::dec;

    // What the packing promises, on the host's values (the same bits, checked above).
    const glm::vec3 c = gpu::sampleColor(sample);
    for (int k = 0; k < 3; ++k) {
      const float x = color[k];
      const float expected = std::isnan(x) || !(x >= 1.17549435e-38f) ? 0.0f : std::min(x, HMB_LAYER_MAX_COLOR);
      EXPECT_LE(std::abs(c[k] - expected), expected * std::exp2(-14.0f)) << "pixel " << i << " channel " << k;
    }
    EXPECT_EQ(bitsOf(gpu::sampleDepth(sample)), bitsOf(p.colorDepth.w)) << "pixel " << i;
    EXPECT_EQ(bitsOf(gpu::surfaceDepth(surface)), bitsOf(p.colorDepth.w)) << "pixel " << i << ": both records keep the depth";
    EXPECT_EQ(gpu::surfaceObjectId(surface), p.objectId) << "pixel " << i;
    const glm::vec2 v = gpu::sampleVelocity(sample);
    EXPECT_TRUE(std::isfinite(v.x) && std::isfinite(v.y)) << "pixel " << i;
    // The surface's velocity is the sample's, bit for bit: the gathers' samples and the mask's
    // walks take the same velocity.
    EXPECT_EQ(gpu::surfaceVelocity(surface), v) << "pixel " << i;
    EXPECT_EQ(surface.z, sample.w) << "pixel " << i;
    const glm::vec2 q = p.velocity;
    if (std::isfinite(q.x) && std::isfinite(q.y) && std::max(std::abs(q.x), std::abs(q.y)) <= 65504.0f) {
      for (int k = 0; k < 2; ++k)  // half: 11 significant bits, or the subnormal step 2^-24
        EXPECT_LE(std::abs(v[k] - q[k]), std::max(std::abs(q[k]) * std::exp2(-11.0f), std::exp2(-24.0f)))
            << "pixel " << i;
    } else if (std::isfinite(q.x) && std::isfinite(q.y)) {
      EXPECT_NEAR(std::atan2(v.y, v.x), std::atan2(q.y, q.x), 1e-3) << "pixel " << i << ": a long velocity keeps its direction";
    } else {
      EXPECT_EQ(v, glm::vec2(0.0f)) << "pixel " << i << ": a non-finite velocity is none";
    }
    const glm::dvec3 n = glm::dvec3(glm::vec3(p.normal));
    const double l1 = std::abs(n.x) + std::abs(n.y) + std::abs(n.z);
    if (p.objectId == 0u) {
      EXPECT_EQ(hostNormal, glm::vec3(0.0f)) << "pixel " << i << ": the background has no normal";
    } else if (std::isfinite(l1) && l1 >= 1.17549435e-38) {
      const double cosine = glm::dot(glm::normalize(glm::dvec3(hostNormal)), n / glm::length(n));
      EXPECT_LE(std::acos(std::min(cosine, 1.0)), 1e-4) << "pixel " << i;
    } else {
      EXPECT_EQ(hostNormal, glm::vec3(0.0f, 0.0f, 1.0f)) << "pixel " << i << ": a zero or non-finite normal is +z";
    }
  }
  EXPECT_EQ(mismatches, 0u) << "of " << count << " pixels";
}

}  // namespace
}  // namespace hmb::test
