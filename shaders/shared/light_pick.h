// Picking one light from the list: uniformly (the book's hittable_list::random, used by the
// `mixture` sampler) or in proportion to emitted power through an alias table (Walker 1977,
// "An efficient method for generating discrete random variables with general distributions";
// Vose 1991's construction, built on the host in host/render/light_table.cpp). O(1) on the device:
// one texel fetch, no loop. The probability a pick reports is the probability it is made with.
#ifndef VKP_LIGHT_PICK_H
#define VKP_LIGHT_PICK_H
#include "gpu_types.h"

VKP_BEGIN

/// Uniform pick among n >= 1 lights with u in [0,1): the index; pdf = 1/n.
VKP_FN uint pickUniform(float u, uint n) { return min(uint(u * float(n)), n - 1u); }

/// First step of an alias pick among n >= 1 columns: the column u falls in, and the position
/// within it (in [0,1)) in `frac`.
VKP_FN uint aliasColumn(float u, uint n, OUT(float) frac) {
    float x = u * float(n);
    uint i = min(uint(x), n - 1u);
    frac = min(x - float(i), 0.99999994f);
    return i;
}

/// Second step: column i keeps the pick when frac < its threshold, else hands it to its alias.
/// `entry` is the column's GpuLight (l0.z = threshold, l0.w = bits of the alias index).
VKP_FN uint aliasResolve(uint i, float frac, GpuLight entry) {
    return (frac < entry.l0.z) ? i : floatBitsToUint(entry.l0.w);
}

/// Power heuristic with beta = 2 (Veach 1997, sec. 9.2.4): the weight of the strategy with pdf a
/// against one with pdf b. 0 when a is 0; finite for any finite inputs.
VKP_FN float powerHeuristic(float a, float b) {
    float a2 = a * a;
    float d = a2 + b * b;
    return (d > 0.0f) ? a2 / d : 0.0f;
}

VKP_END
#endif
