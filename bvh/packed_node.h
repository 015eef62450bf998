// Packed BVH nodes on the host: the twin of kernels/bvh/packed_node.glsl (frames, outward
// rounding of bounds to 16-bit step counts, unpacking), for downloads and tests. Floats round
// as on the device: each product and sum on its own (this file is built without contraction).
#pragma once

#include <cstdint>

#include "bvh/bvh.h"
#include "hmblur/aabb.h"

namespace hmb::bvh {

// The bound `steps` steps from `origin`.
float boundAt(uint32_t steps, float origin, float step);
// The frame of a tree whose root box is `root` (origin 0, step 1 when it is empty).
gpu::BvhFrame frameOf(const Aabb& root);
// The most steps whose bound is at or below x, and the fewest whose bound is at or above x.
uint32_t stepsBelow(float x, float origin, float step);
uint32_t stepsAbove(float x, float origin, float step);
// A node packed in `frame`: its box rounded outwards, leftOrFirst and count in one word.
gpu::BvhPackedNode packNode(const Node& node, const gpu::BvhFrame& frame);
// A packed node with the bounds it stands for.
Node unpackNode(const gpu::BvhPackedNode& node, const gpu::BvhFrame& frame);

}  // namespace hmb::bvh
