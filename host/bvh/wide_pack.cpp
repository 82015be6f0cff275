#include "bvh/wide_pack.h"

namespace vkp {
namespace {

/// Children [first, first + 4) of a wide node into the GpuWideNode n.
template <std::size_t N>
void packFour(const std::array<WideChild, N>& children, std::size_t first, gpu::GpuWideNode& n) {
    for (int k = 0; k < 4; ++k) {
        const WideChild& c = children[first + std::size_t(k)];
        const Aabb box = c.empty() ? Aabb{} : c.box;
        n.loX[k] = box.lo.x;
        n.loY[k] = box.lo.y;
        n.loZ[k] = box.lo.z;
        n.hiX[k] = box.hi.x;
        n.hiY[k] = box.hi.y;
        n.hiZ[k] = box.hi.z;
        n.index[k] = c.index;
        n.count[k] = c.count;
    }
}

}  // namespace

std::vector<gpu::GpuWideNode> packWide(const WideTree& tree) {
    std::vector<gpu::GpuWideNode> out(tree.nodes.size());
    for (std::size_t i = 0; i < tree.nodes.size(); ++i) packFour(tree.nodes[i], 0, out[i]);
    return out;
}

std::vector<gpu::GpuWideNode> packWide8(const WideTreeOf<8>& tree) {
    std::vector<gpu::GpuWideNode> out(2 * tree.nodes.size());
    for (std::size_t i = 0; i < tree.nodes.size(); ++i) {
        packFour(tree.nodes[i], 0, out[2 * i]);
        packFour(tree.nodes[i], 4, out[2 * i + 1]);
    }
    return out;
}

}  // namespace vkp
