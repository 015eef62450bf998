// Runs the compute rasterizer in tests: on raw clip-space triangles (RasterizePass alone), or
// on a scene through the whole G-buffer stage, and reads everything back.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "hmblur/scene.h"
#include "kernels/raster/raster_layout.h"
#include "kernels/shared/scene_layout.h"
#include "runtime/passes/rasterize_pass.h"
#include "tests/oracle/graphics_raster.h"
#include "tests/support/layer_readback.h"

namespace hmb::vk {
class Context;
}

namespace hmb::test {

// A visibility buffer read back: entry i = (triangle id, depth key: raster_layout.h), HMB_VIS_EMPTY when empty.
struct Visibility {
  uint32_t width = 0, height = 0;
  std::vector<glm::uvec2> entries;
  passes::RasterStats stats;
  std::vector<gpu::SetupTriangle> setup;  // the setup kernel's output, stats.setupTriangles of them
  std::vector<glm::uvec2> pairs;          // (setup index, tile index), stats.tilePairs of them

  uint32_t idAt(uint32_t x, uint32_t y) const { return entries[size_t(y) * width + x].x; }
  float depthAt(uint32_t x, uint32_t y) const;
};

// Clip-space triangles, one vec4 per vertex, with each triangle's double-sided flag.
struct ClipTriangles {
  std::vector<glm::vec4> clip;             // vertex positions
  std::vector<gpu::GpuTriangle> triangles;  // v0, v1, v2 index clip; instance indexes doubleSided
  std::vector<bool> doubleSided;            // per instance

  void add(glm::vec4 a, glm::vec4 b, glm::vec4 c, bool isDoubleSided = true);
};

Visibility rasterizeClipTriangles(const vk::Context& context, const ClipTriangles& input, uint32_t width,
                                  uint32_t height, passes::VisibilityScheme scheme);

// The same triangles for the graphics-pipeline oracle, in id order (equal depths: smallest id
// wins, as in the visibility buffer).
std::vector<oracle::OracleTriangle> oracleTriangles(const ClipTriangles& input);

// A scene through transform -> rasterize -> resolve at its frame time.
struct GBufferReadback : LayerReadback {  // the G-buffer's layer
  ClipTriangles clipTriangles;  // the transform kernel's output with the scene's triangles
  Visibility visibility;
  std::vector<glm::uvec2> shutterPaths;  // per pixel, when asked for (kernels/gbuffer/gbuffer_layout.h)
};

GBufferReadback renderGBuffer(const vk::Context& context, const scene::Scene& scene, float frameTime, uint32_t width,
                              uint32_t height, passes::VisibilityScheme scheme, bool shutterPaths = false);

// Fraction of pixels where the compute visibility and the oracle see the same triangle (or both none).
double idAgreement(const Visibility& visibility, const oracle::OracleImage& oracle);

}  // namespace hmb::test
