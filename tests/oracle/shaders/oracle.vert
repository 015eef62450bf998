#version 450
// Passes the clip-space position through untouched: the oracle must see exactly the
// positions the compute rasterizer sees.
layout(location = 0) in vec4 inClip;
layout(location = 1) in uint inId;
layout(location = 0) flat out uint outId;

void main() {
  gl_Position = inClip;
  outId = inId;
}
