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

/// Sobol' dimension 1 (primitive polynomial x + 1) of point `index`, all 32 bits, in five steps
/// instead of a product with 32 columns. Its direction numbers are the rows of Pascal's triangle
/// mod 2: v_k has the bit p places below the top set iff C(k, p) is odd, i.e. iff p is a submask of
/// k (Lucas' theorem). So output bit p (from the top) is the XOR of index bits k over every k that
/// contains p: a superset-sum transform over the five bits of a bit position, one shift-and-mask
/// step per bit s, on the reversed index (where index bit p sits p places below the top; a bit q
/// of the word, q = 31 - p, lacks s in p exactly when q has it).
VKP_FN uint sobolDim1Bits(uint index) {
    uint x = sobolReverseBits(index);
    x ^= (x << 1u) & 0xaaaaaaaau;
    x ^= (x << 2u) & 0xccccccccu;
    x ^= (x << 4u) & 0xf0f0f0f0u;
    x ^= (x << 8u) & 0xff00ff00u;
    x ^= (x << 16u) & 0xffff0000u;
    return x;
}
/// Coordinate 2 or 3 of Sobol' point `index`: the product with the 32 columns of the generator
/// matrix, built by the recurrences of the file comment with k a constant after unrolling, so that
/// every column is a constant, and both dimensions share the masks of the index's bits (on
/// lavapipe both sides of a choice run anyway, so a dimension chosen at run time costs one loop,
/// not two loops and a recurrence per column).
VKP_FN uint sobolDim23Bits(uint index, uint dim) {
    uint x2 = 0u;
    uint x3 = 0u;
    uint a1 = 0u;  // dimension 2: v_{k-1}, v_{k-2}
    uint a2 = 0u;
    uint b1 = 0u;  // dimension 3: v_{k-1}, v_{k-2}, v_{k-3}
    uint b2 = 0u;
    uint b3 = 0u;
    for (uint k = 0u; k < 32u; ++k) {  // a constant 32-trip loop: unrolled, free of lavapipe's limit
        uint va = (k == 0u) ? 0x80000000u : (k == 1u) ? 0xc0000000u : (a1 ^ a2 ^ (a2 >> 2u));
        uint vb = (k == 0u) ? 0x80000000u : (k == 1u) ? 0xc0000000u : (k == 2u) ? 0x20000000u : (b2 ^ b3 ^ (b3 >> 3u));
        uint mask = 0u - ((index >> k) & 1u);
        x2 ^= va & mask;
        x3 ^= vb & mask;
        a2 = a1;
        a1 = va;
        b3 = b2;
        b2 = b1;
        b1 = vb;
    }
    return (dim == 2u) ? x2 : x3;
}

/// Coordinate dim (0..3) of Sobol' point `index`, as a 32-bit fraction (unscrambled), all 32 bits.
VKP_FN uint sobolBits(uint index, uint dim) {
    if (dim == 0u) return sobolReverseBits(index);
    if (dim == 1u) return sobolDim1Bits(index);
    return sobolDim23Bits(index, dim);
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

/// Coordinate dim of a group with Sobol' bits `bits` (of the shuffled index), Owen-scrambled.
VKP_FN uint sobolScrambled(uint bits, uint groupSeed, uint dim) {
    return nestedUniformScramble(bits, sobolScrambleSeed(groupSeed, dim));
}

/// Sample `index`, dimension 4 group + dim (dim 0..3) of the pixel whose seed is pixelSeed, as a
/// 32-bit fraction: shuffled index, Sobol' coordinate, Owen scramble.
VKP_FN uint sobolSampleBits(uint pixelSeed, uint index, uint group, uint dim) {
    uint gs = sobolGroupSeed(pixelSeed, group);
    uint i = nestedUniformScramble(index, gs);
    return sobolScrambled(sobolBits(i, dim), gs, dim);
}

/// The same as a float in [0,1).
VKP_FN float sobolSample(uint pixelSeed, uint index, uint group, uint dim) {
    return sobolToFloat(sobolSampleBits(pixelSeed, index, group, dim));
}

/// sobolSample of dimension 2 or 3 (sample_stream.h's single numbers): the same float without the
/// code of dimensions 0 and 1, which lavapipe would run as well.
VKP_FN float sobolSampleDim23(uint pixelSeed, uint index, uint group, uint dim) {
    uint gs = sobolGroupSeed(pixelSeed, group);
    uint i = nestedUniformScramble(index, gs);
    return sobolToFloat(sobolScrambled(sobolDim23Bits(i, dim), gs, dim));
}

/// Dimensions 0 and 1 of a group (a (0,2)-sequence before scrambling, so every prefix of 2^m
/// samples has one point in each of the 2^m elementary intervals of any shape), one shuffle.
VKP_FN vec2 sobolSample2(uint pixelSeed, uint index, uint group) {
    uint gs = sobolGroupSeed(pixelSeed, group);
    uint i = nestedUniformScramble(index, gs);
    float a = sobolToFloat(sobolScrambled(sobolReverseBits(i), gs, 0u));
    float b = sobolToFloat(sobolScrambled(sobolDim1Bits(i), gs, 1u));
    return vec2(a, b);
}

VKP_END
#endif
