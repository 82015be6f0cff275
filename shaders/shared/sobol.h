// Owen-scrambled, shuffled Sobol' points padded to any number of dimensions (C++ and GLSL).
//
/// Following Burley, "Practical Hash-based Owen Scrambling", JCGT 9(4), 2020:
///   - a point of the 4D Sobol' sequence (the first four Joe-Kuo dimensions, sec. 3 of the paper);
///   - nested uniform (Owen) scrambling of each coordinate by a hash: the coordinate's bits are
///     reversed, permuted by a Laine-Karras-style hash in which bit j depends only on bits <= j
///     (so each output digit depends only on the digits above it: a random tree of flips, i.e. Owen
///     scrambling), and reversed back (Burley sec. 4, after Laine & Karras 2011);
///   - the sample index shuffled the same way (Burley sec. 5): index i goes to an Owen-scrambled
///     index, which maps every aligned block of 2^m indices onto an aligned block of 2^m Sobol'
///     points, so every prefix of 2^m samples (and every aligned run of 2^m samples) is still a
///     (t,m,4)-net, but its points come from a block picked by the seed;
///   - padding (Burley sec. 6): dimensions 4g..4g+3 ("group g") are the same 4D Sobol' points with
///     an independent shuffle seed and independent scramble seeds per group, so no direction-number
///     table beyond 4 x 32 entries is needed and there is no limit on the dimension count. Within a
///     group the 4 coordinates are jointly stratified; across groups they are independent.
/// The permutation is the improved Laine-Karras hash of Vegdahl ("Building a Better LK Hash",
/// psychopath.io, 2021; also in Blender Cycles' sobol-burley sampler) in place of Burley's original
/// constants, whose higher bits are poorly mixed; both keep the dependency structure that makes
/// them Owen scrambles, which is all the stratification needs.
///
/// Generator matrices: the common subset forbids `const` arrays, so the 32 direction numbers of
/// each dimension are generated on the fly by the Sobol' recurrence (Bratley & Fox 1988; Joe & Kuo
/// 2008, "Constructing Sobol sequences with better two-dimensional projections"), with v_k the k-th
/// direction number as a 32-bit fraction:
///   dim 0: v_k = 2^(31-k) (van der Corput: the bit reversal of the index);
///   dim 1: primitive polynomial x + 1,        m = (1):       v_k = v_{k-1} ^ (v_{k-1} >> 1);
///   dim 2: x^2 + x + 1,   m = (1, 3):    v_k = v_{k-1} ^ v_{k-2} ^ (v_{k-2} >> 2);
///   dim 3: x^3 + x + 1,   m = (1, 3, 1): v_k = v_{k-2} ^ v_{k-3} ^ (v_{k-3} >> 3).
/// tests/stats/test_sobol_stats.cpp checks the first 16 numbers of each against the table printed
/// in Burley's supplemental code, and the (0,m,2)-net property of dims 0 and 1.
#ifndef VKP_SOBOL_H
#define VKP_SOBOL_H
#include "glsl_compat.h"
#include "rng.h"

VKP_BEGIN

/// The bits of x in reverse order (GLSL's bitfieldReverse, written out for the C++ build).
VKP_FN uint sobolReverseBits(uint x) {
    x = ((x & 0xaaaaaaaau) >> 1u) | ((x & 0x55555555u) << 1u);
    x = ((x & 0xccccccccu) >> 2u) | ((x & 0x33333333u) << 2u);
    x = ((x & 0xf0f0f0f0u) >> 4u) | ((x & 0x0f0f0f0fu) << 4u);
    x = ((x & 0xff00ff00u) >> 8u) | ((x & 0x00ff00ffu) << 8u);
    return (x >> 16u) | (x << 16u);
}

/// Owen scrambling of the bits of a bit-reversed word (Vegdahl 2021): a bijection in which output
/// bit j depends only on input bits 0..j and the seed.
VKP_FN uint sobolLkHash(uint x, uint seed) {
    x ^= x * 0x3d20adeau;
    x += seed;
    x *= (seed >> 16u) | 1u;
    x ^= x * 0x05526c56u;
    x ^= x * 0x53a22864u;
    return x;
}

/// Nested uniform (Owen) scrambling in base 2 of the 32-bit fraction x (Burley 2020, listing 3):
/// the flip of bit 31-j depends on bits 31..31-j+1 only.
VKP_FN uint nestedUniformScramble(uint x, uint seed) {
    return sobolReverseBits(sobolLkHash(sobolReverseBits(x), seed));
}

