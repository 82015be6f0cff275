#include "bvh/wide_collapse.h"

#include <stdexcept>
#include <string>

namespace vkp {
namespace {

using gpu::GpuNode;

glm::vec3 xyz(const glm::vec4& v) { return glm::vec3(v.x, v.y, v.z); }

/// The two child slots of binary node `n` (inner children keep their FlatBvh node index).
std::array<WideChild, 2> binaryChildren(const GpuNode& n) {
    std::array<WideChild, 2> c;
    const glm::vec4* lo[2] = {&n.a, &n.c};
    const glm::vec4* hi[2] = {&n.b, &n.d};
    for (int k = 0; k < 2; ++k) {
        c[k].index = gpu::floatBitsToUint(lo[k]->w);
        c[k].count = gpu::floatBitsToUint(hi[k]->w);
        if (c[k].empty()) continue;  // keeps the default (empty) box
        c[k].box.lo = xyz(*lo[k]);
        c[k].box.hi = xyz(*hi[k]);
    }
    return c;
}

template <std::size_t N>
struct Collapser {
    const FlatBvh& bvh;
    WideTreeOf<N> out;

    const GpuNode& node(std::uint32_t i) const {
        if (i >= bvh.nodes.size())
            throw std::invalid_argument("collapseToWide: node index " + std::to_string(i) + " out of range");
        return bvh.nodes[i];
    }

    /// Wide node for binary node `b` (its children, opened greedily); returns its index.
    std::uint32_t emit(std::uint32_t b, std::uint32_t depth) {
        std::vector<WideChild> slots;
        for (const WideChild& c : binaryChildren(node(b)))
            if (!c.empty()) slots.push_back(c);
        while (slots.size() < N) {
            int best = -1;
            float bestArea = -1.0f;
            for (std::size_t k = 0; k < slots.size(); ++k)
                if (slots[k].isInner() && slots[k].box.halfArea() > bestArea) {
                    bestArea = slots[k].box.halfArea();
                    best = int(k);
                }
            if (best < 0) break;
            const std::array<WideChild, 2> kids = binaryChildren(node(slots[std::size_t(best)].index));
            slots.erase(slots.begin() + best);
            int at = best;
            for (const WideChild& c : kids)
                if (!c.empty()) slots.insert(slots.begin() + at++, c);
        }
        const auto self = std::uint32_t(out.nodes.size());
        out.nodes.emplace_back();
        out.maxDepth = std::max(out.maxDepth, depth);
        for (std::size_t k = 0; k < slots.size(); ++k) {
            WideChild c = slots[k];
            if (c.isLeaf() && std::uint64_t(c.index) + c.count > bvh.prims.size())
                throw std::invalid_argument("collapseToWide: leaf range out of range");
            if (c.isInner()) c.index = emit(c.index, depth + 1);
            out.nodes[self][k] = c;
        }
        return self;
    }
};

}  // namespace

template <std::size_t N>
WideTreeOf<N> collapseToWideOf(const FlatBvh& bvh) {
    Collapser<N> c{bvh, {}};
    if (bvh.nodes.empty()) {
        c.out.nodes.emplace_back();
        return c.out;
    }
    c.emit(0, 0);
    return c.out;
}

template WideTreeOf<4> collapseToWideOf<4>(const FlatBvh& bvh);
template WideTreeOf<8> collapseToWideOf<8>(const FlatBvh& bvh);

}  // namespace vkp
