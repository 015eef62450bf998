// One pixel of an engine's G-buffer as the library's layer holds it, for the kernels that read
// the engine's buffers or its images: depth to camera-space depth, velocity to pixels, the
// normal decoded; the layer's sample, surface and velocity written. Include after the kernel's
// Params block and its Samples, Surfaces and Velocities buffers.
#ifndef HMB_KERNELS_ENGINE_ENGINE_PIXEL_GLSL
#define HMB_KERNELS_ENGINE_ENGINE_PIXEL_GLSL

// Camera-space depth of the engine's value; HMB_MBLUR_MAX_DEPTH where it is the far plane or
// beyond (or not a number), which the gathers treat as the farthest background.
float cameraDepth(float d) {
  float z = d;
  if (params.depthConvention == HMB_ENGINE_DEPTH_STANDARD_Z) {
    // z/w = far (d - near) / (d (far - near))  =>  d = near far / (far - z (far - near))
    z = d < 1.0 ? params.near * params.far / (params.far - d * (params.far - params.near)) : HMB_MBLUR_MAX_DEPTH;
  } else if (params.depthConvention == HMB_ENGINE_DEPTH_REVERSED_Z) {
    // z/w = near (far - d) / (d (far - near))  =>  d = near far / (near + z (far - near)),
    // near / z when far is infinite
    z = d > 0.0 ? (isinf(params.far) ? params.near / d
                                     : params.near * params.far / (params.near + d * (params.far - params.near)))
                : HMB_MBLUR_MAX_DEPTH;
  }
  return (z > 0.0 && z < HMB_MBLUR_MAX_DEPTH) ? z : HMB_MBLUR_MAX_DEPTH;
}

// The engine's velocity in pixels per frame.
vec2 velocityInPixels(vec2 v) {
  return params.velocityUnits == HMB_ENGINE_VELOCITY_NDC ? v * 0.5 * vec2(params.width, params.height) : v;
}

// The octahedral map's inverse: e in [-1, 1]^2 to a unit vector.
vec3 octahedralDecode(vec2 e) {
  vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
  const float fold = max(-n.z, 0.0);
  n.x += n.x >= 0.0 ? -fold : fold;
  n.y += n.y >= 0.0 ? -fold : fold;
  return normalize(n);
}

// The engine's stored normal (xyz, or the octahedral pair in xy) as a world-space vector.
vec3 decodedNormal(vec3 stored) {
  switch (params.normalEncoding) {
    case HMB_ENGINE_NORMAL_XYZ_UNORM: return stored * 2.0 - 1.0;
    case HMB_ENGINE_NORMAL_OCTAHEDRAL: return octahedralDecode(stored.xy);
    case HMB_ENGINE_NORMAL_OCTAHEDRAL_UNORM: return octahedralDecode(stored.xy * 2.0 - 1.0);
    default: return stored;
  }
}

// Writes pixel i of the layer. withSurfaces: whether the engine gave normals and object ids (else
// +z, and object 1 where anything is, 0 where the far plane is).
void packEnginePixel(uint i, vec3 color, float depthValue, vec2 velocity, vec3 storedNormal, uint id, bool withSurfaces) {
  const float z = cameraDepth(depthValue);
  const bool background = z >= HMB_MBLUR_MAX_DEPTH;
  const vec2 v = velocityInPixels(velocity);  // the background's too: a turning camera moves the sky
  samples[i] = packLayerSample(color, z, v);
  velocities[i] = layerVelocityEntry(v);  // what tile-max ranks
  // The post-process needs neither normals nor object ids; the hybrid's ray mask, reveal and
  // composite read the engine's.
  if (withSurfaces) surfaces[i] = packLayerSurface(decodedNormal(storedNormal), id, z, v);
  else surfaces[i] = packLayerSurface(vec3(0.0, 0.0, 1.0), background ? 0u : 1u, z, v);
}

#endif
