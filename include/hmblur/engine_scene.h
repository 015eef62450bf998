// An engine's geometry for the hybrid's rays, as an engine keeps it: meshes given once, then per
// frame each instance's world transform now and one frame earlier, and the camera's. It builds
// the scene::Scene that EngineHybridMotionBlur traces (its nodes carrying two keys a frame, at
// t - 1/fps and t), so an engine need not describe animation.
#pragma once

#include <cstdint>
#include <span>
#include <string>

#include <glm/glm.hpp>

#include "hmblur/scene.h"

namespace hmb {

class EngineScene {
 public:
  // fps: the engine's frame rate (the previous frame is 1 / fps earlier); exposure: how long the
  // shutter is open, in seconds; softZExtent: SOFT_Z_EXTENT in the engine's units.
  EngineScene(float fps, float exposure, float softZExtent);

  // A mesh in its own space (normals per vertex, three indices a triangle), drawn in `color`
  // by the library's shading (an engine with its own shadeHit can ignore it). Returns its index.
  uint32_t addMesh(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals,
                   std::span<const uint32_t> indices, glm::vec3 color = glm::vec3(1.0f), bool doubleSided = false);

  struct Instance {
    uint32_t mesh = 0;
    uint32_t objectId = 1;  // the G-buffer's id of this object; 0 is the background
    glm::mat4 worldNow{1.0f};
    glm::mat4 worldPrevious{1.0f};  // one frame (1 / fps) earlier
  };
  // The camera looks down its own -Z with +Y up (glTF); yfov in radians.
  struct Camera {
    glm::mat4 worldNow{1.0f};
    glm::mat4 worldPrevious{1.0f};
    float yfov = 0.8f;
    float znear = 0.1f;
    float zfar = 1000.0f;
  };
  // The frame at time t (seconds, the engine's clock): every instance, and the camera. World
  // transforms are translations, rotations and scales (no shear: hmb::Error names the
  // instance); a mesh index past addMesh's is an error too.
  void setFrame(float t, std::span<const Instance> instances, const Camera& camera);

  // The light the library's shading uses (an engine with its own shadeHit can ignore it).
  void setLight(const scene::DirectionalLight& light) { scene_.light = light; }
  // The engine's sky: what the hybrid's rays that hit nothing see (linear colour, black unless
  // set), where the engine's own G-buffer shows its sky.
  void setBackground(glm::vec3 linear) { scene_.background = linear; }

  const scene::Scene& scene() const { return scene_; }

 private:
  scene::Scene scene_;
};

}  // namespace hmb
