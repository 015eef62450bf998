#version 460
// The ray-query anchor's trace (bench/ray_query_anchor.h): the closest hit of each ray through
// the driver's own acceleration structure (VK_KHR_ray_query). Benchmark only: the renderer
// never uses a ray-tracing extension.
#extension GL_EXT_ray_query : require
#extension GL_GOOGLE_include_directive : require
#include "ray_query_layout.h"

layout(local_size_x = HMB_RAY_QUERY_GROUP) in;

struct AnchorRay {
  vec4 originTMin;
  vec4 directionTMax;
};
struct AnchorHit {
  float t;
  float u;
  float v;
  uint triangle;  // 0xffffffff: nothing hit
};

layout(set = 0, binding = HMB_RAY_QUERY_BINDING_SCENE) uniform accelerationStructureEXT scene;
layout(std430, set = 0, binding = HMB_RAY_QUERY_BINDING_RAYS) readonly buffer Rays { AnchorRay rays[]; };
layout(std430, set = 0, binding = HMB_RAY_QUERY_BINDING_HITS) writeonly buffer Hits { AnchorHit hits[]; };
layout(push_constant) uniform Params { uint rayCount; } params;

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= params.rayCount) return;
  const AnchorRay ray = rays[i];
  rayQueryEXT query;
  rayQueryInitializeEXT(query, scene, gl_RayFlagsOpaqueEXT, 0xff, ray.originTMin.xyz, ray.originTMin.w,
                        ray.directionTMax.xyz, ray.directionTMax.w);
  while (rayQueryProceedEXT(query)) {
  }
  AnchorHit hit = AnchorHit(ray.directionTMax.w, 0.0, 0.0, 0xffffffffu);
  if (rayQueryGetIntersectionTypeEXT(query, true) == gl_RayQueryCommittedIntersectionTriangleEXT) {
    const vec2 uv = rayQueryGetIntersectionBarycentricsEXT(query, true);
    hit = AnchorHit(rayQueryGetIntersectionTEXT(query, true), uv.x, uv.y,
                    uint(rayQueryGetIntersectionPrimitiveIndexEXT(query, true)));
  }
  hits[i] = hit;
}
