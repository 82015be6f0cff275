// Texture lookups of glTF materials, C++ and GLSL (glsl_compat.h rules): wrap modes, bilinear
// filtering, sRGB decoding and KHR_texture_transform. The host unit tests (tests/unit/
// test_texture_sample.cpp) run this exact code; tests/gpu/test_gpu_textures.cpp compares the
// GLSL build with it.
//
// Storage (host/render/texture_pack.h): every image of a scene is packed as RGBA8 texels, one
// uint per texel (R in the low byte), rows top to bottom, all images one after the other in one
// texel buffer (lavapipe has no descriptor indexing); a high-dynamic-range image of a JSON texture
// as RGB9E5 texels (TEXF_RGB9E5), also one uint each. A texture header is one uvec4:
//   x: first texel of the image, y: width, z: height, w: flags (TEXF_*).
// glTF's UV (0,0) is the top left corner of the image, so texel row = v * height, no flip.
//
// The includer defines VKP_TEXEL_FETCH(i) (uint: packed RGBA8 texel i of the buffer) BEFORE
// including this file when it wants texSample(); the pure math above it needs nothing.
#ifndef VKP_TEXTURE_SAMPLE_H
#define VKP_TEXTURE_SAMPLE_H
#include "glsl_compat.h"

VKP_BEGIN

// Flags of a texture header (w).
const uint TEXF_WRAP_REPEAT = 0u;  // wrap S in bits 0-1, wrap T in bits 2-3
const uint TEXF_WRAP_CLAMP = 1u;
const uint TEXF_WRAP_MIRROR = 2u;
const uint TEXF_SRGB = 16u;     // colour data: RGB decoded from sRGB to linear (alpha stays linear)
const uint TEXF_NEAREST = 32u;  // magFilter NEAREST: the texel under the point, no filtering
const uint TEXF_RGB9E5 = 64u;   // texels are RGB9E5 (linear RGB, alpha 1), not RGBA8

/// One sRGB-encoded channel value c in [0,1] to linear (IEC 61966-2-1).
VKP_FN float srgbToLinear(float c) {
    return (c <= 0.04045f) ? c / 12.92f : pow((c + 0.055f) / 1.055f, 2.4f);
}

/// A packed RGBA8 texel (R in the low byte) as floats in [0,1]; RGB decoded from sRGB if srgb.
VKP_FN vec4 texDecode(uint packed, bool srgb) {
    vec4 c = vec4(float(packed & 255u), float((packed >> 8u) & 255u), float((packed >> 16u) & 255u),
                  float(packed >> 24u)) / 255.0f;
    if (srgb) {
        c.x = srgbToLinear(c.x);
        c.y = srgbToLinear(c.y);
        c.z = srgbToLinear(c.z);
    }
    return c;
}

/// An RGB9E5 texel (the shared-exponent format of EXT_texture_shared_exponent and Vulkan's
/// E5B9G9R9: R in bits 0-8, G in 9-17, B in 18-26, exponent in 27-31, bias 15, 9-bit mantissas
/// without a hidden bit) as linear RGB with alpha 1.
VKP_FN vec4 rgb9e5Decode(uint packed) {
    float scale = exp2(float(packed >> 27u) - 24.0f);  // 2^(e - 15 - 9)
    return vec4(float(packed & 511u) * scale, float((packed >> 9u) & 511u) * scale,
                float((packed >> 18u) & 511u) * scale, 1.0f);
}

/// A stored texel as floats: RGB9E5 or RGBA8 (sRGB-decoded where the flags say so).
VKP_FN vec4 texTexel(uint packed, uint flags) {
    if ((flags & TEXF_RGB9E5) != 0u) return rgb9e5Decode(packed);
    return texDecode(packed, (flags & TEXF_SRGB) != 0u);
}

