#include "vk/instance.h"

#include <dlfcn.h>
#include <link.h>

#include <algorithm>
#include <cstring>
#include <string>

#include "core/errors.h"
#include "vk/memory_choice.h"

namespace vkp {

namespace {
const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

VKAPI_ATTR VkBool32 VKAPI_CALL onValidationMessage(VkDebugUtilsMessageSeverityFlagBitsEXT,
                                                   VkDebugUtilsMessageTypeFlagsEXT,
                                                   const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                   void* user) {
    auto* log = static_cast<ValidationLog*>(user);
    log->count.fetch_add(1);
    std::lock_guard<std::mutex> lock(log->mutex);
    if (log->messages.size() < 8) log->messages.emplace_back(data && data->pMessage ? data->pMessage : "(no text)");
    return VK_FALSE;
}

DeviceKind kindOf(vk::PhysicalDeviceType t) {
    switch (t) {
        case vk::PhysicalDeviceType::eDiscreteGpu: return DeviceKind::Discrete;
        case vk::PhysicalDeviceType::eIntegratedGpu: return DeviceKind::Integrated;
        case vk::PhysicalDeviceType::eVirtualGpu: return DeviceKind::Virtual;
        case vk::PhysicalDeviceType::eCpu: return DeviceKind::Cpu;
        default: return DeviceKind::Other;
    }
}
/// Checks that the Vulkan loader vk::raii::Context will open has the entry points the Context calls
/// as soon as it is made: a library named libvulkan.so.1 without them (an empty stub on
/// LD_LIBRARY_PATH, a broken install) would otherwise be a call through a null pointer. Opens the
/// library as Vulkan-Hpp's DynamicLoader does (libvulkan.so, then libvulkan.so.1). Throws
/// DeviceError "no Vulkan loader: ..." when there is none, "no usable Vulkan loader: ..." when
/// it lacks an entry point.
void checkLoader() {
    void* lib = dlopen("libvulkan.so", RTLD_NOW | RTLD_LOCAL);
    if (!lib) lib = dlopen("libvulkan.so.1", RTLD_NOW | RTLD_LOCAL);
    if (!lib) throw DeviceError("no Vulkan loader: libvulkan.so.1 could not be opened (apt-get install libvulkan1 mesa-vulkan-drivers)");
    std::string name = "libvulkan.so.1";
    link_map* map = nullptr;
    if (dlinfo(lib, RTLD_DI_LINKMAP, &map) == 0 && map && map->l_name && *map->l_name) name = map->l_name;
    std::string missing;
    auto gipa = reinterpret_cast<PFN_vkGetInstanceProcAddr>(dlsym(lib, "vkGetInstanceProcAddr"));
    if (!gipa) missing = "vkGetInstanceProcAddr";
    for (const char* f : {"vkCreateInstance", "vkEnumerateInstanceLayerProperties", "vkEnumerateInstanceExtensionProperties"})
        if (missing.empty() && !gipa(nullptr, f)) missing = f;
    dlclose(lib);
    if (!missing.empty())
        throw DeviceError("no usable Vulkan loader: " + name + " has no " + missing +
                          " (is a stub or another library named libvulkan on LD_LIBRARY_PATH? apt-get install libvulkan1)");
}
}  // namespace

DeviceInfo describeDevice(const vk::raii::PhysicalDevice& pd, std::uint32_t index) {
    DeviceInfo d;
    d.index = index;
    const vk::PhysicalDeviceProperties props = pd.getProperties();
    d.name = props.deviceName.data();
    d.kind = kindOf(props.deviceType);
    d.apiVersion = props.apiVersion;
    d.maxTexelBufferElements = props.limits.maxTexelBufferElements;
    d.maxUniformBufferRange = props.limits.maxUniformBufferRange;
    d.maxStorageBufferRange = props.limits.maxStorageBufferRange;
    d.maxPushConstantsSize = props.limits.maxPushConstantsSize;
    d.maxComputeWorkGroupInvocations = props.limits.maxComputeWorkGroupInvocations;
    d.maxPerStageDescriptorUniformBuffers = props.limits.maxPerStageDescriptorUniformBuffers;
    d.maxPerStageDescriptorStorageBuffers = props.limits.maxPerStageDescriptorStorageBuffers;
    d.maxPerStageDescriptorSampledImages = props.limits.maxPerStageDescriptorSampledImages;
    d.maxPerStageResources = props.limits.maxPerStageResources;
    d.maxComputeWorkGroupSize[0] = props.limits.maxComputeWorkGroupSize[0];
    d.maxComputeWorkGroupSize[1] = props.limits.maxComputeWorkGroupSize[1];
    d.maxComputeWorkGroupCount[0] = props.limits.maxComputeWorkGroupCount[0];
    d.maxComputeWorkGroupCount[1] = props.limits.maxComputeWorkGroupCount[1];
    const vk::PhysicalDeviceMemoryProperties mem = pd.getMemoryProperties();
    for (std::uint32_t i = 0; i < mem.memoryHeapCount; ++i)
        if (mem.memoryHeaps[i].flags & vk::MemoryHeapFlagBits::eDeviceLocal)
            d.deviceLocalBytes = std::max<std::uint64_t>(d.deviceLocalBytes, mem.memoryHeaps[i].size);
    if (const std::optional<BufferMemoryChoice> c = chooseBufferMemory(mem, ~0u, true)) d.mappedBuffers = c->mapped;
    if (props.apiVersion >= VK_API_VERSION_1_2) {
        auto chain = pd.getProperties2<vk::PhysicalDeviceProperties2, vk::PhysicalDeviceDriverProperties,
                                       vk::PhysicalDeviceMaintenance3Properties, vk::PhysicalDeviceSubgroupProperties>();
        const auto& drv = chain.get<vk::PhysicalDeviceDriverProperties>();
        d.driverName = drv.driverName.data();
        d.driverInfo = drv.driverInfo.data();
        d.maxMemoryAllocationSize = chain.get<vk::PhysicalDeviceMaintenance3Properties>().maxMemoryAllocationSize;
        d.subgroupSize = chain.get<vk::PhysicalDeviceSubgroupProperties>().subgroupSize;
        auto features = pd.getFeatures2<vk::PhysicalDeviceFeatures2, vk::PhysicalDeviceVulkan12Features>();
        d.bufferDeviceAddress = features.get<vk::PhysicalDeviceVulkan12Features>().bufferDeviceAddress;
    }
    const auto families = pd.getQueueFamilyProperties();
    for (std::uint32_t i = 0; i < families.size(); ++i) {
        if (families[i].queueFlags & vk::QueueFlagBits::eCompute) {
            d.computeQueueFamily = i;
            d.timestampValidBits = families[i].timestampValidBits;
            d.timestampPeriodNs = props.limits.timestampPeriod;
            break;
        }
    }
    const vk::FormatProperties fp = pd.getFormatProperties(vk::Format::eR32G32B32A32Uint);
    d.hasTexelFormat = bool(fp.bufferFeatures & vk::FormatFeatureFlagBits::eUniformTexelBuffer);
    return d;
}

VulkanInstance::VulkanInstance(bool validate) : validate_(validate), log_(std::make_unique<ValidationLog>()) {
    checkLoader();
    try {
        context_ = std::make_unique<vk::raii::Context>();
    } catch (const std::exception&) {
        throw DeviceError("no Vulkan loader: libvulkan.so.1 could not be opened (apt-get install libvulkan1 mesa-vulkan-drivers)");
    }
    std::vector<const char*> layers;
    std::vector<const char*> extensions;
    if (validate_) {
        bool found = false;
        for (const auto& l : context_->enumerateInstanceLayerProperties())
            if (std::strcmp(l.layerName.data(), kValidationLayer) == 0) found = true;
        if (!found)
            throw DeviceError("--validate: VK_LAYER_KHRONOS_validation is not installed (apt-get install vulkan-validationlayers)");
        layers.push_back(kValidationLayer);
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    }
    vk::ApplicationInfo app{};
    app.pApplicationName = "vkpath";
    app.pEngineName = "vkpath";
    app.apiVersion = VK_API_VERSION_1_2;
    vk::InstanceCreateInfo ci{};
    ci.pApplicationInfo = &app;
    ci.enabledLayerCount = std::uint32_t(layers.size());
    ci.ppEnabledLayerNames = layers.data();
    ci.enabledExtensionCount = std::uint32_t(extensions.size());
    ci.ppEnabledExtensionNames = extensions.data();
    vk::DebugUtilsMessengerCreateInfoEXT mci{};
    mci.messageSeverity = vk::DebugUtilsMessageSeverityFlagBitsEXT::eWarning | vk::DebugUtilsMessageSeverityFlagBitsEXT::eError;
    mci.messageType = vk::DebugUtilsMessageTypeFlagBitsEXT::eGeneral | vk::DebugUtilsMessageTypeFlagBitsEXT::eValidation |
                      vk::DebugUtilsMessageTypeFlagBitsEXT::ePerformance;
    mci.pfnUserCallback = &onValidationMessage;
    mci.pUserData = log_.get();
    if (validate_) ci.pNext = &mci;  // also reports problems during instance creation
    try {
        instance_ = vk::raii::Instance(*context_, ci);
    } catch (const vk::IncompatibleDriverError&) {
        throw DeviceError("no Vulkan driver: the loader found no driver (ICD) for Vulkan 1.2 (apt-get install mesa-vulkan-drivers)");
    } catch (const vk::SystemError& e) {
        throw DeviceError(std::string("cannot create a Vulkan instance: ") + e.what() + " (apt-get install mesa-vulkan-drivers)");
    }
    if (validate_) messenger_ = vk::raii::DebugUtilsMessengerEXT(instance_, mci);
    try {
        vk::raii::PhysicalDevices pds(instance_);
        for (auto& pd : pds) physical_.push_back(std::move(pd));
    } catch (const vk::SystemError& e) {
        throw DeviceError(std::string("cannot list Vulkan devices: ") + e.what() + " (apt-get install mesa-vulkan-drivers)");
    }
    for (std::uint32_t i = 0; i < physical_.size(); ++i) infos_.push_back(describeDevice(physical_[i], i));
}

void VulkanInstance::throwIfValidationMessages(const std::string& when) const {
    if (!validate_ || log_->count.load() == 0) return;
    std::lock_guard<std::mutex> lock(log_->mutex);
    std::string first = log_->messages.empty() ? std::string("?") : log_->messages.front();
    for (char& c : first)
        if (c == '\n') c = ' ';
    throw VulkanError("validation layer reported " + std::to_string(log_->count.load()) + " message(s) " + when + "; first: " + first);
}

}  // namespace vkp
