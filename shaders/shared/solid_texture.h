// Textures of JSON scenes ("Ray Tracing: The Next Week", Shirley, sec. 4-5), C++ and GLSL
// (glsl_compat.h rules): the 3D checker, images on the book's sphere and quad UVs, and Perlin noise
// (noise, turbulence, marble). The host unit tests (tests/unit/test_solid_texture.cpp) run this
// exact code; tests/gpu/test_gpu_solid_textures.cpp compares the GLSL build with it value by value.
//
// Storage (host/render/texture_pack.cpp packTextures), RGBA32UI texels of the texture-info
// buffer from texel T = info[0].w on (T = 0: the scene has none):
//   T + 0:           (origin.xyz as float bits, texel of the Perlin table relative to T)
//   T + 1 + 2 k:     node k: (kind STEX_*, a, b, 0)
//   T + 2 + 2 k:     node k: (colour.rgb, scale) as float bits
//   T + P + i:       the Perlin table, i < PERLIN_POINTS: (gradient.xyz as float bits,
//                    permX[i] | permY[i] << 8 | permZ[i] << 16)
// Node kinds (STEX_*, shared/kinds.h) and their fields:
//   STEX_SOLID       colour
//   STEX_CHECKER     a = even node, b = odd node, scale = 1 / cell size (the book's inv_scale)
//   STEX_IMAGE       a = texture header index (shared/texture_sample.h), colour multiplies it
//   STEX_NOISE       colour x 0.5 (1 + noise(scale p))
//   STEX_TURBULENCE  colour x turb(scale p), 7 octaves
//   STEX_MARBLE      colour x 0.5 (1 + sin(scale p.z + 10 turb(p))), the book's final noise texture
// Points p are the file's coordinates (the kernel's camera-relative point + origin), so a solid
// texture does not move with the camera.
//
// The includer defines, BEFORE including this file, VKP_STEX_FETCH(i) (uvec4: texel T + i) for
// the noise and evalSolidTexture, and VKP_TEXEL_FETCH / VKP_TEXHEADER_FETCH(h) (uvec4: texture
// header h) for image nodes; the pure math needs nothing.
#ifndef VKP_SOLID_TEXTURE_H
#define VKP_SOLID_TEXTURE_H
#include "glsl_compat.h"
#include "kinds.h"
#include "texture_sample.h"

VKP_BEGIN

/// The book's sphere UV (sec. 4.4, get_sphere_uv) of a point on the unit sphere n (outward unit
/// normal): u = phi / 2 pi with phi = atan2(-z, x) + pi, v = theta / pi with theta = acos(-y).
/// u in [0, 1], v in [0, 1] from the south pole (y = -1) to the north pole (y = 1).
VKP_FN vec2 sphereUv(vec3 n) {
    float theta = acos(clamp(-n.y, -1.0f, 1.0f));
    float phi = atan(-n.z, n.x) + VKP_PI;
    return vec2(phi * (0.5f * VKP_INV_PI), theta * VKP_INV_PI);
}

/// floor(x) mod 2 for any float x, in float (0 or 1; exact: no integer conversion to overflow).
VKP_FN float floorParity(float x) {
    float f = floor(x);
    return f - 2.0f * floor(0.5f * f);
}

/// The book's spatial checker (sec. 4.3): the cell of p, floor(p / cell size) per axis, is even
/// when the sum of its three indices is even. invScale = 1 / cell size.
VKP_FN bool checkerEven(vec3 p, float invScale) {
    float s = floorParity(invScale * p.x) + floorParity(invScale * p.y) + floorParity(invScale * p.z);
    return floorParity(s) == 0.0f;
}

/// The book's Hermite smoothing of a fractional coordinate (sec. 5.4): t^2 (3 - 2 t).
VKP_FN float hermite(float t) { return t * t * (3.0f - 2.0f * t); }

#ifdef VKP_STEX_FETCH
/// Lattice coordinate floor(x) mod 256 as a table index (exact for any float; NaN gives 0).
VKP_FN uint perlinCell(float f) {
    float r = f - 256.0f * floor(f * (1.0f / 256.0f));
    return (r >= 0.0f && r < 256.0f) ? uint(r) : 0u;
}

