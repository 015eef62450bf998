// The camera of a frame, as the library computes it from a scene: what an engine's own
// G-buffer must match for the library's rays to meet it.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

#include "hmblur/scene.h"

namespace hmb {

// The camera of one frame on the host: what the kernels get, and what tests need to check them.
struct FrameCamera {
  glm::mat4 view{1.0f};
  glm::mat4 projection{1.0f};  // Vulkan clip space: y down, depth z/w in [0, 1], reversed (1 at znear)
  glm::mat4 viewProjCurrent{1.0f};
  glm::mat4 viewProjPrevious{1.0f};
  glm::vec3 eye{0.0f};
  float znear = 0.1f;  // camera-space distances of the clip planes
  float zfar = 100.0f;
};

// The camera at frame time t for an image of the given size; the previous frame is t - 1/fps.
FrameCamera frameCamera(const scene::Scene& scene, float t, uint32_t width, uint32_t height);

}  // namespace hmb
