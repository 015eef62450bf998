// Each pixel's visible surface followed over the shutter [t - E, t], on the host: the point the
// sharp frame shows at t, carried by its node's rigid motion and seen by the moving camera at
// shutter open, mid-shutter and close. Screen-space blur assumes the straight line from open to
// close (one velocity per pixel); `bend` says how far the mid-shutter point lies off that line,
// which rotation in the image plane or in depth, a dolly and perspective all make. Deformation
// (skins, morph targets) is not followed: a deforming mesh's point moves with its node.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "hmblur/scene.h"

namespace hmb {

struct ScreenPaths {
  uint32_t width = 0;
  uint32_t height = 0;
  // Pixels between the point's positions at shutter open and close. Background pixels (no
  // surface) follow their view direction, which only the camera's rotation moves. A point
  // behind the camera at some time has +infinity in both maps.
  std::vector<float> length;
  // Pixels between the mid-shutter position and the midpoint of the open-close line.
  std::vector<float> bend;
  bool cameraMoves = false;  // the camera's view differs between open and close
};

// depth: the sharp frame's camera-space depth per pixel (the G-buffer's "depth" layer);
// objectId: its object ids (0: background). Throws hmb::Error when the sizes do not match.
ScreenPaths screenPaths(const scene::Scene& scene, float frameTime, uint32_t width, uint32_t height,
                        std::span<const float> depth, std::span<const uint32_t> objectId);

}  // namespace hmb
