// Loader tests state positions in the file's coordinates; a loaded Scene is camera-relative
// (Scene::origin, docs/design.md "Camera-relative space"). inFileFrame moves it back.
#pragma once
#include "render/gpu_scene.h"
#include "scene/scene.h"
#include "shared/gpu_types.h"

namespace vkp::test {

/// The scene with every position (shapes, instances, camera) in the file's coordinates again:
/// origin 0. Exact where the coordinates and the camera position are exact in float (integers).
inline Scene inFileFrame(Scene s) {
    const glm::dvec3 o = s.origin;
    s.camera.lookfrom = glm::vec3(glm::dvec3(s.camera.lookfrom) + o);
    s.camera.lookat = glm::vec3(glm::dvec3(s.camera.lookat) + o);
    moveOrigin(s, -o, "test");
    return s;
}

/// The camera of `scene` packed as the kernel gets it (packCamera), then moved into the file's
/// coordinates (origin and pixel00 plus Scene::origin; du, dv are directions): for tests that find
/// which pixels see which part of a scene whose geometry they state in the file's coordinates.
inline void packFileFrameCamera(const Scene& scene, gpu::GpuFrame& f) {
    packCamera(scene.camera, f);
    const glm::vec3 o(scene.origin);
    f.origin += glm::vec4(o, 0.0f);
    f.pixel00 += glm::vec4(o, 0.0f);
}

}  // namespace vkp::test
