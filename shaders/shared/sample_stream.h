// The random numbers of one path sample (C++ and GLSL): a SampleStream replaces the bare RNG
// state, and sampleNext()/sampleNext2() replace rngNext()/rngNext2() at every use in the kernel.
//
/// Two sequences (the includer defines VKP_SEQUENCE_SOBOL, a constant: in the kernel the
/// specialization constant SEQUENCE, so the unused one compiles out; C++ default true):
///   random - every number from the hashed RNG of rng.h, keyed by (pixel, sample index, seed):
///            exactly the numbers (and images) of the kernel before the streams existed;
///   sobol  - Owen-scrambled, shuffled Sobol' points (shared/sobol.h), per-pixel seed from
///            (pixel, seed), so every number is a function of (pixel, sample index, seed, dimension)
///            only and any split of samples over dispatches gives the same bits.
///
/// Dimension layout (sobol). Dimensions come in groups of four (sobol.h: one 4D Sobol' point per
/// group, groups independently shuffled and scrambled). Every path vertex owns two groups:
/// vertex v (v = 0: the camera; v = the path's depth after the ray that reached it, 1, 2, ...)
/// owns groups 2v and 2v + 1. Within a vertex, in the order the kernel draws them:
///   - sampleNext2 number k (k = 0, 1) is coordinates (0, 1) of group 2v + k: a (0,2)-sequence, the
///     best 2D stratification there is;
///   - sampleNext number k (k = 0..3) is coordinate 2 + k / 2 of group 2v + k % 2.
/// So, per vertex of the kernel:
///   camera:      jitter = pair 0 (group 0, dims 0-1), lens = pair 1 (group 1, dims 0-1), and in
///                variants with motion blur the path's time = single 0 (group 0, dim 2: sampleTime;
///                jointly stratified with the jitter: dimensions 0-2 of one scrambled Sobol' set);
///   lambertian:  strategy = single 0 (group 2v, dim 2), direction = pair 0 (group 2v, dims 0-1),
///                light point = pair 1 (group 2v+1, dims 0-1), roulette = single 1 (group 2v+1, dim 2);
///   pbr:         strategy = single 0, lobe = single 1, direction = pair 0, light = pair 1, roulette =
///                single 2 (group 2v, dim 3);
///   metal:       fuzz = singles 0-2, roulette = single 3;  dielectric: choice = single 0, roulette = single 1.
/// The strategy number and the BSDF direction of a vertex are thus jointly stratified (one 3D
/// net), the light point gets its own (0,2) pair. A vertex that asks for more than 2 pairs or 4
/// singles, and every vertex past VKP_SOBOL_MAX_VERTEX, gets the hashed RNG instead (the same
/// stream as `random`): past a few bounces Russian roulette and path divergence leave little
/// for stratification to gain.
#ifndef VKP_SAMPLE_STREAM_H
#define VKP_SAMPLE_STREAM_H
#include "glsl_compat.h"
#include "rng.h"
#include "sobol.h"

#ifndef VKP_SEQUENCE_SOBOL
#define VKP_SEQUENCE_SOBOL true
#endif

VKP_BEGIN

/// Vertices 0..VKP_SOBOL_MAX_VERTEX draw Sobol' numbers; later ones the hashed RNG.
const uint VKP_SOBOL_MAX_VERTEX = 8u;
/// Salt of the decision stream's seed under adaptive sampling (sampleStreamInit).
const uint VKP_SOBOL_DECISION_SALT = 0x2545f491u;
/// Salt of the time's hash under `random` (sampleTime).
const uint VKP_TIME_SALT = 0x68e31da4u;

struct SampleStream {
    uint seed;    ///< per-pixel scramble seed (sobolPixelSeed)
    uint index;   ///< index of the sample in the pixel's sequence
    uint vertex;  ///< the vertex drawing now (dimension groups 2 vertex, 2 vertex + 1)
    uint pairs;   ///< 2D numbers drawn at this vertex so far
    uint singles; ///< 1D numbers drawn at this vertex so far
    uint rng;     ///< hashed RNG state (rng.h): `random`, and the fallback past the layout
};

