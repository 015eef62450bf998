// How ray hits are shaded in the passes that trace them (the hybrid's reveal, the reference's
// samples): with the library's shading function (kernels/shared/shading.glsl), or with a GLSL
// function a user supplies, compiled into those kernels when the program runs
// (vk::compileKernelGlsl). The user's function is
//   vec3 shadeHit(HitRecord hit)
// over the record kernels/trace/shade_hit.glsl defines (object id, instance, barycentrics,
// world position and normal, uv, material); it may call the library's own shadeSurface(material,
// uv, normal) and read the scene's buffers as those kernels bind them. The G-buffer's resolve
// keeps the library's shading: a user's shadeHit changes what rays reveal, not the raster.
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
  // A user's shadeHit; an empty text is the library's shading.
  explicit HitShading(std::string glsl) : glsl_(std::move(glsl)) {}

  bool custom() const { return !glsl_.empty(); }
  const std::string& glsl() const { return glsl_; }

  // A shading kernel's builds with the user's function (its plain build, and its address build
  // where the kernel has one), compiled once per kernel. Throws hmb::Error in one line, naming
  // the kernel and the compiler's first error, when the function does not compile.
  const vk::KernelBuilds& buildsFor(std::string_view kernelName) const;

 private:
  std::string glsl_;
  mutable std::mutex mutex_;
  mutable std::map<std::string, vk::KernelBuilds, std::less<>> builds_;
};

}  // namespace hmb::passes
