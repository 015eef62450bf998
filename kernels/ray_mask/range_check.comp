#version 450
// Ray mask, second pass (paper, section 3.2.1, range check): a moving pixel enters the ray
// mask when its range X + u v, u in [0, 1] (along curved paths its own curve, X + u v + u^2 q),
// meets the edge mask: it is then in the inner blur
// of a silhouette, where the raster holds no background. The range is walked at most a pixel
// a step (ceil |v| + 1 positions on a straight one), so an edge band of any width is found.
// Masked pixels are appended to a list (compaction) whose front sizes the ray reveal's
// indirect dispatch; with the coverage composite (HMB_RANGE_CHECK_LIST_UNCOVERED) they are
// marked HMB_MASK_UNREVEALED instead, for list_range_mask to list them for mask_coverage, which
// splits them between the reveal and the composite alone. Runs over the blocks list_range_blocks listed (those of the
// moving tiles with an edge within reach); the mask is 0 elsewhere.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "ray_mask_layout.h"
#include "../mblur/mblur_layout.h"
#include "../shared/layer_layout.h"

layout(local_size_x = HMB_MASK_TILE_GROUP_X, local_size_y = HMB_MASK_TILE_GROUP_Y) in;

// The G-buffer's surfaces (velocity; depth along curved paths): shared/layer_layout.h, read as a
// uniform texel buffer (shared/texel_records.glsl), as are the shutter paths below.
#include "../shared/texel_records.glsl"
layout(binding = HMB_RANGE_CHECK_BINDING_SURFACES) uniform utextureBuffer surfaceTexels;
uvec4 surfaceAt(uint index) { return recordAt(surfaceTexels, index); }
// The edge mask, then the coarse one (HMB_EDGE_BLOCKS_FIRST).
layout(std430, binding = HMB_RANGE_CHECK_BINDING_EDGES) readonly buffer Edges { uint edges[]; };
layout(std430, binding = HMB_RANGE_CHECK_BINDING_BLOCKS) readonly buffer Blocks { uint blockList[]; };
layout(std430, binding = HMB_RANGE_CHECK_BINDING_MASK) buffer Mask { uint mask[]; };  // rayMaskBits, set by atomicOr
layout(std430, binding = HMB_RANGE_CHECK_BINDING_COUNTERS) buffer Counters { RayMaskCounters counters; };
layout(std430, binding = HMB_RANGE_CHECK_BINDING_LIST) writeonly buffer List { uint list[]; };
// Each pixel's path over the shutter, read only along curved paths (gbuffer/gbuffer_layout.h).
layout(binding = HMB_RANGE_CHECK_BINDING_SHUTTER_PATHS) uniform utextureBuffer shutterPathTexels;
uvec2 shutterPathAt(uint index) { return halfRecordAt(shutterPathTexels, index); }
layout(push_constant) uniform Params { RayMaskParams params; };
layout(constant_id = HMB_SPEC_RANGE_CHECK_CURVED_PATH) const bool kCurvedPath = false;

#include "../mblur/mblur_common.glsl"
#include "ray_mask_common.glsl"
#include "own_curved_path.glsl"

