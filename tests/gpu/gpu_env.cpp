#include "gpu_env.h"

#include <cstdlib>
#include <cstring>

namespace vkp::test {

bool inCi() {
    const char* ci = std::getenv("CI");
    return ci && (std::strcmp(ci, "true") == 0 || std::strcmp(ci, "1") == 0);
}

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
