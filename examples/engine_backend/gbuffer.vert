#version 450
// The example engine's G-buffer pass: each vertex now and one frame (1 / fps) earlier.
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;

struct ObjectData {
  mat4 clipNow;       // view-projection x world, now
  mat4 clipPrevious;  // the same one frame earlier
  mat4 normalToWorld; // the inverse transpose of the world transform, now
  vec4 albedo;        // w: the object's id
  vec4 ambient;       // the scene's light: ambient, colour, direction it travels
  vec4 lightColor;
  vec4 lightDirection;
};
layout(std430, binding = 0) readonly buffer Objects { ObjectData objects[]; };

layout(location = 0) out vec3 worldNormal;
layout(location = 1) out vec4 previousClip;
layout(location = 2) flat out uint object;  // the draw's slot in objects[]

void main() {
  const ObjectData o = objects[gl_InstanceIndex];  // each draw's first instance is its object
  gl_Position = o.clipNow * vec4(position, 1.0);
  previousClip = o.clipPrevious * vec4(position, 1.0);
  worldNormal = mat3(o.normalToWorld) * normal;
  object = gl_InstanceIndex;
}
