#include "gpu_env.h"

namespace vkp::test {

GpuEnv::GpuEnv() {
    try {
        instance_ = std::make_unique<VulkanInstance>(/*validate=*/true);
        device_ = std::make_unique<VulkanDevice>(*instance_, "");
    } catch (const std::exception& e) {
        reason_ = e.what();
        device_.reset();
    }
}

GpuEnv& GpuEnv::get() {
    static GpuEnv env;
    return env;
}

}  // namespace vkp::test
