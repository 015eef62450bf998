// How rays are shaded in the passes that trace them (the hybrid's reveal and shutter rays, the
// reference's samples): with the library's shading (kernels/shared/shading.glsl; the scene's
// background where a ray hits nothing), or with GLSL functions a user supplies, compiled into
// those kernels when the program runs (vk::compileKernelGlsl):
//   vec3 shadeHit(HitRecord hit)    over the record hmblur/hit_shading.glsl defines (object id,
//                                   instance, barycentrics, world position and normal, uv, material)
//   vec3 shadeMiss(vec3 direction)  a ray that hits nothing, its world-space unit direction
// Either may call the library's shadeSurface(material, uv, normal) and sceneBackground() and
// read the scene's buffers as those kernels bind them; their text may include
// "hmblur/hit_shading.glsl" (installed beside this header). The G-buffer's resolve keeps the
// library's shading and background: a user's functions change what rays see, not the raster.
#pragma once

#include <map>
#include <mutex>
#include <string>
#include <string_view>

#include "hmblur/kernel_builds.h"

namespace hmb::passes {

class HitShading {
 public:
  HitShading() = default;  // the library's shading
  // A user's shadeHit and shadeMiss; an empty text is the library's.
  explicit HitShading(std::string shadeHit, std::string shadeMiss = {})
      : shadeHit_(std::move(shadeHit)), shadeMiss_(std::move(shadeMiss)) {}

  bool custom() const { return !shadeHit_.empty() || !shadeMiss_.empty(); }
  const std::string& shadeHit() const { return shadeHit_; }
  const std::string& shadeMiss() const { return shadeMiss_; }

  // A shading kernel's builds with the user's function (its plain build, and its address build
  // where the kernel has one), compiled once per kernel. Throws hmb::Error in one line, naming
  // the kernel and the compiler's first error, when a function does not compile.
  const vk::KernelBuilds& buildsFor(std::string_view kernelName) const;

 private:
  std::string shadeHit_, shadeMiss_;
  mutable std::mutex mutex_;
  mutable std::map<std::string, vk::KernelBuilds, std::less<>> builds_;
};

}  // namespace hmb::passes