/// The stream of sample `sampleIndex` of pixel `pixel` (linear index) for the render seed `seed`,
/// at the camera vertex. splitDecision (adaptive sampling, host/render/adaptive.h: sample i with
/// i mod 4 == 3 only steers): the image samples i = 4q + r, r < 3, take indices 3q + r of the
/// pixel's sequence, so they are a prefix of one Sobol' sequence, and the decision samples take
/// index q of an independently scrambled second sequence, so the steering numbers are independent
/// of the image's (the unbiasedness argument of adaptive.h needs that). The RNG fallback keeps
/// rngInit(pixel, sampleIndex, seed) in every case, i.e. `random` is unchanged.
VKP_FN SampleStream sampleStreamInit(uint pixel, uint sampleIndex, uint seed, bool splitDecision) {
    SampleStream s;
    s.seed = sobolPixelSeed(pixel, seed);
    s.index = sampleIndex;
    if (splitDecision) {
        uint q = sampleIndex >> 2u;
        uint r = sampleIndex & 3u;
        s.index = (r == 3u) ? q : 3u * q + r;
        if (r == 3u) s.seed = pcgHash(s.seed ^ VKP_SOBOL_DECISION_SALT);
    }
    s.vertex = 0u;
    s.pairs = 0u;
    s.singles = 0u;
    s.rng = rngInit(pixel, sampleIndex, seed);
    return s;
}

/// Start drawing the numbers of path vertex `vertex` (the path's depth after the ray that found it).
VKP_FN void sampleStartVertex(INOUT(SampleStream) s, uint vertex) {
    s.vertex = vertex;
    s.pairs = 0u;
    s.singles = 0u;
}

/// The next 1D number of the stream, in [0,1).
VKP_FN float sampleNext(INOUT(SampleStream) s) {
    if (VKP_SEQUENCE_SOBOL && s.vertex <= VKP_SOBOL_MAX_VERTEX && s.singles < 4u) {
        uint k = s.singles;
        s.singles += 1u;
        return sobolSampleDim23(s.seed, s.index, 2u * s.vertex + (k & 1u), 2u + (k >> 1u));
    }
    return rngNext(s.rng);
}

/// The next 2D number of the stream, in [0,1)^2.
VKP_FN vec2 sampleNext2(INOUT(SampleStream) s) {
    if (VKP_SEQUENCE_SOBOL && s.vertex <= VKP_SOBOL_MAX_VERTEX && s.pairs < 2u) {
        uint k = s.pairs;
        s.pairs += 1u;
        return sobolSample2(s.seed, s.index, 2u * s.vertex + k);
    }
    return rngNext2(s.rng);
}

/// The path's time in [0,1) for motion blur ("Ray Tracing: The Next Week", sec. 2: each camera ray
/// gets a random time, which its scattered and shadow rays keep), drawn at the camera vertex
/// without changing any other number of the stream, so a variant that draws it sees the same
/// numbers everywhere else as one that does not:
///   sobol  - the camera vertex's single 0 (group 0, dim 2), which nothing else draws: jointly
///            stratified with the jitter (group 0, dims 0-1), and the times of any aligned 2^m
///            samples of a pixel put one point in each interval [j 2^-m, (j+1) 2^-m);
///   random - a hash of the stream's RNG state and a salt; the state is not advanced.
/// Call it at the camera vertex before any other single is drawn there.
VKP_FN float sampleTime(INOUT(SampleStream) s) {
    if (VKP_SEQUENCE_SOBOL) return sampleNext(s);
    return float(pcgHash(pcgHash(s.rng + VKP_TIME_SALT)) >> 8u) * (1.0f / 16777216.0f);
}

VKP_END
#endif
