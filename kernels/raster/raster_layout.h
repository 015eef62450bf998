// Layouts of the rasterizer's kernels: transform -> setup (cull, snap, bin; list triangles
// that need clipping) -> clip -> bin large triangles -> rasterize tiles (visibility buffer)
// -> gbuffer/resolve.
#ifndef HMB_KERNELS_RASTER_RASTER_LAYOUT_H
#define HMB_KERNELS_RASTER_RASTER_LAYOUT_H

#include "../shared/glsl_cpp.h"

#define HMB_RASTER_GROUP 64
// Screen tiles of the binner, in pixels: one (triangle, tile) pair is one invocation's work.
#define HMB_RASTER_TILE 8
// Sub-pixel precision: vertices snap to 1/256 pixel, so shared edges evaluate identically.
#define HMB_RASTER_SUBPIXEL 256.0
// A triangle touching more tiles than this hands its (triangle, tile) pairs to
// bin_large_triangles, where a whole workgroup writes them, instead of writing them itself.
#define HMB_RASTER_LARGE_TILES 16u

// A visibility-buffer entry is uint64 (depth key << 32 | triangle id), read as uvec2
// (x = triangle id, y = depth key). Cleared to all ones: no triangle, the far plane.
#define HMB_VIS_EMPTY 0xffffffffu

// transform_vertices
#define HMB_TRANSFORM_BINDING_VERTICES 0
#define HMB_TRANSFORM_BINDING_INSTANCE_VERTICES 1
#define HMB_TRANSFORM_BINDING_INSTANCES 2
#define HMB_TRANSFORM_BINDING_CAMERA 3
#define HMB_TRANSFORM_BINDING_CLIP_CURRENT 4
#define HMB_TRANSFORM_BINDING_CLIP_PREVIOUS 5
#define HMB_TRANSFORM_BINDING_SHADING 6  // GpuVertexShading per instance vertex
#define HMB_TRANSFORM_BINDING_PREVIOUS_VERTICES 7  // GpuVertex per mesh vertex at t - 1/fps (deforming scenes)
#define HMB_TRANSFORM_BINDING_COUNT 8
// Specialization constant: true for a scene with deforming meshes, whose previous positions
// are their own (GpuScene::previousVertices); false reads only the one vertex buffer.
#define HMB_SPEC_TRANSFORM_DEFORMED 0

// transform_shutter_path: clip positions at mid-shutter and shutter open (the curved path).
#define HMB_SHUTTER_PATH_BINDING_VERTICES 0
#define HMB_SHUTTER_PATH_BINDING_INSTANCE_VERTICES 1
#define HMB_SHUTTER_PATH_BINDING_SHUTTER_CLIP 2        // GpuShutterClip per instance
#define HMB_SHUTTER_PATH_BINDING_PREVIOUS_VERTICES 3   // as HMB_TRANSFORM_BINDING_PREVIOUS_VERTICES
#define HMB_SHUTTER_PATH_BINDING_CLIP_MID 4            // vec4 per instance vertex
#define HMB_SHUTTER_PATH_BINDING_CLIP_OPEN 5
#define HMB_SHUTTER_PATH_BINDING_COUNT 6
// Specialization constant: as HMB_SPEC_TRANSFORM_DEFORMED.
#define HMB_SPEC_SHUTTER_PATH_DEFORMED 0

HMB_GPU_BEGIN
struct ShutterPathParams {
  uint vertexCount;
  // A deformed vertex at mid-shutter and shutter open, in frames before t: its position moves
  // along the line from the frame's to the previous frame's (extrapolated past one frame).
  float midFrames;
  float openFrames;
  uint pad0;
};
HMB_GPU_END
HMB_CHECK_SIZE(ShutterPathParams, 16)

// setup_triangles
#define HMB_SETUP_BINDING_TRIANGLES 0
#define HMB_SETUP_BINDING_INSTANCES 1
#define HMB_SETUP_BINDING_CLIP_CURRENT 2
#define HMB_SETUP_BINDING_SETUP 3      // SetupTriangle[]
#define HMB_SETUP_BINDING_PAIRS 4      // uvec2 (setup index, tile index)[]
#define HMB_SETUP_BINDING_COUNTERS 5   // RasterCounters
#define HMB_SETUP_BINDING_LARGE 6      // uint setup index[] of triangles binned by bin_large_triangles
#define HMB_SETUP_BINDING_CLIP_LIST 7  // uint triangle[] that need clipping (clip_triangles has the same bindings)
#define HMB_SETUP_BINDING_COUNT 8

// size_dispatch
#define HMB_SIZE_DISPATCH_BINDING_COUNTERS 0
#define HMB_SIZE_DISPATCH_BINDING_COUNT 1

// bin_large_triangles
#define HMB_BIN_LARGE_BINDING_SETUP 0
#define HMB_BIN_LARGE_BINDING_PAIRS 1
#define HMB_BIN_LARGE_BINDING_COUNTERS 2
#define HMB_BIN_LARGE_BINDING_LARGE 3
#define HMB_BIN_LARGE_BINDING_COUNT 4

// rasterize_tiles
#define HMB_RASTERIZE_BINDING_SETUP 0
#define HMB_RASTERIZE_BINDING_PAIRS 1
#define HMB_RASTERIZE_BINDING_COUNTERS 2
#define HMB_RASTERIZE_BINDING_VISIBILITY 3
#define HMB_RASTERIZE_BINDING_COUNT 4

