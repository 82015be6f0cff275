#include "render/render_key.h"

#include <cstdio>
#include <cstring>

#include "core/fnv1a.h"
#include "pathtrace.spv.h"

namespace vkp {

namespace {
std::string number(double v) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.9g", v);
    return buf;
}
}  // namespace

RenderKey renderKey(const GpuArrays& arrays, const RenderOptions& options) {
    RenderKey k;
    auto add = [&](const char* name, std::string value) { k.entries.emplace_back(name, std::move(value)); };
    add("vkpath", VKPATH_VERSION);
    add("size", std::to_string(arrays.width) + "x" + std::to_string(arrays.height));
    add("seed", std::to_string(arrays.frame.size.w));
    add("max depth", std::to_string(arrays.frame.size.z));
    add("rr depth", std::to_string(arrays.frame.counts.y));
    add("sampler", samplerName(options.sampler));
    add("sequence", sequenceName(options.sequence));
    add("light pick", lightPickName(options.lightPick));
    add("light sampling", lightSamplingName(options.lightSampling));
    add("solid-angle min", number(options.solidAngleMinSize));
    add("adaptive", options.adaptive() ? number(options.adaptiveThreshold) + " from " + std::to_string(options.adaptiveMinSpp) + " spp" : "off");
    add("variant", options.fullVariant ? "full" : "auto");
    add("aov", options.aov ? "on" : "off");  // the sums of the feature images are part of the state
    Fnv1a kernel;  // the kernel's code: a build with other shaders takes other samples
    kernel.add(std::as_bytes(std::span<const std::uint32_t>(kPathtraceSpv, sizeof(kPathtraceSpv) / sizeof(kPathtraceSpv[0]))));
    char kernelHex[24];
    std::snprintf(kernelHex, sizeof kernelHex, "%016llx", static_cast<unsigned long long>(kernel.h));
    add("kernel", kernelHex);
    Fnv1a h;  // nothing in the arrays depends on the workgroup size or the tile order (speed options)
    for (const KernelBinding& b : kKernelBindings) {
        if (b.binding == VKP_BINDING_ACTIVE) continue;  // the first active-pixel list: every pixel
        const std::span<const std::byte> data = arrays.hostData(b.binding);
        h.add(b.binding);
        h.add(data.size());
        h.add(data);
    }
    char hex[24];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h.h));
    add("scene", hex);
    return k;
}

std::string keyMismatch(const RenderKey& have, const RenderKey& want) {
    for (const auto& [name, value] : want.entries) {
        const std::string* other = nullptr;
        for (const auto& e : have.entries)
            if (e.first == name) other = &e.second;
        if (!other) return name + " is missing in it";
        if (*other != value) {
            if (name == "scene") return "the scene's content differs (hash " + *other + " in it, " + value + " here)";
            return name + " is " + *other + " in it, " + value + " here";
        }
    }
    for (const auto& e : have.entries) {
        bool known = false;
        for (const auto& w : want.entries) known = known || w.first == e.first;
        if (!known) return e.first + " is unknown here";
    }
    return {};
}

}  // namespace vkp
