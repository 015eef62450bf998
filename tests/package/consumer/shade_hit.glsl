// The consumer's shading of what the library's rays hit, written against the installed
// include: its normal as a colour.
#include "hmblur/hit_shading.glsl"

vec3 shadeHit(HitRecord hit) { return hit.normal * 0.5 + 0.5; }
