// Packing of 4-wide nodes into the quantized layout of shaders/tests/wide_quantized.h (a lever of
// the layout micro-benchmark, issue 18). Every packed node is decoded with the kernel's own decode
// and checked to contain the original children's boxes.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

#include <glm/glm.hpp>

#include "shared/wide_bvh.h"
#include "tests/wide_quantized.h"

namespace vkp::test {

/// Packs 4-wide nodes (same order) into quantized ones (QUANTIZED_NODE_TEXELS texels each).
/// Throws std::runtime_error if a node cannot be quantized (a step out of float's range, a leaf
/// of more than 255 primitives) or a decoded box would not contain its child's.
inline std::vector<glm::uvec4> packWideQuantized(const std::vector<gpu::GpuWideNode>& nodes) {
    using gpu::quantizedCoordinate;
    std::vector<glm::uvec4> out(nodes.size() * gpu::QUANTIZED_NODE_TEXELS, glm::uvec4(0u));
    for (std::size_t i = 0; i < nodes.size(); ++i) {
        const gpu::GpuWideNode& n = nodes[i];
        const glm::vec4 lo[3] = {n.loX, n.loY, n.loZ}, hi[3] = {n.hiX, n.hiY, n.hiZ};
        glm::uvec4* t = &out[i * gpu::QUANTIZED_NODE_TEXELS];
        auto used = [&](int k) { return n.count[k] != 0 || n.index[k] != gpu::GPU_NODE_EMPTY; };
        for (int a = 0; a < 3; ++a) {
            float bmin = std::numeric_limits<float>::max(), bmax = -std::numeric_limits<float>::max();
            for (int k = 0; k < 4; ++k)
                if (used(k)) {
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
            const float step = gpu::quantizedStep(biased);
            t[0][a] = glm::floatBitsToUint(bmin);
            t[0].w |= biased << (8 * a);
            for (int k = 0; k < 4; ++k) {
                std::uint32_t ql = 255, qh = 0;  // an empty slot: inverted
                if (used(k)) {
                    ql = std::uint32_t(std::clamp(std::floor((double(lo[a][k]) - double(bmin)) / double(step)), 0.0, 255.0));
                    while (ql > 0 && quantizedCoordinate(bmin, ql, step) > lo[a][k]) --ql;
                    qh = std::uint32_t(std::clamp(std::ceil((double(hi[a][k]) - double(bmin)) / double(step)), 0.0, 255.0));
                    while (qh < 255 && quantizedCoordinate(bmin, qh, step) < hi[a][k]) ++qh;
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
        const gpu::GpuWideNode d = gpu::decodeQuantizedWideNode(t[0], t[1], t[2], t[3]);
        const glm::vec4 dlo[3] = {d.loX, d.loY, d.loZ}, dhi[3] = {d.hiX, d.hiY, d.hiZ};
        for (int k = 0; k < 4; ++k)
            for (int a = 0; a < 3; ++a)
                if (used(k) && !(dlo[a][k] <= lo[a][k] && dhi[a][k] >= hi[a][k]))
                    throw std::runtime_error("quantized node: a decoded box does not contain its child's");
    }
    return out;
}

}  // namespace vkp::test
