#version 450
// Tile-max (McGuire et al. 2012, the paper's tile-dilate first step): for each m x m tile, the
// gather velocity of largest magnitude among its pixels, each pixel's velocity converted and
// clamped to m first (mblur_common.glsl), from the G-buffer's velocities as floats (ranking the
// layer's half floats made near-equal speeds tie or swap: bench/results/tile-max-ranking/).
// Tiles at the right and bottom borders are partial.
// Ties go to the pixel first in row-major image order, whatever order the lanes ran in.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "mblur_layout.h"
#include "../shared/layer_layout.h"

layout(local_size_x = HMB_TILE_MAX_GROUP_X, local_size_y = HMB_TILE_MAX_GROUP_Y) in;

// The G-buffer's velocities, read as a uniform texel buffer (shared/texel_records.glsl).
#include "../shared/texel_records.glsl"
layout(binding = HMB_TILE_MAX_BINDING_VELOCITIES) uniform utextureBuffer velocityTexels;
layout(std430, binding = HMB_TILE_MAX_BINDING_TILES) writeonly buffer Tiles { vec4 tiles[]; };
layout(push_constant) uniform Params { TileMaxParams params; };

#include "mblur_common.glsl"

// The velocities alone.
void visitTilePixel(uvec2 pixel, uint index, GatherVelocityParts velocity, float speed) {}

vec2 tileVelocityAt(uint index) { return uintBitsToFloat(halfRecordAt(velocityTexels, index)); }

#include "tile_max_reduction.glsl"

void main() {
  reduceTileMax(gl_WorkGroupID.xy, params.width, params.height, params.tileSize, params.tilesX, params.velocityScale,
                false);
}
