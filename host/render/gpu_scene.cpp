#include "render/gpu_scene.h"

#include "render/environment.h"
#include "render/light_table.h"

#include <bit>
#include <algorithm>
#include <cmath>
#include <numeric>

#include <glm/gtc/constants.hpp>

namespace vkp {

namespace {
glm::vec4 v4(glm::vec3 v, float w = 0.0f) { return glm::vec4(v, w); }
float bitsf(std::uint32_t u) { return std::bit_cast<float>(u); }
}  // namespace

void packCamera(const Camera& cam, gpu::GpuFrame& frame) {
    const float theta = glm::radians(cam.vfov);
    const float h = std::tan(theta / 2.0f);
    const float viewportH = 2.0f * h * cam.focusDist;
    const float viewportW = viewportH * (float(cam.width) / float(cam.height));
    const glm::vec3 w = glm::normalize(cam.lookfrom - cam.lookat);
    const glm::vec3 u = glm::normalize(glm::cross(cam.vup, w));
    const glm::vec3 v = glm::cross(w, u);
    const glm::vec3 viewportU = viewportW * u;
    const glm::vec3 viewportV = -viewportH * v;
    const glm::vec3 du = viewportU / float(cam.width);
    const glm::vec3 dv = viewportV / float(cam.height);
    const glm::vec3 upperLeft = cam.lookfrom - cam.focusDist * w - viewportU / 2.0f - viewportV / 2.0f;
    const float defocusRadius = cam.focusDist * std::tan(glm::radians(cam.defocusAngle / 2.0f));
    frame.origin = v4(cam.lookfrom, 1.0f);  // w: the ray offset's scale, set from the BVH by packGpuArrays
    frame.pixel00 = v4(upperLeft + 0.5f * (du + dv));
    frame.pixelDu = v4(du);
    frame.pixelDv = v4(dv);
    frame.defocusU = v4(u * defocusRadius);
    frame.defocusV = v4(v * defocusRadius);
}

std::uint32_t tileStride(std::uint32_t n) {
    if (n <= 2) return 1;
    // Near the golden section of n (consecutive workgroups land far apart), coprime with n so
    // that g -> g * s mod n is a permutation, and small enough that g * s fits in 32 bits.
    std::uint64_t s = std::min<std::uint64_t>(std::uint64_t(0.6180339887 * n), (0xffffffffull / n) - 1);
    s = std::max<std::uint64_t>(s, 1);
    while (std::gcd(s, std::uint64_t(n)) != 1) --s;
    return std::uint32_t(s);
}

gpu::GpuFrame packFrame(const Scene& scene, LightPick pick) {
    gpu::GpuFrame f{};
    packCamera(scene.camera, f);
    f.background = v4(scene.render.background);
    f.size = glm::uvec4(scene.camera.width, scene.camera.height, scene.render.maxDepth, scene.render.seed);
    const std::uint32_t punctual = std::uint32_t(scene.punctualLights.size());
    f.counts = glm::uvec4(std::uint32_t(scene.lights.size()), scene.render.rouletteDepth, emittingLightCount(scene) + punctual, 0);
    f.punctual = glm::uvec4(punctual, 0, 0, 0);
    const double rot = glm::radians(double(scene.environment.rotateY));
    f.env = glm::vec4(float(std::cos(rot)), float(std::sin(rot)), float(envPickProbability(scene, pick)),
                      hasEnvironmentLight(scene) ? 1.0f : 0.0f);
    if (scene.environment.hasMap())
        f.envSize = glm::uvec4(scene.environment.image.width, scene.environment.image.height, 0, 0);
    return f;
}

std::vector<gpu::GpuMaterial> packMaterials(const std::vector<Material>& materials) {
    std::vector<gpu::GpuMaterial> out;
    out.reserve(materials.size());
    for (const Material& original : materials) {
        // glTF Pbr materials: the glTF BRDF (MAT_PBR), except transmission -> exact-Fresnel glass
        // and emitters -> diffuse_light (single-sided unless doubleSided). See kernelMaterial.
        const Material m = kernelMaterial(original);
        std::uint32_t flags = std::uint32_t(m.type);
        if (m.twoSided) flags |= gpu::MATF_TWO_SIDED;
        if (m.fresnelExact) flags |= gpu::MATF_FRESNEL_EXACT;
        if (m.emits()) flags |= gpu::MATF_EMITS;
        const float param = m.type == MaterialType::Dielectric ? m.ior : m.fuzz;
        gpu::GpuMaterial g{};
        g.m0 = v4(m.albedo, bitsf(flags));
        g.m1 = v4(m.emit, param);
        if (m.type == MaterialType::Dielectric) g.m2 = v4(m.absorption, 0.0f);  // Beer-Lambert inside
        if (m.albedoTexture >= 0 || m.emitTexture >= 0) {  // JSON textures (lib/solid_texture.glsl)
            g.m0.w = bitsf(flags | gpu::MATF_SOLID_TEXTURE);
            g.m2 = glm::vec4(bitsf(std::uint32_t(m.albedoTexture + 1)), bitsf(std::uint32_t(m.emitTexture + 1)), 0.0f, 0.0f);
        }
        if (m.type == MaterialType::Pbr) {
            g.m0 = v4(glm::vec3(m.pbr.baseColor), bitsf(flags));
            g.m2 = v4(m.pbr.specularColor, m.pbr.specular);
            // z: transmissionFactor where a texture decides per hit (transmissionTextured), else 0.
            g.m3 = glm::vec4(m.pbr.metallic, m.pbr.roughness, transmissionTextured(m) ? m.pbr.transmission : 0.0f, m.ior);
            if (m.pbr.layers() != 0u) {  // clear coat and sheen (shared/layers.h)
                g.m0.w = bitsf(flags | gpu::MATF_LAYERED);
                g.m4 = glm::vec4(m.pbr.clearcoat, m.pbr.clearcoatRoughness, m.pbr.sheenRoughness, 0.0f);
                g.m5 = v4(m.pbr.sheenColor, 0.0f);
            }
        }
        out.push_back(g);
    }
    return out;
}

std::vector<gpu::GpuMedium> packMedia(const std::vector<Medium>& media) {
    std::vector<gpu::GpuMedium> out;
    out.reserve(media.size());
    for (const Medium& m : media) {
        gpu::GpuMedium g{};
        glm::vec4* rows[3] = {&g.r0, &g.r1, &g.r2};
        for (int i = 0; i < 3; ++i)  // row i of the column-major toLocal
            *rows[i] = glm::vec4(float(m.toLocal[0][i]), float(m.toLocal[1][i]), float(m.toLocal[2][i]), float(m.toLocalOffset[i]));
        g.params = glm::vec4(m.density, bitsf(std::uint32_t(m.boundary)), bitsf(m.material), 0.0f);
        out.push_back(g);
    }
    return out;
}

}  // namespace vkp