// Where the segment a -> b (both inside the image) crosses flagged blocks of the coarse edge
// image: the segment's parameters, in [0, 1], where it enters the first and leaves the last
// (x < 0: none; with firstOnly the walk stops at the first, y unset). A grid walk over the blocks
// it crosses, ~|b - a| / 2 steps where the fine walk takes |b - a|. Every fine-walk pixel lies on
// the segment (up to rounding), and a block is flagged when an edge pixel lies within a pixel of
// it, so the fine walk meets no edge outside that span. Each move steps one block towards the
// last one, so `moves` moves end there; `entry`, the block's entry in the edge buffer, moves
// with it, and `entered` is the parameter where the walk entered the block it is in.
vec2 segmentEdgeBlockSpan(vec2 a, vec2 b, bool firstOnly) {
  const float side = float(HMB_EDGE_BLOCK);
  const uint blocksX = HMB_EDGE_BLOCKS_ACROSS(params.blur.width);
  ivec2 block = ivec2(floor(a / side));
  const ivec2 last = ivec2(floor(b / side));
  const vec2 d = b - a;
  const ivec2 stepSign = ivec2(sign(d));
  const vec2 inverse = vec2(d.x != 0.0 ? 1.0 / abs(d.x) : 0.0, d.y != 0.0 ? 1.0 / abs(d.y) : 0.0);
  // Segment parameter at the next block boundary on each axis, and between boundaries.
  const vec2 boundary = vec2(block + max(stepSign, ivec2(0))) * side;
  vec2 tNext = vec2(d.x != 0.0 ? abs(boundary.x - a.x) * inverse.x : 2.0, d.y != 0.0 ? abs(boundary.y - a.y) * inverse.y : 2.0);
  const vec2 tStep = side * inverse;
  const uint moves = uint(abs(last.x - block.x) + abs(last.y - block.y));
  uint entry = HMB_EDGE_BLOCK_ENTRY(params.blur.width, params.blur.height, uint(block.x), uint(block.y));
  const uint rowStep = uint(stepSign.y) * blocksX;  // modulo 2^32: one row up or down
  float entered = 0.0;
  vec2 span = vec2(-1.0);
  for (uint i = 0u; i < moves; ++i) {
    const bool flagged = edges[entry] != 0u;
    if (flagged && span.x < 0.0) {
      span.x = entered;
      if (firstOnly) return span;
    }
    const bool stepX = block.y == last.y || (block.x != last.x && tNext.x < tNext.y);
    if (stepX) {
      block.x += stepSign.x;
      entry += uint(stepSign.x);
      entered = tNext.x;
      tNext.x += tStep.x;
    } else {
      block.y += stepSign.y;
      entry += rowStep;
      entered = tNext.y;
      tNext.y += tStep.y;
    }
    if (flagged) span.y = entered;
  }
  if (edges[entry] != 0u) span = vec2(span.x < 0.0 ? entered : span.x, 1.0);
  return span;
}

bool insideImage(vec2 p) {
  return all(greaterThanEqual(p, vec2(0.0))) && p.x < float(params.blur.width) && p.y < float(params.blur.height);
}

// Whether the curved path X + s v + s^2 q, s in [0, 1], passes through a flagged block: its
// chords over k equal steps of s, each walked by segmentEdgeBlockSpan. A quadratic strays
// from its chord over a step h by at most |q| h^2 / 4, so k >= sqrt(|q| / 2) keeps every
// fine-walk position within half a pixel of a chord, inside the pixel of margin a block's
// flag has: "no" here still means the fine walk meets no edge.
bool curvedPathMeetsEdgeBlock(vec2 centre, vec2 v, vec2 q) {
  const uint chords = max(1u, uint(ceil(sqrt(0.5 * length(q)))));
  vec2 from = centre;
  for (uint j = 1u; j <= chords; ++j) {
    const float s = float(j) / float(chords);
    const vec2 to = centre + s * v + (s * s) * q;
    if (segmentEdgeBlockSpan(from, to, true).x >= 0.0) return true;
    from = to;
  }
  return false;
}

// The range check along a curved path X + s v + s^2 q, s in [0, 1], at most a pixel a step:
// the path's speed |v + 2 s q| is convex in s, so it peaks at an end, |v| or |v + 2q|.
bool curvedPathMeetsEdge(uvec2 pixel, vec2 v, vec2 q) {
  const vec2 centre = vec2(pixel) + 0.5;
  // The path lies in the triangle of its control points X, X + v / 2, X + v + q: when they are
  // inside the image no position is clamped, and the coarse blocks can answer "no" first.
  if (insideImage(centre + 0.5 * v) && insideImage(centre + v + q) && !curvedPathMeetsEdgeBlock(centre, v, q))
    return false;
  // <= 2 maxSpeed: inversePath keeps |v| + |q| within maxSpeed.
  const uint steps = uint(ceil(max(length(v), length(v + 2.0 * q))));
  for (uint i = 0u; i <= steps; ++i) {
    const float s = steps == 0u ? 0.0 : float(i) / float(steps);
    const ivec2 p = nearestPixel(centre + s * v + (s * s) * q, params.blur.width, params.blur.height);
    const uint at = uint(p.y) * params.blur.width + uint(p.x);
    if (edgeMaskBit(edges[at / 32u], at)) return true;
  }
  return false;
}

