// Choosing a Vulkan device: a pure function over plain descriptions of the devices, so that every
// rule (and every refusal message) is unit-tested without a device (tests/unit/test_device_select).
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace vkp {

enum class DeviceKind { Other, Integrated, Discrete, Virtual, Cpu };

/// What vkpath needs to know about one physical device (filled from Vulkan by vk/context.cpp).
struct DeviceInfo {
    std::uint32_t index = 0;  ///< position in vkEnumeratePhysicalDevices
    std::string name;
    DeviceKind kind = DeviceKind::Other;
    std::string driverName;   ///< VkPhysicalDeviceDriverProperties::driverName (may be empty)
    std::string driverInfo;   ///< e.g. "Mesa 22.3.6 (LLVM 15.0.6)"
    std::uint32_t apiVersion = 0;  ///< VK_MAKE_API_VERSION encoded
    std::optional<std::uint32_t> computeQueueFamily;  ///< a family with VK_QUEUE_COMPUTE_BIT
    std::uint32_t maxTexelBufferElements = 0;
    std::uint32_t maxUniformBufferRange = 0;
    std::uint32_t maxStorageBufferRange = 0;  ///< bytes one storage-buffer binding may span
    std::uint32_t maxPushConstantsSize = 0;
    std::uint32_t maxComputeWorkGroupInvocations = 0;
    /// Descriptors one compute stage may use, by kind (Vulkan guarantees at least 12 uniform
    /// buffers, 4 storage buffers, 16 sampled images, which uniform texel buffers count against,
    /// and 128 resources in all): checked against the kernel's bindings by fitProblem.
    std::uint32_t maxPerStageDescriptorUniformBuffers = 0;
    std::uint32_t maxPerStageDescriptorStorageBuffers = 0;
    std::uint32_t maxPerStageDescriptorSampledImages = 0;
    std::uint32_t maxPerStageResources = 0;
    std::uint32_t maxComputeWorkGroupSize[2] = {0, 0};   ///< x, y
    std::uint32_t maxComputeWorkGroupCount[2] = {0, 0};  ///< x, y
    std::uint32_t subgroupSize = 0;  ///< VkPhysicalDeviceSubgroupProperties::subgroupSize (0: not reported)
    std::uint64_t maxMemoryAllocationSize = 0;  ///< bytes of one allocation (Vulkan 1.1; 0: not reported)
    std::uint64_t deviceLocalBytes = 0;         ///< size of the largest device-local memory heap
    /// Device-local memory that the host maps (host-visible, coherent, cached: unified memory, as
    /// lavapipe's and integrated GPUs'); false: buffers are reached through staging copies
    /// (vk/memory_choice.h, for a buffer that may take any memory type).
    bool mappedBuffers = false;
    bool hasTexelFormat = false;  ///< R32G32B32A32_UINT usable as a uniform texel buffer
    bool bufferDeviceAddress = false;  ///< VkPhysicalDeviceVulkan12Features::bufferDeviceAddress (optional)
    /// The compute family's timestampValidBits (0: no timestamps there) and the device's
    /// timestampPeriod, nanoseconds per tick: what Renderer times its dispatches with.
    std::uint32_t timestampValidBits = 0;
    double timestampPeriodNs = 0.0;
};

/// Empty if the device can run vkpath, else the reason it cannot (one short phrase).
std::string unusableReason(const DeviceInfo& d);

/// Preference order when no device is named: discrete > integrated > virtual > CPU > other.
int kindRank(DeviceKind k);
const char* kindName(DeviceKind k);
std::string apiVersionString(std::uint32_t v);

struct DeviceChoice {
    std::optional<std::uint32_t> index;  ///< the chosen device, if any
    std::string error;                   ///< why none was chosen (one line), if index is empty
};

/// Pick a device. selector: "" (the most capable usable device), a decimal index ("1"), or a
/// case-insensitive substring of the device name ("llvmpipe"). Never throws.
DeviceChoice selectDevice(const std::vector<DeviceInfo>& devices, const std::string& selector);

}  // namespace vkp
