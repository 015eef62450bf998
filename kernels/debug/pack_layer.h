// Layout of debug/pack_layer.comp: the image layer's packing and unpacking
// (shared/layer_layout.h) run on the device, so a test can hold them to the host's, bit for bit.
#ifndef HMB_KERNELS_DEBUG_PACK_LAYER_H
#define HMB_KERNELS_DEBUG_PACK_LAYER_H

#include "../shared/glsl_cpp.h"

#define HMB_PACK_LAYER_GROUP 64

#define HMB_PACK_LAYER_BINDING_INPUTS 0    // LayerPixel per entry
#define HMB_PACK_LAYER_BINDING_SAMPLES 1   // uvec4 per entry, written: packLayerSample
#define HMB_PACK_LAYER_BINDING_SURFACES 2  // uvec4 per entry, written: packLayerSurface
#define HMB_PACK_LAYER_BINDING_DECODED 3   // LayerPixel per entry, written: the packed texels decoded
#define HMB_PACK_LAYER_BINDING_COUNT 4

HMB_GPU_BEGIN
// One pixel of a layer, unpacked.
struct LayerPixel {
  vec4 colorDepth;       // rgb, w camera-space depth
  vec4 normal;           // xyz; w unused
  vec2 velocity;         // pixels per frame (decoded: the surface's, half floats)
  vec2 sampleVelocity;   // decoded only: the sample's (half floats)
  uint objectId;
  float surfaceDepth;    // decoded only: the surface's
  uint pad1;
  uint pad2;
};

struct PackLayerParams {
  uint count;
  uint pad0;
  uint pad1;
  uint pad2;
};
HMB_GPU_END
HMB_CHECK_SIZE(LayerPixel, 64)
HMB_CHECK_SIZE(PackLayerParams, 16)

#endif