// The range check at one pixel moving by v (speed > 0).
bool meetsEdge(uvec2 pixel, vec2 v, float speed) {
  const uint steps = uint(ceil(speed));  // <= maxSpeed, the image's larger side
  const vec2 centre = vec2(pixel) + 0.5;
  // Ranges that leave the image are clamped pixel by pixel; those take the fine walk alone, the
  // others over the flagged blocks' span and a step beyond each end (a step is over half a
  // pixel, so a position two steps out lies a pixel or more outside the span: rounding cannot
  // carry it into an edge pixel). Fine walks over the whole range had taken a CPU device nearly
  // half of the check (bench/results/range-check-span/).
  uint first = 0u, last = steps;
  if (insideImage(centre + v)) {
    const vec2 span = segmentEdgeBlockSpan(centre, centre + v, false);
    if (!(span.x >= 0.0)) return false;
    first = uint(max(floor(span.x * float(steps)) - 1.0, 0.0));
    last = uint(min(ceil(span.y * float(steps)) + 1.0, float(steps)));
  }
  for (uint i = first; i <= last; ++i) {
    const ivec2 p = nearestPixel(centre + v * (float(i) / float(steps)), params.blur.width, params.blur.height);
    const uint at = uint(p.y) * params.blur.width + uint(p.x);
    if (edgeMaskBit(edges[at / 32u], at)) return true;
  }
  return false;
}

void checkPixel(uvec2 pixel) {
  const uint index = pixel.y * params.blur.width + pixel.x;
  const uvec4 surface = surfaceAt(index);
  float speed;
  vec2 v = gatherVelocity(surfaceVelocity(surface), params.blur.velocityScale, params.blur.maxSpeed, speed);
  // Along curved paths: the pixel's own, as the coverage composite samples it.
  vec2 q = vec2(0.0);
  const bool curved = kCurvedPath && (params.blur.flags & HMB_GATHER_FLAG_CURVED_PATH) != 0u && speed > 0.0 &&
                      ownCurvedPath(pixel, index, surface, sanitizeDepth(surfaceDepth(surface)), v, q);
  // The mask is filled with HMB_MASK_NONE before.
  if (!(speed > 0.0) || !(curved ? curvedPathMeetsEdge(pixel, v, q) : meetsEdge(pixel, v, speed))) return;
  if ((params.flags & HMB_RANGE_CHECK_LIST_UNCOVERED) != 0u) {
    atomicOr(mask[index / 16u], rayMaskBits(HMB_MASK_UNREVEALED, index));  // list_range_mask lists it
    return;
  }
  atomicOr(mask[index / 16u], rayMaskBits(HMB_MASK_REVEALED, index));
  list[atomicAdd(counters.maskCount, 1u)] = index;
}

// The listed blocks, a group each on a GPU; on a CPU device each group takes a run of the list
// (ray_mask_layout.h).
void main() {
  const uvec2 run = groupRun(counters.rangeBlockCount);
  for (uint entry = run.x; entry < run.y; ++entry) {
    const uint listed = blockList[entry];
    const uvec2 pixel = rangeBlockOrigin(listed) + gl_LocalInvocationID.xy;
    // Lanes past the tile's or the image's edge have no pixel.
    const bool inTile = all(lessThan(gl_LocalInvocationID.xy, rangeBlockSide(listed, params.blur.tileSize)));
    if (inTile && pixel.x < params.blur.width && pixel.y < params.blur.height) checkPixel(pixel);
  }
}
