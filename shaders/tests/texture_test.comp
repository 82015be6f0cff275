#version 460
// Device test kernel for shared/texture_sample.h: the GLSL build of texSample and texTransform on
// texels in an R32UI texel buffer (read as the path tracer reads them, lib/surface.glsl), so that
// tests/gpu/test_gpu_textures.cpp can compare with the C++ build on the same lookups.
//
// Bindings: 0 texels (R32UI uniform texel buffer), 1 in (vec4 per item: uv, header slot, 0),
// 2 out (2 vec4 per item: texSample(header, uv), texTransform(uv, rs, offset)).
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 64) in;

layout(set = 0, binding = 0) uniform usamplerBuffer uTexels;
layout(std430, set = 0, binding = 1) readonly buffer InBuf { vec4 inData[]; };
layout(std430, set = 0, binding = 2) writeonly buffer OutBuf { vec4 outData[]; };
layout(push_constant) uniform Push {
    uvec4 headers[4];
    vec4 rs;
    vec4 offset;  // xy
    uint count;
} pc;

#define VKP_TEXEL_FETCH(i) texelFetch(uTexels, int(i)).x
#include "shared/texture_sample.h"

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= pc.count) return;
    vec4 item = inData[i];
    outData[2u * i] = texSample(pc.headers[uint(item.z) & 3u], item.xy);
    outData[2u * i + 1u] = vec4(texTransform(item.xy, pc.rs, pc.offset.xy), 0.0f, 0.0f);
}
