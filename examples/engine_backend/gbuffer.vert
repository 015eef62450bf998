#version 450
// The example engine's G-buffer pass: each vertex now and one frame (1 / fps) earlier.
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;

struct ObjectData {
  mat4 clipNow;       // view-projection x model, now
  mat4 clipPrevious;  // the same one frame earlier
  mat4 model;
  vec4 albedo;  // w: the object's id
};
layout(std430, binding = 0) readonly buffer Objects { ObjectData objects[]; };

layout(location = 0) out vec3 worldNormal;
layout(location = 1) out vec4 previousClip;
layout(location = 2) flat out vec3 albedo;
layout(location = 3) flat out uint object;

void main() {
  const ObjectData o = objects[gl_InstanceIndex];  // each draw's first instance is its object
  gl_Position = o.clipNow * vec4(position, 1.0);
  previousClip = o.clipPrevious * vec4(position, 1.0);
  worldNormal = mat3(o.model) * normal;
  albedo = o.albedo.rgb;
  object = uint(o.albedo.w);
}