/// A texture coordinate reduced to a range where the wrap mode gives the same texels and where
/// u * size cannot overflow an int: [0,1) for repeat, [0,2) for mirrored repeat (period 2),
/// [-1,2] for clamp. NaN becomes 0.
VKP_FN float texReduce(float u, uint mode) {
    if (!(u == u)) return 0.0f;
    if (mode == TEXF_WRAP_CLAMP) return min(max(u, -1.0f), 2.0f);
    float period = (mode == TEXF_WRAP_MIRROR) ? 2.0f : 1.0f;
    float r = u - period * floor(u / period);
    return (r >= period) ? 0.0f : r;  // u tiny negative: u - period rounds to period
}

/// Texel index i (any integer) of an axis of n texels under the wrap mode, in [0, n).
VKP_FN int texWrap(int i, int n, uint mode) {
    if (mode == TEXF_WRAP_CLAMP) return min(max(i, 0), n - 1);
    // GLSL leaves % undefined for negative operands: fold negative i without one.
    int period = (mode == TEXF_WRAP_MIRROR) ? 2 * n : n;
    int k = (i >= 0) ? i % period : (period - 1) - ((-i - 1) % period);
    return (k < n) ? k : period - 1 - k;
}

/// Bilinear footprint of coordinate u (already reduced) on an axis of n texels: the lower texel
/// index (before wrapping) and the weight of the upper one. Texel centres sit at (i + 0.5) / n.
VKP_FN int texBilinearAxis(float u, int n, OUT(float) w1) {
    float x = u * float(n) - 0.5f;
    float f = floor(x);
    w1 = x - f;
    return int(f);
}

/// KHR_texture_transform: uv' = T(offset) R(rotation) S(scale) uv with R = [cos sin; -sin cos]
/// (row-major, as the extension's README writes it). rs = (cos * sx, sin * sy, -sin * sx,
/// cos * sy) is precomputed on the host (host/render/texture_pack.cpp), offset added last.
VKP_FN vec2 texTransform(vec2 uv, vec4 rs, vec2 offset) {
    return vec2(rs.x * uv.x + rs.y * uv.y, rs.z * uv.x + rs.w * uv.y) + offset;
}

#ifdef VKP_TEXEL_FETCH
/// Sample texture `header` (see above) at uv: bilinear (or nearest) with the header's wrap modes,
/// decoded to linear when the texture holds colour data. Filtering happens after decoding.
VKP_FN vec4 texSample(uvec4 header, vec2 uv) {
    uint base = header.x;
    int w = int(header.y);
    int h = int(header.z);
    uint ws = header.w & 3u;
    uint wt = (header.w >> 2u) & 3u;
    float u = texReduce(uv.x, ws);
    float v = texReduce(uv.y, wt);
    if ((header.w & TEXF_NEAREST) != 0u) {
        int ix = texWrap(int(floor(u * float(w))), w, ws);
        int iy = texWrap(int(floor(v * float(h))), h, wt);
        return texTexel(VKP_TEXEL_FETCH(base + uint(iy * w + ix)), header.w);
    }
    float fx;
    float fy;
    int x0 = texBilinearAxis(u, w, fx);
    int y0 = texBilinearAxis(v, h, fy);
    int xa = texWrap(x0, w, ws);
    int xb = texWrap(x0 + 1, w, ws);
    int ya = texWrap(y0, h, wt);
    int yb = texWrap(y0 + 1, h, wt);
    vec4 c00 = texTexel(VKP_TEXEL_FETCH(base + uint(ya * w + xa)), header.w);
    vec4 c10 = texTexel(VKP_TEXEL_FETCH(base + uint(ya * w + xb)), header.w);
    vec4 c01 = texTexel(VKP_TEXEL_FETCH(base + uint(yb * w + xa)), header.w);
    vec4 c11 = texTexel(VKP_TEXEL_FETCH(base + uint(yb * w + xb)), header.w);
    vec4 top = c00 * (1.0f - fx) + c10 * fx;
    vec4 bottom = c01 * (1.0f - fx) + c11 * fx;
    return top * (1.0f - fy) + bottom * fy;
}
#endif

VKP_END
#endif
