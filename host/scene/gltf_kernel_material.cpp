// kernelMaterial: what the kernel renders for a glTF Pbr material. Opaque glTF materials keep the
// glTF BRDF (MaterialType::Pbr -> MAT_PBR, shaders/shared/microfacet.h); transmission and
// emission are mapped to the book's materials.
#include "scene/scene.h"

namespace vkp {

Material kernelMaterial(const Material& m) {
    if (m.type != MaterialType::Pbr) return m;
    Material k;
    k.name = m.name;
    k.emit = m.emit;
    if (m.emits()) {
        // Emitters become diffuse_light: emission kept (front face only unless doubleSided, the
        // glTF convention); their reflection is dropped (as the book's lights, and exact for the
        // black base colour exporters give lamps).
        k.type = MaterialType::DiffuseLight;
        k.twoSided = m.twoSided;
        return k;
    }
    if (m.pbr.transmission > 0.0f && !transmissionTextured(m)) return transmittedMaterial(m);
    // Opaque (or transmitting where a transmissionTexture says so, decided per hit): the glTF BRDF
    // itself (Lambertian base + GGX specular, blended by metallic).
    k = m;
    k.albedo = glm::vec3(m.pbr.baseColor);
    return k;
}

const char* texCoord1Slot(const Material& m) {
    if (m.type != MaterialType::Pbr) return nullptr;
    const PbrParams& p = m.pbr;
    const std::pair<const TextureRef*, const char*> slots[] = {
        {&p.baseColorTexture, "baseColorTexture"}, {&p.metallicRoughnessTexture, "metallicRoughnessTexture"},
        {&p.normalTexture, "normalTexture"},       {&p.emissiveTexture, "emissiveTexture"},
        {&p.specularTexture, "specularTexture"},   {&p.specularColorTexture, "specularColorTexture"},
        {&p.transmissionTexture, "transmissionTexture"}, {&p.clearcoatTexture, "clearcoatTexture"},
        {&p.clearcoatRoughnessTexture, "clearcoatRoughnessTexture"}, {&p.clearcoatNormalTexture, "clearcoatNormalTexture"},
        {&p.sheenColorTexture, "sheenColorTexture"}, {&p.sheenRoughnessTexture, "sheenRoughnessTexture"}};
    for (const auto& [ref, name] : slots)
        if (ref->valid() && ref->texCoord == 1) return name;
    return nullptr;
}

bool transmissionTextured(const Material& m) {
    return m.type == MaterialType::Pbr && !m.emits() && m.pbr.transmission > 0.0f && m.pbr.transmissionTexture.valid();
}

Material transmittedMaterial(const Material& m) {
    Material k;
    k.name = m.name;
    if (m.ior >= 1.0f) {
        // Transmission (any amount) becomes smooth clear glass with the exact Fresnel equations:
        // tint, roughness and partial transmission are dropped.
        k.type = MaterialType::Dielectric;
        k.albedo = glm::vec3(1.0f);
        k.ior = m.ior;
        k.fresnelExact = true;
        k.absorption = m.pbr.volumeAbsorption;  // KHR_materials_volume
    } else {
        // KHR_materials_ior 0 (no refraction defined): the book's fuzzy metal, F0 = base colour,
        // fuzz = GGX alpha = roughness^2.
        k.type = MaterialType::Metal;
        k.albedo = glm::vec3(m.pbr.baseColor);
        k.fuzz = m.pbr.roughness * m.pbr.roughness;
    }
    return k;
}

}  // namespace vkp
