// Packing the host scene into the GPU structs of shaders/shared/gpu_types.h.
#pragma once
#include <vector>

#include "render/features.h"
#include "scene/scene.h"
#include "shared/gpu_types.h"
#include "shared/medium.h"

namespace vkp {

/// The camera of "Ray Tracing in One Weekend" (sec. 12-13): w = unit(lookfrom - lookat),
/// u = unit(vup x w), v = w x u; column index grows along +u, row 0 is the top (rows grow along -v).
/// Fills origin, pixel00, pixelDu, pixelDv, defocusU, defocusV of `frame`.
void packCamera(const Camera& cam, gpu::GpuFrame& frame);

/// Stride s of the scrambled tile order (GpuPush::band, ::adaptive): coprime with n, n * s < 2^32.
std::uint32_t tileStride(std::uint32_t n);

/// Everything in GpuFrame for a render of scene at its (possibly overridden) settings; `pick`
/// decides the environment's share of next-event estimation (envPickProbability). Nothing in it
/// depends on the workgroup size or the tile order (GpuPush::band, render/renderer.cpp).
gpu::GpuFrame packFrame(const Scene& scene, LightPick pick = LightPick::Power);

std::vector<gpu::GpuMaterial> packMaterials(const std::vector<Material>& materials);

/// The kernel's records of the media (shared/medium.h GpuMedium), in Scene::media order.
std::vector<gpu::GpuMedium> packMedia(const std::vector<Medium>& media);

}  // namespace vkp
