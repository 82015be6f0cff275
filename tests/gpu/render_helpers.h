// Small helpers for GPU tests that render scenes.
#pragma once
#include <filesystem>
#include <memory>
#include <string>

#include "bvh/flatten.h"
#include "bvh/two_level.h"
#include "render/renderer.h"
#include "scene/scene.h"
#include "vk/device.h"

namespace vkp::test {

/// A renderer with its scene and BVH kept alive beside it.
struct TestRender {
    Scene scene;
    FlatBvh bvh;
    std::unique_ptr<Renderer> renderer;
};

/// Loads `file`, sets the image size (keeping nothing of the scene's), builds and uploads it.
inline TestRender makeRender(VulkanDevice& dev, const std::filesystem::path& file, std::uint32_t width,
                             std::uint32_t height, Sampler sampler, std::uint32_t samplesPerDispatch = 1) {
    TestRender r;
    r.scene = loadSceneJson(file);
    r.scene.camera.width = width;
    r.scene.camera.height = height;
    r.bvh = buildSceneBvh(r.scene);  // two-level when the scene has instances
    RendererOptions o;
    o.sampler = sampler;
    o.samplesPerDispatch = samplesPerDispatch;
    r.renderer = std::make_unique<Renderer>(dev, r.scene, r.bvh, o);
    return r;
}

}  // namespace vkp::test
