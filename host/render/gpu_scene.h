// Packing the host scene into the GPU structs of shaders/shared/gpu_types.h.
#pragma once
#include <vector>

#include "scene/scene.h"
#include "shared/gpu_types.h"

namespace vkp {

/// The camera of "Ray Tracing in One Weekend" (sec. 12-13): w = unit(lookfrom - lookat),
/// u = unit(vup x w), v = w x u; column index grows along +u, row 0 is the top (rows grow along -v).
/// Fills origin, pixel00, pixelDu, pixelDv, defocusU, defocusV of `frame`.
void packCamera(const Camera& cam, gpu::GpuFrame& frame);

/// Everything in GpuFrame for a render of scene at its (possibly overridden) settings.
gpu::GpuFrame packFrame(const Scene& scene, std::uint32_t primCount, std::uint32_t nodeCount);

std::vector<gpu::GpuMaterial> packMaterials(const std::vector<Material>& materials);

/// One GpuLight per entry of scene.lights; primOfShape maps a shape index to its packed primitive.
std::vector<gpu::GpuLight> packLights(const Scene& scene, const std::vector<std::uint32_t>& primOfShape);

}  // namespace vkp