/// The k-th direction number (k = 0..31) of Sobol' dimension dim (0..3) from the three before it
/// (vk1 = v_{k-1}, vk2 = v_{k-2}, vk3 = v_{k-3}); the initial numbers come from m (file comment).
VKP_FN uint sobolDirection(uint dim, uint k, uint vk1, uint vk2, uint vk3) {
    if (dim == 0u) return 0x80000000u >> k;
    if (dim == 1u) return (k == 0u) ? 0x80000000u : (vk1 ^ (vk1 >> 1u));
    if (dim == 2u) {
        if (k == 0u) return 0x80000000u;
        if (k == 1u) return 0xc0000000u;
        return vk1 ^ vk2 ^ (vk2 >> 2u);
    }
    if (k == 0u) return 0x80000000u;
    if (k == 1u) return 0xc0000000u;
    if (k == 2u) return 0x20000000u;
    return vk2 ^ vk3 ^ (vk3 >> 3u);
}

/// Coordinate dim (0..3) of Sobol' point `index`, as a 32-bit fraction (unscrambled).
VKP_FN uint sobolBits(uint index, uint dim) {
    if (dim == 0u) return sobolReverseBits(index);
    uint x = 0u;
    uint v1 = 0u;
    uint v2 = 0u;
    uint v3 = 0u;
    for (uint k = 0u; k < 32u; ++k) {  // a constant 32-trip loop: unrolled, free of lavapipe's limit
        uint v = sobolDirection(dim, k, v1, v2, v3);
        x ^= v & (0u - ((index >> k) & 1u));
        v3 = v2;
        v2 = v1;
        v1 = v;
    }
    return x;
}

/// A 32-bit fraction as a float in [0,1): its top 24 bits times 2^-24 (exact; 1.0 never occurs).
VKP_FN float sobolToFloat(uint bits) { return float(bits >> 8u) * (1.0f / 16777216.0f); }

/// Per-pixel scramble seed from the linear pixel index and the render's seed. The salt keeps it
/// apart from rngInit's chain on the same keys.
VKP_FN uint sobolPixelSeed(uint pixel, uint seed) {
    return pcgHash(pcgHash(pcgHash(seed) ^ 0x5bd1e995u) ^ pixel);
}

/// Shuffle seed of dimension group g (dimensions 4g..4g+3) of a pixel.
VKP_FN uint sobolGroupSeed(uint pixelSeed, uint group) { return pcgHash(pixelSeed ^ pcgHash(group + 0x9e3779b9u)); }

/// Scramble seed of coordinate dim (0..3) of a group.
VKP_FN uint sobolScrambleSeed(uint groupSeed, uint dim) { return pcgHash(groupSeed + dim + 1u); }

/// Sample `index`, dimension 4 group + dim (dim 0..3) of the pixel whose seed is pixelSeed, as a
/// 32-bit fraction: shuffled index, Sobol' coordinate, Owen scramble.
VKP_FN uint sobolSampleBits(uint pixelSeed, uint index, uint group, uint dim) {
    uint gs = sobolGroupSeed(pixelSeed, group);
    uint i = nestedUniformScramble(index, gs);
    return nestedUniformScramble(sobolBits(i, dim), sobolScrambleSeed(gs, dim));
}

/// The same as a float in [0,1).
VKP_FN float sobolSample(uint pixelSeed, uint index, uint group, uint dim) {
    return sobolToFloat(sobolSampleBits(pixelSeed, index, group, dim));
}

/// Dimensions 0 and 1 of a group (a (0,2)-sequence before scrambling, so every prefix of 2^m
/// samples has one point in each of the 2^m elementary intervals of any shape), one shuffle.
VKP_FN vec2 sobolSample2(uint pixelSeed, uint index, uint group) {
    uint gs = sobolGroupSeed(pixelSeed, group);
    uint i = nestedUniformScramble(index, gs);
    float a = sobolToFloat(nestedUniformScramble(sobolReverseBits(i), sobolScrambleSeed(gs, 0u)));
    float b = sobolToFloat(nestedUniformScramble(sobolBits(i, 1u), sobolScrambleSeed(gs, 1u)));
    return vec2(a, b);
}

VKP_END
#endif
