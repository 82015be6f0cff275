#include "vk/device_select.h"

#include <algorithm>
#include <cctype>
#include <sstream>

namespace vkp {

namespace {
constexpr std::uint32_t kApi12 = (1u << 22) | (2u << 12);  // VK_MAKE_API_VERSION(0, 1, 2, 0)

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

bool isIndex(const std::string& s) {
    return !s.empty() && s.size() < 6 && std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isdigit(c); });
}

std::string refusalList(const std::vector<DeviceInfo>& devices, const std::vector<std::uint32_t>& which) {
    std::ostringstream os;
    for (std::size_t i = 0; i < which.size(); ++i) {
        const DeviceInfo& d = devices[which[i]];
        os << (i ? "; " : "") << "device " << d.index << " (" << d.name << "): " << unusableReason(d);
    }
    return os.str();
}
}  // namespace

std::string unusableReason(const DeviceInfo& d) {
    if (d.apiVersion < kApi12) return "Vulkan " + apiVersionString(d.apiVersion) + " < 1.2";
    if (!d.computeQueueFamily) return "no compute queue";
    if (!d.hasTexelFormat) return "R32G32B32A32_UINT texel buffers not supported";
    if (d.maxTexelBufferElements < (1u << 16)) return "maxTexelBufferElements < 65536";
    if (d.maxUniformBufferRange < 16384) return "maxUniformBufferRange < 16384";
    if (d.maxPushConstantsSize < 128) return "maxPushConstantsSize < 128";
    return {};
}

int kindRank(DeviceKind k) {
    switch (k) {
        case DeviceKind::Discrete: return 4;
        case DeviceKind::Integrated: return 3;
        case DeviceKind::Virtual: return 2;
        case DeviceKind::Cpu: return 1;
        default: return 0;
    }
}

const char* kindName(DeviceKind k) {
    switch (k) {
        case DeviceKind::Discrete: return "discrete GPU";
        case DeviceKind::Integrated: return "integrated GPU";
        case DeviceKind::Virtual: return "virtual GPU";
        case DeviceKind::Cpu: return "CPU";
        default: return "other";
    }
}

std::string apiVersionString(std::uint32_t v) {
    return std::to_string((v >> 22) & 0x7fu) + "." + std::to_string((v >> 12) & 0x3ffu) + "." + std::to_string(v & 0xfffu);
}

DeviceChoice selectDevice(const std::vector<DeviceInfo>& devices, const std::string& selector) {
    DeviceChoice out;
    if (devices.empty()) {
        out.error = "no Vulkan device found (install a driver: apt-get install mesa-vulkan-drivers)";
        return out;
    }
    std::vector<std::uint32_t> candidates;
    if (selector.empty()) {
        for (std::uint32_t i = 0; i < devices.size(); ++i) candidates.push_back(i);
    } else if (isIndex(selector)) {
        std::uint32_t i = std::uint32_t(std::stoul(selector));
        if (i >= devices.size()) {
            out.error = "--device " + selector + ": no such device (there are " + std::to_string(devices.size()) +
                        "; see 'vkpath devices')";
            return out;
        }
        candidates.push_back(i);
    } else {
        const std::string want = lower(selector);
        for (std::uint32_t i = 0; i < devices.size(); ++i)
            if (lower(devices[i].name).find(want) != std::string::npos) candidates.push_back(i);
        if (candidates.empty()) {
            out.error = "--device '" + selector + "': no device name contains it (see 'vkpath devices')";
            return out;
        }
    }
    std::optional<std::uint32_t> best;
    for (std::uint32_t i : candidates) {
        if (!unusableReason(devices[i]).empty()) continue;
        if (!best || kindRank(devices[i].kind) > kindRank(devices[*best].kind)) best = i;
    }
    if (!best) {
        out.error = "no suitable Vulkan device: " + refusalList(devices, candidates);
        return out;
    }
    out.index = best;
    return out;
}

}  // namespace vkp
