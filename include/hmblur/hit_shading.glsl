// The GLSL side of hmb::passes::HitShading (hit_shading.h): what a user's shading functions are
// given. The library compiles a user's
//   vec3 shadeHit(HitRecord hit)    the colour of the surface a ray hit
//   vec3 shadeMiss(vec3 direction)  the colour a ray that hits nothing sees (world space, unit)
// into the kernels that shade rays (the hybrid's reveal and shutter rays, the reference's
// samples). Their text may include this file as "hmblur/hit_shading.glsl", and so may an
// engine's own shaders (`-I <prefix>/include`), to share a shading function with its fragment
// shader. Inside the library's kernels a user's function may also call
//   vec3 shadeSurface(uint material, vec2 uv, vec3 normal)  the library's shading of the scene's materials
//   vec3 sceneBackground()                                  the scene's background (Scene::background)
// A colour that is not finite is written as black.
#ifndef HMBLUR_HIT_SHADING_GLSL
#define HMBLUR_HIT_SHADING_GLSL

struct HitRecord {
  uint objectId;      // the hit instance's object id (the scene's; 0 is the background)
  uint instance;      // the hit instance
  vec2 barycentrics;  // (u, v): the weights of the hit triangle's second and third vertices
  vec3 position;      // world space
  vec3 normal;        // world space, unit, facing the ray's origin
  vec2 uv;            // texture coordinates (0 in scenes without textures)
  uint material;      // the instance's material
};

#endif
