// Device selection is a pure function: every rule and every refusal message, without a device.
#include <gtest/gtest.h>

#include "vk/device_select.h"

namespace vkp {
namespace {

DeviceInfo dev(std::uint32_t index, const std::string& name, DeviceKind kind) {
    DeviceInfo d;
    d.index = index;
    d.name = name;
    d.kind = kind;
    d.apiVersion = (1u << 22) | (3u << 12);
    d.computeQueueFamily = 0;
    d.maxTexelBufferElements = 1u << 27;
    d.maxUniformBufferRange = 65536;
    d.maxPushConstantsSize = 128;
    d.hasTexelFormat = true;
    return d;
}

TEST(DeviceSelect, PrefersDiscreteThenIntegratedThenVirtualThenCpu) {
    std::vector<DeviceInfo> ds = {dev(0, "llvmpipe", DeviceKind::Cpu), dev(1, "virgl", DeviceKind::Virtual),
                                  dev(2, "Intel UHD", DeviceKind::Integrated), dev(3, "RTX", DeviceKind::Discrete)};
    EXPECT_EQ(selectDevice(ds, "").index, 3u);
    ds.pop_back();
    EXPECT_EQ(selectDevice(ds, "").index, 2u);
    ds.pop_back();
    EXPECT_EQ(selectDevice(ds, "").index, 1u);
    ds.pop_back();
    EXPECT_EQ(selectDevice(ds, "").index, 0u);
}

TEST(DeviceSelect, SkipsUnusableDevicesWhenChoosingByDefault) {
    std::vector<DeviceInfo> ds = {dev(0, "llvmpipe", DeviceKind::Cpu), dev(1, "old GPU", DeviceKind::Discrete)};
    ds[1].apiVersion = (1u << 22) | (1u << 12);
    const DeviceChoice c = selectDevice(ds, "");
    ASSERT_TRUE(c.index);
    EXPECT_EQ(*c.index, 0u);
}

TEST(DeviceSelect, ByIndexAndByNameSubstring) {
    std::vector<DeviceInfo> ds = {dev(0, "llvmpipe (LLVM 15)", DeviceKind::Cpu), dev(1, "AMD Radeon", DeviceKind::Discrete)};
    EXPECT_EQ(selectDevice(ds, "0").index, 0u);
    EXPECT_EQ(selectDevice(ds, "LLVMPIPE").index, 0u);
    EXPECT_EQ(selectDevice(ds, "radeon").index, 1u);
}

TEST(DeviceSelect, ExplainsEveryRefusal) {
    std::vector<DeviceInfo> ds = {dev(0, "llvmpipe", DeviceKind::Cpu)};
    EXPECT_FALSE(selectDevice({}, "").index);
    EXPECT_NE(selectDevice({}, "").error.find("apt-get install mesa-vulkan-drivers"), std::string::npos);
    EXPECT_NE(selectDevice(ds, "7").error.find("no such device"), std::string::npos);
    EXPECT_NE(selectDevice(ds, "nvidia").error.find("no device name contains it"), std::string::npos);

    ds[0].computeQueueFamily.reset();
    DeviceChoice c = selectDevice(ds, "");
    EXPECT_FALSE(c.index);
    EXPECT_NE(c.error.find("device 0 (llvmpipe): no compute queue"), std::string::npos) << c.error;
    ds[0] = dev(0, "llvmpipe", DeviceKind::Cpu);
    ds[0].apiVersion = (1u << 22) | (1u << 12);
    EXPECT_NE(selectDevice(ds, "0").error.find("Vulkan 1.1.0 < 1.2"), std::string::npos);
    ds[0] = dev(0, "llvmpipe", DeviceKind::Cpu);
    ds[0].hasTexelFormat = false;
    EXPECT_NE(selectDevice(ds, "").error.find("texel buffers"), std::string::npos);
}

TEST(DeviceSelect, ApiVersionString) { EXPECT_EQ(apiVersionString((1u << 22) | (3u << 12) | 230u), "1.3.230"); }

}  // namespace
}  // namespace vkp
