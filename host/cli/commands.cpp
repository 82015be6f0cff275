#include "cli/commands.h"

#include <chrono>
#include <cstdio>

#include "bvh/flatten.h"
#include "core/errors.h"
#include "render/features.h"
#include "render/renderer.h"
#include "render/session.h"
#include "scene/scene.h"
#include "vk/device.h"

namespace vkp {

namespace {
using Clock = std::chrono::steady_clock;

Scene loadWithOverrides(const CliArgs& a) {
    Scene s = loadSceneJson(a.scene);
    if (a.spp) s.render.spp = *a.spp;
    if (a.width) s.camera.width = *a.width;
    if (a.height) s.camera.height = *a.height;
    if (a.maxDepth) s.render.maxDepth = *a.maxDepth;
    if (a.seed) s.render.seed = *a.seed;
    return s;
}

std::size_t countShapes(const Scene& s, ShapeType t) {
    std::size_t n = 0;
    for (const Shape& sh : s.shapes) n += sh.type == t;
    return n;
}
}  // namespace

int runRender(const CliArgs& a, Clock::time_point processStart) {
    Scene scene = loadWithOverrides(a);
    std::vector<std::filesystem::path> outputs = a.outputs;
    if (outputs.empty()) outputs.push_back(a.scene.stem().string() + ".png");
    for (const auto& o : outputs) checkOutputPath(o);  // fail before the render, leave no file

    FlatBvh bvh = buildFlatBvh(scene);
    VulkanInstance instance(a.validate);
    VulkanDevice device(instance, a.device);
    RendererOptions ro;
    ro.sampler = a.sampler;
    ro.fullVariant = a.fullVariant;
    ro.samplesPerDispatch = a.samplesPerDispatch;
    Renderer renderer(device, scene, bvh, ro);
    if (!a.quiet)
        std::fprintf(stderr, "vkpath: %s, %ux%u, %u spp, device %s, variant %s\n", a.scene.string().c_str(),
                     scene.camera.width, scene.camera.height, scene.render.spp, device.info().name.c_str(),
                     renderer.features().name().c_str());

    SessionOptions so;
    so.spp = scene.render.spp;
    so.timeLimit = a.timeLimit;
    so.outputs = outputs;
    so.exposure = a.exposure;
    so.dumpEvery = a.dumpEvery;
    so.dumpDir = a.dumpDir;
    so.dumpFormats = a.dumpFormats;
    so.quiet = a.quiet;
    const SessionResult r = runSession(renderer, so, processStart);

    const double samples = double(r.spp) * double(r.pixels);
    const double rs = std::max(r.renderSeconds, 1e-9);
    std::fprintf(stderr,
                 "vkpath: %u spp in %.2f s (rendering %.2f s, first sample %.2f s): %.3f M samples/s, %.3f M rays/s, "
                 "%llu non-finite samples dropped\n",
                 r.spp, r.seconds, r.renderSeconds, r.firstBatchSeconds, samples / rs / 1e6, double(r.counters.rays) / rs / 1e6,
                 static_cast<unsigned long long>(r.counters.nonfinite));
    if (r.counters.loopGuard)
        std::fprintf(stderr, "vkpath: warning: %llu paths were cut short by the loop guard\n",
                     static_cast<unsigned long long>(r.counters.loopGuard));
    for (const auto& o : outputs) std::fprintf(stderr, "vkpath: wrote %s\n", o.string().c_str());
    return kExitOk;
}

int runInfo(const CliArgs& a) {
    const Scene scene = loadWithOverrides(a);
    const FlatBvh bvh = buildFlatBvh(scene);
    const Features f = sceneFeatures(scene, a.sampler);
    std::printf("scene        %s\n", a.scene.string().c_str());
    std::printf("image        %ux%u, %u spp, max depth %u, seed %u\n", scene.camera.width, scene.camera.height,
                scene.render.spp, scene.render.maxDepth, scene.render.seed);
    std::printf("primitives   %zu (%zu spheres, %zu quads, %zu triangles)\n", scene.shapes.size(),
                countShapes(scene, ShapeType::Sphere), countShapes(scene, ShapeType::Quad),
                countShapes(scene, ShapeType::Triangle));
    std::size_t emitters = 0;
    for (std::uint32_t l : scene.lights) emitters += scene.materials[scene.shapes[l].material].emits();
    std::printf("lights       %zu sampled objects (%zu emitting)\n", scene.lights.size(), emitters);
    std::printf("materials    %zu\n", scene.materials.size());
    std::printf("bvh          %zu nodes, %zu leaves, depth %u, SAH cost %.3f, built in %.2f ms\n", bvh.stats.nodeCount,
                bvh.stats.leafCount, bvh.stats.maxDepth, bvh.stats.sahCost, bvh.stats.buildMs);
    std::printf("variant      %s\n", f.name().c_str());
    return kExitOk;
}

int runDevices(const CliArgs& a) {
    VulkanInstance instance(a.validate);
    const auto& devs = instance.devices();
    if (devs.empty()) throw DeviceError("no Vulkan device found (install a driver: apt-get install mesa-vulkan-drivers)");
    const DeviceChoice def = selectDevice(devs, a.device);
    for (const DeviceInfo& d : devs) {
        const std::string why = unusableReason(d);
        std::printf("%u%s %s\n    type %s, driver %s%s%s, Vulkan %s%s\n", d.index,
                    def.index && *def.index == d.index ? " (default)" : "", d.name.c_str(), kindName(d.kind),
                    d.driverName.empty() ? "?" : d.driverName.c_str(), d.driverInfo.empty() ? "" : " / ",
                    d.driverInfo.c_str(), apiVersionString(d.apiVersion).c_str(),
                    why.empty() ? "" : (", unusable: " + why).c_str());
    }
    return def.index ? kExitOk : kExitNoDevice;
}

}  // namespace vkp
