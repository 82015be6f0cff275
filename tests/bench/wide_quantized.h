// Quantized 4-wide nodes, a lever measured by the layout micro-benchmark (issue 18; compressed wide
// BVH nodes, Ylitie, Karras and Laine, "Efficient Incoherent Ray Traversal on GPUs Through
// Compressed Wide BVHs", HPG 2017, sec. 3.1): the same tree as GpuWideNode (shared/wide_bvh.h) in 4
// texels (64 bytes) instead of 8. Per node: the union box's min corner `origin` (floats) and a
// power-of-two step per axis; per child and axis an 8-bit lower and upper grid coordinate, so that
// lo = origin + qlo * step, hi = origin + qhi * step (one rounding: q * step is exact) contain the
// child's box. The kernel decodes a node into a GpuWideNode (shaders/tests/bvh_trace.comp,
// VKP_BVH_WIDE_QUANTIZED) and traverses it unchanged.
//   texel 0: origin.xyz (float bits); w: the steps' biased exponents (byte a = axis a, step 2^(e - 127))
//   texel 1: qlo per axis (x, y, z; byte k = child k); w: counts (byte k = child k's count)
//   texel 2: qhi per axis; w: 0
//   texel 3: index (child k's node or first primitive, as GpuWideNode::index)
// Empty slots: qlo 255, qhi 0 on every axis (inverted by 255 steps; every step is at least 2^-8 of
// the origin's magnitude and at least 2^-100, so an empty slot is never entered).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <vector>

#include <glm/glm.hpp>

#include "shared/wide_bvh.h"

namespace vkp::test {

constexpr std::uint32_t kQuantizedNodeTexels = 4;

inline float quantizedStep(std::uint32_t biasedExponent) {
    const std::uint32_t bits = biasedExponent << 23;
    float f;
    std::memcpy(&f, &bits, sizeof f);
    return f;
}
/// The decoded coordinate origin + q * step in float, as the kernel computes it.
inline float quantizedCoordinate(float origin, std::uint32_t q, float step) { return origin + float(q) * step; }

/// Packs 4-wide nodes (same order) into quantized ones; the decoded boxes contain the originals.
inline std::vector<glm::uvec4> packWideQuantized(const std::vector<gpu::GpuWideNode>& nodes) {
    std::vector<glm::uvec4> out(nodes.size() * kQuantizedNodeTexels, glm::uvec4(0u));
    for (std::size_t i = 0; i < nodes.size(); ++i) {
        const gpu::GpuWideNode& n = nodes[i];
        const glm::vec4 lo[3] = {n.loX, n.loY, n.loZ}, hi[3] = {n.hiX, n.hiY, n.hiZ};
        glm::uvec4* t = &out[i * kQuantizedNodeTexels];
        for (int a = 0; a < 3; ++a) {
            float bmin = std::numeric_limits<float>::max(), bmax = -std::numeric_limits<float>::max();
            for (int k = 0; k < 4; ++k)
                if (n.count[k] != 0 || n.index[k] != gpu::GPU_NODE_EMPTY) {
                    bmin = std::min(bmin, lo[a][k]);
                    bmax = std::max(bmax, hi[a][k]);
                }
            if (bmin > bmax) bmin = bmax = 0.0f;  // a node of empty slots only
            const double extent = std::max({double(bmax) - double(bmin), std::ldexp(std::fabs(double(bmin)), -8),
                                            std::ldexp(std::fabs(double(bmax)), -8), std::ldexp(1.0, -100)});
            int e = int(std::ceil(std::log2(extent / 255.0)));
            while (std::ldexp(255.0, e) < extent) ++e;
            if (e < -126 || e > 127) throw std::runtime_error("quantized node: step out of range");
            const std::uint32_t biased = std::uint32_t(e + 127);
            const float step = quantizedStep(biased);
            std::memcpy(&t[0][a], &bmin, sizeof bmin);
            t[0].w |= biased << (8 * a);
            for (int k = 0; k < 4; ++k) {
                std::uint32_t ql = 255, qh = 0;
                if (n.count[k] != 0 || n.index[k] != gpu::GPU_NODE_EMPTY) {
                    ql = std::uint32_t(std::clamp(std::floor((double(lo[a][k]) - double(bmin)) / double(step)), 0.0, 255.0));
                    while (ql > 0 && quantizedCoordinate(bmin, ql, step) > lo[a][k]) --ql;
                    qh = std::uint32_t(std::clamp(std::ceil((double(hi[a][k]) - double(bmin)) / double(step)), 0.0, 255.0));
                    while (qh < 255 && quantizedCoordinate(bmin, qh, step) < hi[a][k]) ++qh;
                    if (quantizedCoordinate(bmin, ql, step) > lo[a][k] || quantizedCoordinate(bmin, qh, step) < hi[a][k])
                        throw std::runtime_error("quantized node: a child box does not fit its grid");
                }
                t[1][a] |= ql << (8 * k);
                t[2][a] |= qh << (8 * k);
            }
        }
        for (int k = 0; k < 4; ++k) {
            if (n.count[k] > 255) throw std::runtime_error("quantized node: a leaf of more than 255 primitives");
            t[1].w |= n.count[k] << (8 * k);
        }
        t[3] = n.index;
    }
    return out;
}

}  // namespace vkp::test
