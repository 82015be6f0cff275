// The Vulkan loader, instance and (optionally) the validation layer, plus descriptions of every
// physical device. Compute only: no window-system or surface extension is ever enabled.
#pragma once
#include <atomic>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "vk/device_select.h"
#include "vk/vk_raii.h"

namespace vkp {

/// Messages from VK_LAYER_KHRONOS_validation; with --validate any message is an error.
struct ValidationLog {
    std::atomic<std::uint32_t> count{0};
    std::mutex mutex;
    std::vector<std::string> messages;  ///< the first few, for the error line
};

class VulkanInstance {
public:
    /// Opens the loader (libvulkan.so.1) and creates a Vulkan 1.2 instance. validate: enable
    /// VK_LAYER_KHRONOS_validation and a messenger that records warnings and errors.
    /// Throws DeviceError saying which of "no loader / no driver / no layer" it is and how to fix it.
    explicit VulkanInstance(bool validate);

    const std::vector<DeviceInfo>& devices() const { return infos_; }
    vk::raii::PhysicalDevice& physicalDevice(std::uint32_t index) { return physical_[index]; }
    vk::raii::Instance& instance() { return instance_; }
    bool validating() const { return validate_; }
    ValidationLog& validationLog() { return *log_; }
    /// Throws VulkanError with the first message if the validation layer said anything.
    void throwIfValidationMessages(const std::string& when) const;

private:
    bool validate_;
    std::unique_ptr<ValidationLog> log_;
    std::unique_ptr<vk::raii::Context> context_;
    vk::raii::Instance instance_{nullptr};
    vk::raii::DebugUtilsMessengerEXT messenger_{nullptr};
    std::vector<vk::raii::PhysicalDevice> physical_;
    std::vector<DeviceInfo> infos_;
};

/// Describe one physical device for selectDevice().
DeviceInfo describeDevice(const vk::raii::PhysicalDevice& pd, std::uint32_t index);

}  // namespace vkp