/// The book's Perlin noise (sec. 5.6-5.7) at p: random unit gradients at the lattice points, picked
/// by permX[i] ^ permY[j] ^ permZ[k], dotted with the offset to p and blended with Hermite
/// weights. |noise| <= sqrt(3) (host solidTextureBound; about 1 in practice); 0 at every lattice point. The table is at texel pt of the solid-texture
/// data (see the file comment).
VKP_FN float perlinNoise(vec3 p, uint pt) {
    vec3 f = floor(p);
    vec3 w = p - f;
    uint i0 = perlinCell(f.x);
    uint j0 = perlinCell(f.y);
    uint k0 = perlinCell(f.z);
    uint px0 = VKP_STEX_FETCH(pt + i0).w & 255u;
    uint px1 = VKP_STEX_FETCH(pt + ((i0 + 1u) & 255u)).w & 255u;
    uint py0 = (VKP_STEX_FETCH(pt + j0).w >> 8u) & 255u;
    uint py1 = (VKP_STEX_FETCH(pt + ((j0 + 1u) & 255u)).w >> 8u) & 255u;
    uint pz0 = (VKP_STEX_FETCH(pt + k0).w >> 16u) & 255u;
    uint pz1 = (VKP_STEX_FETCH(pt + ((k0 + 1u) & 255u)).w >> 16u) & 255u;
    float uu = hermite(w.x);
    float vv = hermite(w.y);
    float ww = hermite(w.z);
    float accum = 0.0f;
    for (uint c = 0u; c < 8u; ++c) {
        uint di = c & 1u;
        uint dj = (c >> 1u) & 1u;
        uint dk = (c >> 2u) & 1u;
        uint idx = (di == 0u ? px0 : px1) ^ (dj == 0u ? py0 : py1) ^ (dk == 0u ? pz0 : pz1);
        uvec4 g = VKP_STEX_FETCH(pt + idx);
        vec3 grad = vec3(uintBitsToFloat(g.x), uintBitsToFloat(g.y), uintBitsToFloat(g.z));
        vec3 off = vec3(w.x - float(di), w.y - float(dj), w.z - float(dk));
        float wx = di == 0u ? 1.0f - uu : uu;
        float wy = dj == 0u ? 1.0f - vv : vv;
        float wz = dk == 0u ? 1.0f - ww : ww;
        accum += wx * wy * wz * dot(grad, off);
    }
    return accum;
}

/// The book's turbulence (sec. 5.8): |sum over 7 octaves of 2^-i noise(2^i p)|, >= 0.
VKP_FN float perlinTurbulence(vec3 p, uint pt) {
    float accum = 0.0f;
    vec3 q = p;
    float weight = 1.0f;
    for (int i = 0; i < TURBULENCE_OCTAVES; ++i) {
        accum += weight * perlinNoise(q, pt);
        weight *= 0.5f;
        q = 2.0f * q;
    }
    return abs(accum);
}

/// The file-coordinate origin of the kernel's camera-relative points (see the file comment).
VKP_FN vec3 solidTextureOrigin() {
    uvec4 t = VKP_STEX_FETCH(0u);
    return vec3(uintBitsToFloat(t.x), uintBitsToFloat(t.y), uintBitsToFloat(t.z));
}

#if defined(VKP_TEXEL_FETCH) && defined(VKP_TEXHEADER_FETCH)
/// The colour of texture node `node` at the point p (file coordinates) with surface UV uv (the
/// book's convention: v up; an image's top row is at v = 1). Linear RGB, >= 0.
VKP_FN vec3 evalSolidTexture(uint node, vec3 p, vec2 uv) {
    uint pt = VKP_STEX_FETCH(0u).w;
    for (uint depth = 0u; depth <= STEX_MAX_DEPTH; ++depth) {
        uvec4 n0 = VKP_STEX_FETCH(1u + STEX_NODE_TEXELS * node);
        uvec4 n1b = VKP_STEX_FETCH(2u + STEX_NODE_TEXELS * node);
        vec3 colour = vec3(uintBitsToFloat(n1b.x), uintBitsToFloat(n1b.y), uintBitsToFloat(n1b.z));
        float scale = uintBitsToFloat(n1b.w);
        if (n0.x == STEX_CHECKER) {
            node = checkerEven(p, scale) ? n0.y : n0.z;
            continue;
        }
        if (n0.x == STEX_IMAGE) {
            vec4 c = texSample(VKP_TEXHEADER_FETCH(n0.y), vec2(uv.x, 1.0f - uv.y));
            return colour * vec3(c.x, c.y, c.z);
        }
        if (n0.x == STEX_NOISE) return colour * (0.5f * (1.0f + perlinNoise(scale * p, pt)));
        if (n0.x == STEX_TURBULENCE) return colour * perlinTurbulence(scale * p, pt);
        if (n0.x == STEX_MARBLE) return colour * (0.5f * (1.0f + sin(scale * p.z + 10.0f * perlinTurbulence(p, pt))));
        return colour;  // STEX_SOLID
    }
    return vec3(0.0f);  // deeper than STEX_MAX_DEPTH: the loader refuses such textures
}
#endif
#endif

VKP_END
#endif
