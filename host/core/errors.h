// Error types and the process exit codes they map to (README "Exit codes").
#pragma once
#include <stdexcept>
#include <string>

namespace vkp {

/// Exit codes of the vkpath command.
enum ExitCode : int {
    kExitOk = 0,
    kExitBadInput = 1,   ///< bad input file or usage
    kExitNoDevice = 2,   ///< no Vulkan loader, driver, device or no suitable device
    kExitVulkan = 3,     ///< Vulkan failure at run time
};

/// Bad input: a scene, an image, a flag. what() is one line, starting with the file name and the
/// place in it (a JSON pointer, a glTF mesh/accessor), e.g. "scene.json: /objects/3/radius: must be > 0".
struct InputError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// No usable Vulkan device. what() says which case (no loader, no driver, no device, none suitable)
/// and how to fix it.
struct DeviceError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// A Vulkan call failed while rendering (device lost, out of memory, validation message...).
struct VulkanError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

}  // namespace vkp
