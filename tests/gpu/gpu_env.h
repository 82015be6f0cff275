// The shared Vulkan set-up of the GPU tests: one instance with the validation layer on, and the
// default device. Any validation message fails the test that caused it (see checkValidation).
// Without a usable device the tests are skipped with the reason; in CI (CI=true) the gtest main of
// the gpu and stress executables turns every skip into a failure (tests/support/test_main.cpp).
#pragma once
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "vk/device.h"

namespace vkp::test {

class GpuEnv {
public:
    /// The process-wide device, or nullptr with reason() set.
    static GpuEnv& get();
    VulkanDevice* device() { return device_.get(); }
    VulkanInstance* instance() { return instance_.get(); }
    const std::string& reason() const { return reason_; }

private:
    GpuEnv();
    std::unique_ptr<VulkanInstance> instance_;
    std::unique_ptr<VulkanDevice> device_;
    std::string reason_;
};

}  // namespace vkp::test

/// Use at the top of a GPU test: gives `dev` (VulkanDevice&), or skips with the reason (which
/// fails in CI, see the file comment).
#define VKP_REQUIRE_DEVICE(dev)                                                      \
    auto* dev##_ptr = ::vkp::test::GpuEnv::get().device();                           \
    if (!dev##_ptr) GTEST_SKIP() << "no Vulkan device: " << ::vkp::test::GpuEnv::get().reason(); \
    ::vkp::VulkanDevice& dev = *dev##_ptr
