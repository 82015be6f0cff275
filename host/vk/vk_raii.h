// The one place that includes Vulkan-Hpp's RAII header (expensive to compile: include it only
// from host/vk and host/render implementation files and their headers).
#pragma once
#include <vulkan/vulkan_raii.hpp>
