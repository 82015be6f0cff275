#include "bvh/wide_pack.h"

namespace vkp {

std::vector<gpu::GpuWideNode> packWide(const WideTree& tree) {
    std::vector<gpu::GpuWideNode> out(tree.nodes.size());
    for (std::size_t i = 0; i < tree.nodes.size(); ++i) {
        gpu::GpuWideNode& n = out[i];
        for (int k = 0; k < 4; ++k) {
            const WideChild& c = tree.nodes[i][std::size_t(k)];
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
    return out;
}

}  // namespace vkp
