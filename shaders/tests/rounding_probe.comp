#version 460
// Device test kernel: does the device round the arithmetic that the GPU tests compare with the C++
// twin bit for bit as the host does (tests/gpu/device_rounding.h)? Per item (a, b, c):
//   out.x = a / b, out.y = 1 / b, out.z = sqrt(|a|), out.w = a * b + c
// written as plain GLSL, without `precise`: the kernels' own arithmetic. Vulkan allows 2.5 ulp for
// a division and sqrt's precision is inherited from 1 / inversesqrt (Vulkan specification, appendix
// "Precision and Operation of SPIR-V Instructions"), and a * b + c may be fused into one fma
// unless NoContraction says otherwise; the host rounds each operation exactly (IEEE 754).
//
// Bindings: 0 in (vec4 per item: a, b, c, unused), 1 out (vec4 per item). Push constant: count.
layout(local_size_x = 64) in;

layout(std430, set = 0, binding = 0) readonly buffer InBuf { vec4 inData[]; };
layout(std430, set = 0, binding = 1) writeonly buffer OutBuf { vec4 outData[]; };
layout(push_constant) uniform Push { uint count; } pc;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= pc.count) return;
    vec4 v = inData[i];
    outData[i] = vec4(v.x / v.y, 1.0 / v.y, sqrt(abs(v.x)), v.x * v.y + v.z);
}
