#include "runtime/metrics/screen_paths.h"

#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <unordered_map>

#include <glm/glm.hpp>

#include "hmblur/error.h"
#include "runtime/device_scene/gpu_scene.h"
#include "runtime/device_scene/trace_scene.h"

namespace hmb {
namespace {

// Where a world point (w = 1) or direction (w = 0) lands in pixels; nullopt behind the camera.
std::optional<glm::vec2> pixelOf(const FrameCamera& camera, glm::vec4 world, uint32_t width, uint32_t height) {
  const glm::vec4 clip = camera.viewProjCurrent * world;
  if (!(clip.w > 0.0f)) return std::nullopt;
  const glm::vec2 ndc = glm::vec2(clip) / clip.w;
  return glm::vec2((ndc.x + 1.0f) * 0.5f * float(width), (ndc.y + 1.0f) * 0.5f * float(height));
}

}  // namespace

ScreenPaths screenPaths(const scene::Scene& scene, float frameTime, uint32_t width, uint32_t height,
                        std::span<const float> depth, std::span<const uint32_t> objectId) {
  const size_t pixels = size_t(width) * height;
  if (depth.size() != pixels || objectId.size() != pixels)
    throw Error("screen paths: the depth and object id layers must hold " + std::to_string(pixels) + " pixels");
  const float exposure = scene.settings.exposure;
  const float times[3] = {frameTime - exposure, frameTime - 0.5f * exposure, frameTime};
  FrameCamera cameras[3];
  for (int k = 0; k < 3; ++k) cameras[k] = frameCamera(scene, times[k], width, height);
  // The rays the raster's pixels stand for (runtime/device_scene/trace_scene.h): a pixel's point lies at its
  // camera-space depth along forward + sx right + sy down.
  const gpu::PinholeCamera rays = pinholeCamera(scene, frameTime, width, height);
  // An object id names a node (every instance of it moves with that node).
  std::unordered_map<uint32_t, uint32_t> nodeOf;
  for (const scene::Instance& instance : scene.instances) nodeOf.emplace(instance.objectId, instance.node);
  struct Motion {
    glm::mat4 objectFromWorld;
    glm::mat4 world[3];
  };
  std::unordered_map<uint32_t, Motion> motions;
  for (const auto& [id, node] : nodeOf) {
    Motion m;
    for (int k = 0; k < 3; ++k) m.world[k] = scene.worldMatrixAt(node, times[k]);
    m.objectFromWorld = glm::inverse(m.world[2]);
    motions.emplace(id, m);
  }

  ScreenPaths paths;
  paths.width = width;
  paths.height = height;
  paths.cameraMoves = cameras[0].view != cameras[2].view || cameras[0].projection != cameras[2].projection;
  paths.length.assign(pixels, 0.0f);
  paths.bend.assign(pixels, 0.0f);
  constexpr float kBehind = std::numeric_limits<float>::infinity();
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      const size_t i = size_t(y) * width + x;
      const float sx = 2.0f * (float(x) + 0.5f) / float(width) - 1.0f;
      const float sy = 2.0f * (float(y) + 0.5f) / float(height) - 1.0f;
      const glm::vec3 direction = glm::vec3(rays.forward) + sx * glm::vec3(rays.right) + sy * glm::vec3(rays.down);
      const auto motion = motions.find(objectId[i]);
      std::optional<glm::vec2> at[3];
      if (objectId[i] == 0 || motion == motions.end() || !std::isfinite(depth[i])) {
        for (int k = 0; k < 3; ++k) at[k] = pixelOf(cameras[k], glm::vec4(direction, 0.0f), width, height);
      } else {
        const glm::vec4 point = motion->second.objectFromWorld * glm::vec4(glm::vec3(rays.eye) + depth[i] * direction, 1.0f);
        for (int k = 0; k < 3; ++k) at[k] = pixelOf(cameras[k], motion->second.world[k] * point, width, height);
      }
      if (!at[0] || !at[1] || !at[2]) {
        paths.length[i] = paths.bend[i] = kBehind;
        continue;
      }
      paths.length[i] = glm::distance(*at[0], *at[2]);
      paths.bend[i] = glm::distance(*at[1], 0.5f * (*at[0] + *at[2]));
    }
  return paths;
}

}  // namespace hmb
