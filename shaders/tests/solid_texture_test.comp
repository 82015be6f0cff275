#version 460
// Device test kernel for shared/solid_texture.h: the GLSL build of perlinNoise, perlinTurbulence
// and evalSolidTexture over a texture-info buffer and texels packed by the host
// (host/render/texture_pack.cpp), read as the path tracer reads them (lib/solid_texture.glsl), so
// that tests/gpu/test_gpu_solid_textures.cpp can compare them with the C++ build value by value.
//
// Bindings: 0 texture info (RGBA32UI uniform texel buffer), 1 texels (R32UI), 2 in (2 vec4 per
// item: p.xyz, node (as a float); uv.xy), 3 out (2 vec4 per item: evalSolidTexture(node, p, uv),
// 0; perlinNoise(p), perlinTurbulence(p), sphereUv(normalize(p)))).
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 64) in;

layout(set = 0, binding = 0) uniform usamplerBuffer uTexInfo;
layout(set = 0, binding = 1) uniform usamplerBuffer uTexels;
layout(std430, set = 0, binding = 2) readonly buffer InBuf { vec4 inData[]; };
layout(std430, set = 0, binding = 3) writeonly buffer OutBuf { vec4 outData[]; };
layout(push_constant) uniform Push { uint count; } pc;

uint gBase = 0u;
#define VKP_STEX_FETCH(i) texelFetch(uTexInfo, int(gBase + (i)))
#define VKP_TEXHEADER_FETCH(h) texelFetch(uTexInfo, int(texelFetch(uTexInfo, 0).x + (h)))
#define VKP_TEXEL_FETCH(i) texelFetch(uTexels, int(i)).x
#include "shared/solid_texture.h"

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= pc.count) return;
    gBase = texelFetch(uTexInfo, 0).w;
    vec4 a = inData[2u * i];
    vec4 b = inData[2u * i + 1u];
    uint pt = VKP_STEX_FETCH(0u).w;
    outData[2u * i] = vec4(evalSolidTexture(uint(a.w), a.xyz, b.xy), 0.0f);
    vec2 uv = length(a.xyz) > 0.0f ? sphereUv(normalize(a.xyz)) : vec2(0.0f);
    outData[2u * i + 1u] = vec4(perlinNoise(a.xyz, pt), perlinTurbulence(a.xyz, pt), uv);
}
