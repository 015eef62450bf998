#version 450
// The image layer's packing on the device (shared/layer_layout.h): each input pixel packed into
// a sample and a surface, and the two decoded again, for the test that holds the device's
// rounding to the host's (tests/gbuffer/layer_packing_test.cpp).
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "pack_layer.h"
#include "../shared/indexing.glsl"
#include "../shared/layer_layout.h"

layout(local_size_x = HMB_PACK_LAYER_GROUP) in;

layout(std430, binding = HMB_PACK_LAYER_BINDING_INPUTS) readonly buffer Inputs { LayerPixel inputs[]; };
layout(std430, binding = HMB_PACK_LAYER_BINDING_SAMPLES) writeonly buffer Samples { uvec4 samples[]; };
layout(std430, binding = HMB_PACK_LAYER_BINDING_SURFACES) writeonly buffer Surfaces { uvec4 surfaces[]; };
layout(std430, binding = HMB_PACK_LAYER_BINDING_DECODED) writeonly buffer Decoded { LayerPixel decoded[]; };
layout(push_constant) uniform Params { PackLayerParams params; };

void main() {
  const uint i = linearInvocationIndex(HMB_PACK_LAYER_GROUP);
  if (i >= params.count) return;
  const LayerPixel p = inputs[i];
  const uvec4 s = packLayerSample(p.colorDepth.rgb, p.colorDepth.w, p.velocity);
  const uvec4 f = packLayerSurface(p.normal.xyz, p.objectId, p.colorDepth.w, p.velocity);
  samples[i] = s;
  surfaces[i] = f;
  LayerPixel d;
  d.colorDepth = vec4(sampleColor(s), sampleDepth(s));
  d.normal = vec4(surfaceNormal(f), 0.0);
  d.velocity = surfaceVelocity(f);
  d.objectId = surfaceObjectId(f);
  d.sampleVelocity = sampleVelocity(s);
  d.surfaceDepth = surfaceDepth(f);
  decoded[i] = d;
}
