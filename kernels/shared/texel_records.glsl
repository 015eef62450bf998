// Reads of 16-byte records through uniform texel buffers (RGBA32UI views of storage buffers:
// vk::Buffer::texelView). Kernels read what they fetch at per-lane addresses this way: on
// Mesa 22.3's lavapipe a texel fetch is one unconditional 16-byte load per lane and a transpose
// where a storage-buffer load is a loop over the lanes with a branch each; on GPUs it is the
// cached read-only path. A fetch loads all four words, so a kernel that needs one or two words
// of a record keeps the storage-buffer load.
#ifndef HMB_KERNELS_SHARED_TEXEL_RECORDS_GLSL
#define HMB_KERNELS_SHARED_TEXEL_RECORDS_GLSL

#extension GL_EXT_samplerless_texture_functions : require

uvec4 recordAt(utextureBuffer records, uint i) { return texelFetch(records, int(i)); }
vec4 floatRecordAt(utextureBuffer records, uint i) { return uintBitsToFloat(texelFetch(records, int(i))); }

// Records first..first+3 as a matrix's columns.
mat4 mat4RecordsAt(utextureBuffer records, uint first) {
  return mat4(floatRecordAt(records, first), floatRecordAt(records, first + 1u), floatRecordAt(records, first + 2u),
              floatRecordAt(records, first + 3u));
}

// Entry i of an array of 8-byte entries, two to a record.
uvec2 halfRecordAt(utextureBuffer records, uint i) {
  const uvec4 two = texelFetch(records, int(i >> 1u));
  return (i & 1u) == 0u ? two.xy : two.zw;
}

#endif
