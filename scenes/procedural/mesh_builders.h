// Tessellated primitives with normals and uvs in [0, 1], and small procedural textures, for
// the reference scenes. Units are whatever the caller uses (the scenes use metres).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "hmblur/scene.h"

namespace hmb::scene::procedural {

// Axis-aligned box centred on the origin; each face has its own vertices (flat normals).
Mesh makeBox(const glm::vec3& halfExtent, uint32_t material);

// Rectangle in the XZ plane centred on the origin, facing +Y; size is (x, z).
Mesh makePlane(const glm::vec2& size, uint32_t material);

// Cylinder along +Y from y = 0 to y = height, optionally closed by flat caps.
Mesh makeCylinder(float radius, float height, uint32_t segments, uint32_t material, bool caps = true);

// Surface of revolution about +Y of a profile of (radius, y) points, bottom to top. Smooth
// normals across the profile; points with radius 0 close the surface without slivers.
Mesh makeLathe(const std::vector<glm::vec2>& profile, uint32_t segments, uint32_t material);

// Sphere centred on the origin.
Mesh makeSphere(float radius, uint32_t segments, uint32_t rings, uint32_t material);

// Torus about +Y: a circle of `tubeRadius` swept at `ringRadius` from the axis.
Mesh makeTorus(float ringRadius, float tubeRadius, uint32_t segments, uint32_t tubeSegments, uint32_t material);

// Appends `part` transformed by `transform` (normals by its inverse transpose) to `into`;
// the material of `into` is kept.
void appendMesh(Mesh& into, const Mesh& part, const glm::mat4& transform);

// Checkerboard of cellsX x cellsY cells, colours as sRGB bytes.
Texture makeCheckerTexture(std::string name, uint32_t width, uint32_t height, uint32_t cellsX, uint32_t cellsY,
                           const glm::u8vec3& colorA, const glm::u8vec3& colorB);

// Vertical stripes (along v), alternating two colours.
Texture makeStripeTexture(std::string name, uint32_t width, uint32_t height, uint32_t stripes,
                          const glm::u8vec3& colorA, const glm::u8vec3& colorB);

}  // namespace hmb::scene::procedural