// link_tile_pairs (the tile-lists scheme): each pair's .y, its tile, becomes the next pair of
// that tile's list; heads[tile] is the list's first pair, HMB_TILE_LIST_END ends a list.
#define HMB_LINK_BINDING_PAIRS 0
#define HMB_LINK_BINDING_COUNTERS 1
#define HMB_LINK_BINDING_HEADS 2
#define HMB_LINK_BINDING_COUNT 3
#define HMB_TILE_LIST_END 0xffffffffu

// rasterize_tile_lists
#define HMB_TILE_LISTS_BINDING_SETUP 0
#define HMB_TILE_LISTS_BINDING_PAIRS 1
#define HMB_TILE_LISTS_BINDING_HEADS 2
#define HMB_TILE_LISTS_BINDING_VISIBILITY 3
#define HMB_TILE_LISTS_BINDING_COUNTERS 4  // RasterCounters: overflow
#define HMB_TILE_LISTS_BINDING_COUNT 5

HMB_GPU_BEGIN

// Depth is reversed (runtime/device_scene/gpu_scene.cpp): z/w is 1 at the near plane and falls towards 0
// at the far one, so float's fine steps near 0 fall where perspective needs them and a
// near/far ratio of 1e9 still separates surfaces a part in 1e6 apart. The key of a depth in
// [0, 1] is its bits inverted: nearer surfaces have smaller keys, so atomicMin keeps the
// nearest, and the far plane (0 and -0 alike) keys as all ones, the empty entry.
HMB_SHARED uint depthKey(float depth) { return depth > 0.0f ? ~floatBitsToUint(depth) : 0xffffffffu; }
HMB_SHARED float depthOfKey(uint key) { return uintBitsToFloat(~key); }

struct RasterParams {
  uint width;
  uint height;
  uint triangleCount;      // setup: triangles in; rasterize: unused
  uint setupCapacity;      // SetupTriangle slots (and large-triangle list slots)
  uint pairCapacity;       // (triangle, tile) pair slots
  uint tilesX;
  uint pass;               // size_dispatch: 0 sizes clip_triangles, 1 the passes after it;
                           // rasterize_depth32: 0 writes depth, 1 writes ids where depth matches
  uint clipCapacity;       // clip-list slots
};

// A triangle ready to rasterize: snapped screen positions (pixels, y down) ordered so that
// the inside has positive edge functions, depth z/w per vertex, and its pixel bounds.
struct SetupTriangle {
  vec2 p0;
  vec2 p1;
  vec2 p2;
  uint triangle;      // id of the scene triangle it came from (near clipping may split one)
  uint firstPair;     // index of its first (triangle, tile) pair; its tiles follow row by row
  vec4 depth;         // xyz: z/w at p0, p1, p2 (reversed: 1 at the near plane)
  uvec4 pixelBounds;  // inclusive pixel rectangle: x0, y0, x1, y1
};

// Atomic counters of one frame and the indirect dispatches sized from them. setupCount and
// pairCount keep counting past their capacities, so after an overflow the host knows the size
// that fits.
struct RasterCounters {
  uint setupCount;
  uint pairCount;
  uint largeCount;
  uint overflow;     // HMB_RASTER_OVERFLOW_* bits: the host grows the buffers and renders again
  uint rasterizeX;   // indirect dispatch of rasterize_tiles (VkDispatchIndirectCommand)
  uint rasterizeY;
  uint rasterizeZ;
  uint clipCount;    // triangles listed for clip_triangles
  uint binLargeX;    // indirect dispatch of bin_large_triangles: one workgroup per triangle
  uint binLargeY;
  uint binLargeZ;
  uint pad0;
  uint clipX;        // indirect dispatch of clip_triangles: one invocation per listed triangle
  uint clipY;
  uint clipZ;
  uint pad1;
};

HMB_GPU_END

HMB_CHECK_SIZE(RasterParams, 32)
HMB_CHECK_SIZE(SetupTriangle, 64)
HMB_CHECK_SIZE(RasterCounters, 64)

#define HMB_RASTER_OVERFLOW_SETUP 1u          // more set-up triangles than setupCapacity
#define HMB_RASTER_OVERFLOW_PAIRS 2u          // more (triangle, tile) pairs than pairCapacity
#define HMB_RASTER_OVERFLOW_PAIRS_WRAPPED 4u  // the pair count passed 2^32
#define HMB_RASTER_OVERFLOW_CLIP 8u           // more triangles to clip than clipCapacity
// A tile's list was left unfinished: llvmpipe (Mesa 22.3; not Mesa 25's) ends an invocation's
// loops after 65535 iterations in all, silently, and rasterize_tile_lists walks a tile's list in
// one loop.
#define HMB_RASTER_OVERFLOW_TILE_LIST 16u

// Byte offsets of the indirect dispatches inside RasterCounters.
#define HMB_RASTER_COUNTERS_RASTERIZE_OFFSET 16
#define HMB_RASTER_COUNTERS_BIN_LARGE_OFFSET 32
#define HMB_RASTER_COUNTERS_CLIP_OFFSET 48

#endif
