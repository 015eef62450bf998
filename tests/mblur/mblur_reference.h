// Plain C++ of every motion blur kernel's math (kernels/mblur/), operation for operation, so the
// kernels can be compared with it on any input.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "hmblur/post_process_settings.h"
#include "kernels/mblur/mblur_hash.h"
#include "runtime/passes/gather_pass.h"

namespace hmb::test::mblur {

// One G-buffer layer, row 0 at the top.
struct Layer {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<glm::vec4> color;
  std::vector<glm::vec4> normalDepth;  // w: camera-space depth
  std::vector<glm::vec2> velocity;     // pixels per frame
  // Each pixel's path over the shutter as the G-buffer holds it (kernels/gbuffer/gbuffer_layout.h:
  // half floats of X - p(t - E/2) and X - p(t - E)); empty: none, the gathers go straight.
  std::vector<glm::uvec2> shutterPaths;
};

// A path record: X - p(t - E/2) and X - p(t - E) as half floats (non-finite ones as given).
glm::uvec2 packShutterPath(glm::vec2 fromMid, glm::vec2 fromOpen);

// The layer as the gathers read it: every pixel through the packed sample the device holds
// (kernels/shared/layer_layout.h): colour at 13 mantissa bits, alpha 1, velocity in half floats.
// The gathers' references read their input through it; the harness uploads the same packing.
Layer stored(const Layer& layer);
std::vector<glm::uvec4> packedSamples(const Layer& layer);
// Velocities as the packed surface holds them (half floats, non-finite ones none): what the
// hybrid's ray mask reads.
std::vector<glm::vec2> storedVelocity(const std::vector<glm::vec2>& velocity);
std::vector<glm::uvec4> packedSurfaces(const Layer& layer);
// The G-buffer's velocities (kernels/shared/layer_layout.h), which tile-max reads: the layer's
// own floats (non-finite ones none), in whole 16-byte records.
std::vector<glm::vec2> packedVelocities(const Layer& layer);

// mblur_common.glsl
glm::vec2 gatherVelocity(glm::vec2 q, float velocityScale, float maxSpeed, float& speed);
// Its speed alone, as the gathers weigh samples (mblur_common.glsl).
float gatherSpeed(glm::vec2 q, float velocityScale, float maxSpeed);
glm::vec4 sanitizeColor(glm::vec4 c);
float sanitizeDepth(float z);
// The jitter hash is the kernels' own (kernels/mblur/mblur_hash.h).
using gpu::mblurHash;
using gpu::nextHash;
using gpu::unitFromHash;
glm::ivec2 nearestPixel(glm::vec2 position, uint32_t width, uint32_t height);
float cone(float ds, float v);
// gather_samples.glsl's sample i of `samples` along v_N: u in (0, 1] for the adapted range, t in
// [-1, 1] for the centred one; none for the centred range's middle sample of an odd count
// (it lands on the pixel itself).
std::optional<float> gatherSampleParameter(uint32_t i, uint32_t samples, float jitter, bool adapted);
float cylinder(float v, float s);

// The paper's appendix, eqs. 6-9, before any boost.
struct AppendixWeights {
  float foreground = 0.0f;  // w_f
  float background = 0.0f;  // w_b
  float simultaneous = 0.0f;  // w_s
};
AppendixWeights appendixWeights(float targetDepth, float sampleDepth, float targetSpeed, float sampleSpeed, float ds,
                                float softZExtent);

// tile_max.comp: vec4 (velocity, speed, 0) per tile, ranking `velocity` as given (the
// G-buffer's velocities: floats).
std::vector<glm::vec4> tileMax(const std::vector<glm::vec2>& velocity, uint32_t width, uint32_t height,
                               uint32_t tileSize, float velocityScale);
// neighbor_max.comp
std::vector<glm::vec4> neighborMax(const std::vector<glm::vec4>& tileMax, passes::TileGrid grid,
                                   uint32_t neighborhood);
// gather_samples.glsl's curved path: a record's quadratic terms (false without a path), how
// nearly a sample's path passes x, and a pixel's own path (false where it keeps the straight
// line).
bool shutterPathTerms(glm::uvec2 record, glm::vec2& a, glm::vec2& c);
void inversePath(glm::vec2 a, glm::vec2 c, glm::vec2 change, float maxLength, glm::vec2& linear, glm::vec2& quadratic);
float pathReach(glm::ivec2 samplePixel, glm::uvec2 sampleRecord, glm::vec2 v, glm::vec2 x);
// The McGuire gather (kernels/mblur/gather_samples.glsl, the McGuire fields of settings, its
// curved path where settings ask for it and the layer has paths); mask:
// width * height or nullptr (the weights composite's boosts inside it, composite.comp).
std::vector<glm::vec4> gather(const Layer& layer, const std::vector<glm::vec4>& neighborMax,
                              const std::vector<uint32_t>* mask, const passes::PostProcessSettings& settings,
                              passes::MaskWeights maskWeights = {});
// gather_jimenez.comp
std::vector<glm::vec4> gatherJimenez(const Layer& layer, const std::vector<glm::vec4>& neighborMax,
                                     const passes::PostProcessSettings& settings);
// The whole stage: tile-max, neighbour-max and the selected gather.
std::vector<glm::vec4> postProcess(const Layer& layer, const std::vector<uint32_t>* mask,
                                   const passes::PostProcessSettings& settings);

}  // namespace hmb::test::mblur
