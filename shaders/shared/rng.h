// Random numbers for the kernels and the CPU twin: a counter-based stream per (pixel, sample).
// The stream of one sample depends only on (pixel index, sample index, seed), never on how the
// samples are split over dispatches or on the order in which invocations run, so a render is
// reproducible bit for bit whatever the batch size.
//
// Construction (Jarzynski & Olano, "Hash Functions for GPU Rendering", JCGT 9(3), 2020):
//   - rngInit hashes the three keys with the PCG hash (their recommended 1D hash, a single step of
//     PCG's RXS-M-XS output function on a 32-bit LCG state), chained: h = H(seed), H(h ^ pixel),
//     H(h + sample);
//   - rngNext advances a 32-bit LCG (multiplier 747796405, increment 2891336453, period 2^32) and
//     returns the RXS-M-XS permutation of the new state, i.e. PCG RXS-M-XS 32/32 (O'Neill,
//     "PCG: A Family of Simple Fast Space-Efficient Statistically Good Algorithms", 2014).
// Statistical checks: tests/stats/test_rng_stats.cpp (uniformity, pairs within a path, pairs
// across neighbouring pixels and samples, serial correlation, bit balance).
#ifndef VKP_RNG_H
#define VKP_RNG_H
#include "glsl_compat.h"

VKP_BEGIN

/// PCG hash of one 32-bit word (Jarzynski & Olano 2020, sec. 2 "pcg"): a bijection on uint.
VKP_FN uint pcgHash(uint v) {
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

/// Initial RNG state of one sample: pixel = linear pixel index (y * width + x), sampleIndex =
/// global index of the sample in that pixel (0, 1, 2, ... over the whole render), seed = the
/// render's seed. Distinct pixels give distinct states for a fixed seed (pcgHash is a bijection).
VKP_FN uint rngInit(uint pixel, uint sampleIndex, uint seed) {
    uint h = pcgHash(seed);
    h = pcgHash(h ^ pixel);
    return pcgHash(h + sampleIndex);
}

/// Next 32 random bits of the stream (advances state).
VKP_FN uint rngNextUint(INOUT(uint) state) {
    state = state * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

/// Next float, uniform on [0,1): the top 24 bits times 2^-24, so every value is exactly
/// representable, the largest is 1 - 2^-24 and 1.0 never occurs.
VKP_FN float rngNext(INOUT(uint) state) {
    return float(rngNextUint(state) >> 8u) * (1.0f / 16777216.0f);
}

/// Two successive floats of the stream: (first draw, second draw), each in [0,1).
VKP_FN vec2 rngNext2(INOUT(uint) state) {
    float a = rngNext(state);
    float b = rngNext(state);
    return vec2(a, b);
}

VKP_END
#endif
