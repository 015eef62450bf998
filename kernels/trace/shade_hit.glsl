// The surface a ray hit and its colour, for every kernel that shades ray hits (the reference,
// the ray reveal and the shutter rays): normal and uv interpolated from the mesh's vertices, the normal carried
// to world space with the instance's transform at the ray's time and turned to the viewer
// when a (double-sided) back face is seen, as the G-buffer resolve does, gathered in a
// HitRecord (include/hmblur/hit_shading.glsl, installed with the API), then shadeHit(HitRecord):
// the shading function every method shares, or a user's; and shadeMiss(direction) for a ray
// that hits nothing: the scene's background, or a user's (passes::HitShading compiles these
// kernels again with HMB_CUSTOM_SHADE_HIT / HMB_CUSTOM_SHADE_MISS and the user's functions as
// the includes "custom_shade_hit.glsl" / "custom_shade_miss.glsl"). Needs closest_hit.glsl and
// shared/shading.glsl included first and the scene's vertices, instances and camera
// (shared/scene_bindings.glsl).
#ifndef HMB_KERNELS_TRACE_SHADE_HIT_GLSL
#define HMB_KERNELS_TRACE_SHADE_HIT_GLSL

struct HitSurface {
  vec3 normal;  // world space, unit, facing the ray's origin
  vec2 uv;
};

// transformIndex: the hit instance's transform at the ray's time (instance * timeCount + time).
HitSurface hitSurface(BvhHit hit, vec3 direction, uint transformIndex) {
  const vec4 a = leafTriangle(3u * hit.entry), b3 = leafTriangle(3u * hit.entry + 1u),
             c = leafTriangle(3u * hit.entry + 2u);
  const uvec3 tri = floatBitsToUint(vec3(a.w, b3.w, c.w));
  const vec3 b = vec3(1.0 - hit.u - hit.v, hit.u, hit.v);
  const vec3 objectNormal = b.x * vertexNormal(tri.x) + b.y * vertexNormal(tri.y) + b.z * vertexNormal(tri.z);
  HitSurface s;
  s.uv = kTexturePath ? b.x * vertexUv(tri.x) + b.y * vertexUv(tri.y) + b.z * vertexUv(tri.z) : vec2(0.0);
  const mat3 objectFromWorld = mat3(objectFromWorldAt(transformIndex));
  const mat3 normalToWorld = transpose(objectFromWorld);
  vec3 n = normalToWorld * objectNormal;
  n = dot(n, n) > 0.0 && !any(isinf(n)) ? normalize(n) : vec3(0.0, 0.0, 1.0);
  // cross(M a, M b) = det(M) M^-T cross(a, b): the world counter-clockwise normal.
  const vec3 p0 = a.xyz, p1 = b3.xyz, p2 = c.xyz;
  const float handedness = determinant(objectFromWorld) < 0.0 ? -1.0 : 1.0;
  const vec3 geometric = handedness * (normalToWorld * cross(p1 - p0, p2 - p0));
  if (dot(geometric, direction) > 0.0) n = -n;
  s.normal = n;
  return s;
}

// What the shading of a ray hit is given; a user's shadeHit takes the same.
#include "../../include/hmblur/hit_shading.glsl"

vec3 sceneBackground() { return camera.background.rgb; }

#ifdef HMB_CUSTOM_SHADE_HIT
#include "custom_shade_hit.glsl"
#else
vec3 shadeHit(HitRecord hit) { return shadeSurface(hit.material, hit.uv, hit.normal); }
#endif

#ifdef HMB_CUSTOM_SHADE_MISS
#include "custom_shade_miss.glsl"
#else
vec3 shadeMiss(vec3 direction) { return sceneBackground(); }
#endif

// transformIndex: as hitSurface's.
HitRecord hitRecord(BvhHit hit, vec3 origin, vec3 direction, uint transformIndex) {
  const HitSurface s = hitSurface(hit, direction, transformIndex);
  HitRecord r;
  r.objectId = traceInstanceAt(hit.instance).objectId;
  r.instance = hit.instance;
  r.barycentrics = vec2(hit.u, hit.v);
  r.position = origin + hit.t * direction;
  r.normal = s.normal;
  r.uv = s.uv;
  r.material = instanceMaterial(hit.instance);
  return r;
}

#endif
