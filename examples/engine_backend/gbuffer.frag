#version 450
// Writes what hybrid-mblur's engine backend reads: linear colour, camera-space depth, the
// screen motion over the last frame in pixels (now minus then, +y down as Vulkan's framebuffer),
// world normal and object id. The colour is the base colour under one directional light and
// ambient light, as the library shades.
layout(location = 0) in vec3 worldNormal;
layout(location = 1) in vec4 previousClip;
layout(location = 2) flat in uint object;

struct ObjectData {
  mat4 clipNow;
  mat4 clipPrevious;
  mat4 normalToWorld;
  vec4 albedo;
  vec4 ambient;
  vec4 lightColor;
  vec4 lightDirection;
};
layout(std430, binding = 0) readonly buffer Objects { ObjectData objects[]; };

// The framebuffer's size, set when the pipeline is made.
layout(constant_id = 0) const float kWidth = 1.0;
layout(constant_id = 1) const float kHeight = 1.0;

layout(location = 0) out vec4 color;
layout(location = 1) out float depth;
layout(location = 2) out vec2 velocity;
layout(location = 3) out vec4 normal;    // world space, facing the viewer
layout(location = 4) out uint objectId;  // 0 is the background (the clear value)

void main() {
  const ObjectData o = objects[object];
  vec3 n = normalize(worldNormal);
  if (!gl_FrontFacing) n = -n;  // a double-sided surface seen from behind
  const float lambert = max(dot(n, -o.lightDirection.xyz), 0.0);
  color = vec4(o.albedo.rgb * (o.ambient.rgb + o.lightColor.rgb * lambert), 1.0);
  normal = vec4(n, 0.0);
  objectId = uint(o.albedo.w);
  depth = 1.0 / gl_FragCoord.w;  // clip w: the camera-space depth of a perspective projection
  // gl_FragCoord is the pixel's centre now; the same surface point one frame ago, in pixels.
  const vec2 previousPixel = (previousClip.xy / previousClip.w * 0.5 + 0.5) * vec2(kWidth, kHeight);
  velocity = gl_FragCoord.xy - previousPixel;
}
