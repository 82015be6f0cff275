#version 460
// Device test kernel for shared/distribution.h and shared/environment_map.h: the GLSL build of the
// 2D distribution and the environment map's sampling, on a table in a texel buffer read through
// distFetch (the way the path tracer reads it), so a host test can compare with the C++ build.
//
// Bindings: 0 the table (R32F uniform texel buffer), 1 in (vec4 per item), 2 out (2 vec4 per item).
// Push constants: routine, count, nu (map width), nv (map height), cos and sin of rotate_y.
// Routines (in.xy = u in [0,1)^2):
//  0 DIST2D  out0.xy = sampleDistribution2D(u), out0.z = its pdf, out0.w = pdfDistribution2D(out0.xy)
//            out1.xy = invertDistribution2D(out0.xy)
//  1 ENVMAP  out0.xyz = sampleEnvMap(u) (world direction), out0.w = its pdf,
//            out1.x = pdfEnvMap(out0.xyz), out1.yz = its map (u, v)
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 64) in;

layout(set = 0, binding = 0) uniform samplerBuffer uTable;
layout(std430, set = 0, binding = 1) readonly buffer InBuf { vec4 inData[]; };
layout(std430, set = 0, binding = 2) writeonly buffer OutBuf { vec4 outData[]; };
layout(push_constant) uniform Push {
    uint routine;
    uint count;
    uint nu;
    uint nv;
    float c;
    float s;
} pc;

float distFetch(uint i) { return texelFetch(uTable, int(i)).x; }
#include "shared/environment_map.h"

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= pc.count) return;
    vec2 u = inData[i].xy;
    vec4 out0 = vec4(0.0);
    vec4 out1 = vec4(0.0);
    if (pc.routine == 0u) {
        float pdf;
        vec2 p = sampleDistribution2D(0u, pc.nu, pc.nv, u, pdf);
        out0 = vec4(p, pdf, pdfDistribution2D(0u, pc.nu, pc.nv, p));
        out1.xy = invertDistribution2D(0u, pc.nu, pc.nv, p);
    } else {
        float pdf;
        vec2 uv;
        vec3 d = sampleEnvMap(pc.nu, pc.nv, vec2(pc.c, pc.s), u, pdf, uv);
        out0 = vec4(d, pdf);
        out1 = vec4(pdfEnvMap(pc.nu, pc.nv, vec2(pc.c, pc.s), d), uv, 0.0);
    }
    outData[2u * i] = out0;
    outData[2u * i + 1u] = out1;
}
