// An image layer as a kernel binds it: HMB_LAYER(name, firstBinding, access) declares layer
// `name` from binding firstBinding on, with access writeonly, readonly or nothing. The plain
// build binds its two buffers (samples and surfaces: HMB_LAYER_BINDINGS slots); builds with
// HMB_BIND_BY_ADDRESS (devices with few storage-buffer bindings) bind one LayerTable of their
// addresses. Either way a kernel reads and writes LAYER_SAMPLE(name, i) and
// LAYER_SURFACE(name, i) (packed as shared/layer_layout.h says, decoded with its
// functions: sample*, surface*), and writes a whole pixel with WRITE_LAYER.
#ifndef HMB_KERNELS_SHARED_LAYER_BINDINGS_GLSL
#define HMB_KERNELS_SHARED_LAYER_BINDINGS_GLSL

#include "layer_layout.h"

#ifdef HMB_BIND_BY_ADDRESS
#define HMB_LAYER(name, firstBinding, access) \
  layout(std430, binding = firstBinding) readonly buffer name##Table { LayerTable name; };
#define LAYER_SAMPLE(name, i) name.samples.v[i]
#define LAYER_SURFACE(name, i) name.surfaces.v[i]
#else
#define HMB_LAYER(name, firstBinding, access)                                                              \
  layout(std430, binding = firstBinding + 0) access buffer name##Samples { uvec4 name##SampleArray[]; };   \
  layout(std430, binding = firstBinding + 1) access buffer name##Surfaces { uvec4 name##SurfaceArray[]; };
#define LAYER_SAMPLE(name, i) name##SampleArray[i]
#define LAYER_SURFACE(name, i) name##SurfaceArray[i]
#endif

// A layer the kernel only reads, at per-pixel addresses: HMB_LAYER_TEXELS(name, firstBinding)
// declares it, READ_LAYER_SAMPLE(name, i) and READ_LAYER_SURFACE(name, i) read it. In the plain
// build its two buffers are uniform texel buffers (one record a pixel each:
// texel_records.glsl); address builds read the table as HMB_LAYER does.
#ifdef HMB_BIND_BY_ADDRESS
#define HMB_LAYER_TEXELS(name, firstBinding) HMB_LAYER(name, firstBinding, readonly)
#define READ_LAYER_SAMPLE(name, i) LAYER_SAMPLE(name, i)
#define READ_LAYER_SURFACE(name, i) LAYER_SURFACE(name, i)
#else
#include "texel_records.glsl"
#define HMB_LAYER_TEXELS(name, firstBinding)                                    \
  layout(binding = firstBinding + 0) uniform utextureBuffer name##SampleTexels; \
  layout(binding = firstBinding + 1) uniform utextureBuffer name##SurfaceTexels;
#define READ_LAYER_SAMPLE(name, i) recordAt(name##SampleTexels, i)
#define READ_LAYER_SURFACE(name, i) recordAt(name##SurfaceTexels, i)
#endif

// Pixel i of the layer: two stores.
#define WRITE_LAYER(name, i, color, normal, objectId, depth, velocity)              \
  {                                                                                  \
    LAYER_SAMPLE(name, i) = packLayerSample(color, depth, velocity);                 \
    LAYER_SURFACE(name, i) = packLayerSurface(normal, objectId, depth, velocity);    \
  }

#endif
