#version 450
// Neighbour-max (McGuire et al. 2012, the tile-dilate second step): for each tile, the tile-max
// of largest speed in the n x n tiles around it, the neighbourhood clipped at the grid border.
// Ties go to the tile first in row-major order.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "mblur_layout.h"

layout(local_size_x = HMB_NEIGHBOR_MAX_GROUP_X, local_size_y = HMB_NEIGHBOR_MAX_GROUP_Y) in;

layout(std430, binding = HMB_NEIGHBOR_MAX_BINDING_TILE_MAX) readonly buffer TileMax { vec4 tileMax[]; };
layout(std430, binding = HMB_NEIGHBOR_MAX_BINDING_NEIGHBOR_MAX) writeonly buffer NeighborMax { vec4 neighborMax[]; };
layout(push_constant) uniform Params { NeighborMaxParams params; };

void main() {
  const uvec2 tile = gl_GlobalInvocationID.xy;
  if (tile.x >= params.tilesX || tile.y >= params.tilesY) return;
  const int radius = int(params.neighborhood / 2u);
  const ivec2 first = max(ivec2(tile) - radius, ivec2(0));
  const ivec2 last = min(ivec2(tile) + radius, ivec2(params.tilesX, params.tilesY) - 1);

  vec4 best = vec4(0.0, 0.0, -1.0, 0.0);
  for (int y = first.y; y <= last.y; ++y) {
    for (int x = first.x; x <= last.x; ++x) {
      const vec4 candidate = tileMax[uint(y) * params.tilesX + uint(x)];
      if (candidate.z > best.z) best = candidate;  // strict: the earlier tile keeps a tie
    }
  }
  neighborMax[tile.y * params.tilesX + tile.x] = best;
}
