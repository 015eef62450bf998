// The consumer's sky, for the library's rays that hit nothing: one colour, as its own clear.
#include "hmblur/hit_shading.glsl"

vec3 shadeMiss(vec3 direction) { return vec3(0.25, 0.5, 1.0); }
