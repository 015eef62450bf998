#version 450
// Writes what hybrid-mblur's engine backend reads: linear colour, camera-space depth and the
// screen motion over the last frame in pixels (now minus then, +y down as Vulkan's framebuffer).
layout(location = 0) in vec3 worldNormal;
layout(location = 1) in vec4 previousClip;
layout(location = 2) flat in vec3 albedo;
layout(location = 3) flat in uint object;

// The framebuffer's size, set when the pipeline is made.
layout(constant_id = 0) const float kWidth = 1.0;
layout(constant_id = 1) const float kHeight = 1.0;

layout(location = 0) out vec4 color;
layout(location = 1) out float depth;
layout(location = 2) out vec2 velocity;
layout(location = 3) out vec4 normal;  // world space (the hybrid's edge mask reads it)
layout(location = 4) out uint objectId;  // 0 is the background (the clear value)

void main() {
  const vec3 light = normalize(vec3(0.4, 0.8, 0.5));
  const vec3 n = normalize(worldNormal);
  color = vec4(albedo * (0.25 + 0.75 * max(dot(n, light), 0.0)), 1.0);
  normal = vec4(n, 0.0);
  objectId = object;
  depth = 1.0 / gl_FragCoord.w;  // clip w: the camera-space depth of a perspective projection
  // gl_FragCoord is the pixel's centre now; the same surface point one frame ago, in pixels.
  const vec2 previousPixel = (previousClip.xy / previousClip.w * 0.5 + 0.5) * vec2(kWidth, kHeight);
  velocity = gl_FragCoord.xy - previousPixel;
}
