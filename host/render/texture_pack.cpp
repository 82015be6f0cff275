#include "render/texture_pack.h"

#include <bit>
#include <cmath>
#include <cstring>

#include <glm/gtc/packing.hpp>

#include "render/perlin_table.h"
#include "shared/solid_texture.h"
#include "shared/texture_sample.h"

namespace vkp {

namespace {
std::uint32_t bits(float f) { return std::bit_cast<std::uint32_t>(f); }

std::uint32_t wrapFlag(TextureWrap w) {
    switch (w) {
        case TextureWrap::ClampToEdge: return gpu::TEXF_WRAP_CLAMP;
        case TextureWrap::MirroredRepeat: return gpu::TEXF_WRAP_MIRROR;
        default: return gpu::TEXF_WRAP_REPEAT;
    }
}

/// The two texels of one texture slot: (rotation x scale) and (offset, header index or kNoTexture, UV set).
void packSlot(const TextureRef& r, glm::uvec4* out) {
    const float c = std::cos(r.rotation), s = std::sin(r.rotation);
    out[0] = glm::uvec4(bits(c * r.scale.x), bits(s * r.scale.y), bits(-s * r.scale.x), bits(c * r.scale.y));
    out[1] = glm::uvec4(bits(r.offset.x), bits(r.offset.y), r.valid() ? std::uint32_t(r.texture) : kNoTexture,
                        r.valid() ? r.texCoord : 0u);
}

/// The emissive texture the kernel applies to `original` (a glTF emitter becomes a diffuse_light).
TextureRef emissiveTextureOf(const Material& original) {
    if (original.type == MaterialType::Pbr && kernelMaterial(original).type == MaterialType::DiffuseLight)
        return original.pbr.emissiveTexture;
    return TextureRef{};
}

/// The textures of a material's layers the kernel reads (those of a layer that is present).
std::vector<const TextureRef*> layerTextures(const Material& m) {
    std::vector<const TextureRef*> out;
    if (m.type != MaterialType::Pbr) return out;
    const std::uint32_t layers = m.pbr.layers();
    if (layers & gpu::LAYER_COAT) {
        out.push_back(&m.pbr.clearcoatTexture);
        out.push_back(&m.pbr.clearcoatRoughnessTexture);
        out.push_back(&m.pbr.clearcoatNormalTexture);
    }
    if (layers & gpu::LAYER_SHEEN) {
        out.push_back(&m.pbr.sheenColorTexture);
        out.push_back(&m.pbr.sheenRoughnessTexture);
    }
    return out;
}

bool materialReadsTextures(const Material& original) {
    const Material m = kernelMaterial(original);
    if (m.type == MaterialType::Pbr) {
        for (const TextureRef* t : layerTextures(m))
            if (t->valid()) return true;
        return m.pbr.baseColorTexture.valid() || m.pbr.metallicRoughnessTexture.valid() || m.pbr.normalTexture.valid() ||
               m.pbr.specularTexture.valid() || m.pbr.specularColorTexture.valid() || transmissionTextured(m);
    }
    return emissiveTextureOf(original).valid();
}

std::vector<bool> usedMaterials(const Scene& scene) {
    std::vector<bool> used(scene.materials.size(), false);
    forEachShape(scene, [&](const Shape& s) { used[s.material] = true; });
    return used;
}
}  // namespace

bool sceneHasTextures(const Scene& scene) {
    const std::vector<bool> used = usedMaterials(scene);
    for (std::size_t i = 0; i < scene.materials.size(); ++i)
        if (used[i] && materialReadsTextures(scene.materials[i])) return true;
    return false;
}

bool sceneHasExtensionTextures(const Scene& scene) {
    const std::vector<bool> used = usedMaterials(scene);
    for (std::size_t i = 0; i < scene.materials.size(); ++i) {
        if (!used[i]) continue;
        const Material m = kernelMaterial(scene.materials[i]);
        if (m.type == MaterialType::Pbr &&
            (m.pbr.specularTexture.valid() || m.pbr.specularColorTexture.valid() || transmissionTextured(m)))
            return true;
    }
    return false;
}

bool sceneHasTexCoord1(const Scene& scene) {
    const std::vector<bool> used = usedMaterials(scene);
    auto one = [](const TextureRef& r) { return r.valid() && r.texCoord == 1; };
    for (std::size_t i = 0; i < scene.materials.size(); ++i) {
        if (!used[i]) continue;
        const Material m = kernelMaterial(scene.materials[i]);  // the slots packTextures fills
        if (one(emissiveTextureOf(scene.materials[i]))) return true;
        if (m.type != MaterialType::Pbr) continue;
        const PbrParams& p = m.pbr;
        if (one(p.baseColorTexture) || one(p.metallicRoughnessTexture) || one(p.normalTexture) || one(p.specularTexture) ||
            one(p.specularColorTexture) || (transmissionTextured(m) && one(p.transmissionTexture)))
            return true;
        for (const TextureRef* t : layerTextures(m))
            if (one(*t)) return true;
    }
    return false;
}

bool sceneHasAlpha(const Scene& scene) {
    const std::vector<bool> used = usedMaterials(scene);
    for (std::size_t i = 0; i < scene.materials.size(); ++i) {
        if (!used[i]) continue;
        const Material m = kernelMaterial(scene.materials[i]);
        if (m.type == MaterialType::Pbr && m.pbr.alphaMode != AlphaMode::Opaque) return true;
    }
    return false;
}

namespace {
/// True if some mesh triangle whose kernel material is MAT_PBR has one of the attribute flags in mask.
bool pbrTriangleHas(const Scene& scene, std::uint32_t mask) {
    std::vector<int> pbr(scene.materials.size(), -1);
    bool found = false;
    forEachShape(scene, [&](const Shape& s) {
        if (found || s.type != ShapeType::Triangle || s.attributes == Shape::kNoAttributes) return;
        int& p = pbr[s.material];
        if (p < 0) p = kernelMaterial(scene.materials[s.material]).type == MaterialType::Pbr ? 1 : 0;
        if (p == 1 && (scene.triangleVertices.at(s.attributes).flags & mask)) found = true;
    });
    return found;
}
}  // namespace

bool sceneHasVertexAttributes(const Scene& scene) {
    return pbrTriangleHas(scene, TriangleVertices::kHasNormal | TriangleVertices::kHasUv);
}

bool sceneHasVertexColors(const Scene& scene) { return pbrTriangleHas(scene, TriangleVertices::kHasColor); }

TexturePack packTextures(const Scene& scene, bool materialRecords) {
    TexturePack out;
    const std::uint32_t nm = materialRecords ? std::uint32_t(scene.materials.size()) : 0u;
    const std::uint32_t headerBase = 1 + kMatTexTexels * nm;
    out.info.assign(headerBase + scene.textures.size(), glm::uvec4(0));
    out.info[0] = glm::uvec4(headerBase, nm, std::uint32_t(scene.textures.size()), 0u);
    for (std::uint32_t i = 0; i < nm; ++i) {
        const Material m = kernelMaterial(scene.materials[i]);
        glm::uvec4* rec = &out.info[1 + kMatTexTexels * i];
        const bool pbr = m.type == MaterialType::Pbr;
        const TextureRef none;
        packSlot(pbr ? m.pbr.baseColorTexture : none, rec + 2 * kTexSlotBaseColor);
        packSlot(pbr ? m.pbr.metallicRoughnessTexture : none, rec + 2 * kTexSlotMetallicRoughness);
        packSlot(pbr ? m.pbr.normalTexture : none, rec + 2 * kTexSlotNormal);
        packSlot(emissiveTextureOf(scene.materials[i]), rec + 2 * kTexSlotEmissive);
        packSlot(pbr ? m.pbr.specularTexture : none, rec + 2 * kTexSlotSpecular);
        packSlot(pbr ? m.pbr.specularColorTexture : none, rec + 2 * kTexSlotSpecularColor);
        packSlot(transmissionTextured(m) ? m.pbr.transmissionTexture : none, rec + 2 * kTexSlotTransmission);
        rec[gpu::MAT_TEX_ALPHA_TEXEL] = glm::uvec4(std::uint32_t(m.pbr.alphaMode), bits(m.pbr.alphaCutoff), bits(m.pbr.normalScale),
                                        bits(m.pbr.baseColor.w));
        // Clear coat and sheen: the kernel reads these slots only for a material with the layer.
        const std::uint32_t layers = pbr ? m.pbr.layers() : 0u;
        const bool coat = (layers & gpu::LAYER_COAT) != 0u, sheen = (layers & gpu::LAYER_SHEEN) != 0u;
        packSlot(coat ? m.pbr.clearcoatTexture : none, rec + 2 * gpu::TEX_SLOT_CLEARCOAT);
        packSlot(coat ? m.pbr.clearcoatRoughnessTexture : none, rec + 2 * gpu::TEX_SLOT_CLEARCOAT_ROUGHNESS);
        packSlot(coat ? m.pbr.clearcoatNormalTexture : none, rec + 2 * gpu::TEX_SLOT_CLEARCOAT_NORMAL);
        packSlot(sheen ? m.pbr.sheenColorTexture : none, rec + 2 * gpu::TEX_SLOT_SHEEN_COLOR);
        packSlot(sheen ? m.pbr.sheenRoughnessTexture : none, rec + 2 * gpu::TEX_SLOT_SHEEN_ROUGHNESS);
        rec[gpu::MAT_TEX_LAYER_TEXEL] = glm::uvec4(bits(m.pbr.clearcoatNormalScale), 0u, 0u, 0u);
    }
    std::vector<std::uint32_t> imageStart(scene.images.size(), 0);
    for (std::size_t i = 0; i < scene.images.size(); ++i) {
        const TextureImage& img = scene.images[i];
        imageStart[i] = std::uint32_t(out.texels.size());
        const std::size_t n = std::size_t(img.width) * img.height;
        const std::size_t start = out.texels.size();
        out.texels.resize(start + n);
        if (n > 0) std::memcpy(out.texels.data() + start, img.rgba8.data(), n * 4);  // R in the low byte
    }
    for (std::size_t t = 0; t < scene.textures.size(); ++t) {
        const Texture& tex = scene.textures[t];
        const TextureImage& img = scene.images.at(tex.image);
        std::uint32_t flags = wrapFlag(tex.wrapS) | (wrapFlag(tex.wrapT) << 2u);
        if (tex.srgb) flags |= gpu::TEXF_SRGB;
        if (tex.nearest) flags |= gpu::TEXF_NEAREST;
        if (img.rgb9e5) flags |= gpu::TEXF_RGB9E5;
        out.info[headerBase + t] = glm::uvec4(imageStart[tex.image], img.width, img.height, flags);
    }
    if (!scene.solidTextures.empty()) {
        // JSON textures (shared/solid_texture.h): the origin and the Perlin table's place, the
        // nodes, the table.
        const std::uint32_t at = std::uint32_t(out.info.size());
        const std::uint32_t nodes = std::uint32_t(scene.solidTextures.size());
        const std::uint32_t tableAt = 1 + gpu::STEX_NODE_TEXELS * nodes;
        out.info[0].w = at;
        const glm::vec3 origin(scene.origin);
        out.info.emplace_back(bits(origin.x), bits(origin.y), bits(origin.z), tableAt);
        for (const SolidTexture& t : scene.solidTextures) {
            const std::uint32_t a = t.kind == gpu::STEX_CHECKER ? t.even : t.kind == gpu::STEX_IMAGE ? t.texture : 0u;
            const std::uint32_t b = t.kind == gpu::STEX_CHECKER ? t.odd : 0u;
            out.info.emplace_back(t.kind, a, b, 0u);
            out.info.emplace_back(bits(t.colour.x), bits(t.colour.y), bits(t.colour.z), bits(t.scale));
        }
        const std::vector<glm::uvec4> table = perlinTable();
        out.info.insert(out.info.end(), table.begin(), table.end());
    }
    if (out.texels.empty()) out.texels.push_back(0u);
    return out;
}

std::vector<glm::uvec4> packVertexAttributes(const Scene& scene, const FlatBvh& bvh) {
    std::vector<glm::uvec4> out(std::max<std::size_t>(bvh.primToShape.size(), 1) * kAttributeTexels, glm::uvec4(0));
    std::vector<glm::uvec4> extra;  // TEXCOORD_1 and COLOR_0 records, appended after the primitive records
    const MeshVertices& mv = scene.vertices;
    for (std::size_t i = 0; i < bvh.primToShape.size(); ++i) {
        const Shape* sp = primShape(scene, bvh, i);
        if (!sp) continue;  // an instance primitive
        const Shape& s = *sp;
        if (s.type != ShapeType::Triangle || s.attributes == Shape::kNoAttributes) continue;
        const TriangleVertices& tv = scene.triangleVertices.at(s.attributes);
        glm::uvec4* rec = &out[i * kAttributeTexels];
        glm::vec2 uv[3] = {glm::vec2(0.0f), glm::vec2(0.0f), glm::vec2(0.0f)};
        if ((tv.flags & TriangleVertices::kHasUv) && !mv.uv.empty())
            for (int k = 0; k < 3; ++k) uv[k] = mv.uv.at(tv.v[k]);
        rec[0] = glm::uvec4(bits(uv[0].x), bits(uv[0].y), bits(uv[1].x), bits(uv[1].y));
        std::uint32_t uv1At = 0;  // 0: no TEXCOORD_1 (the first record starts at 8 or later)
        if ((tv.flags & TriangleVertices::kHasUv1) && !mv.uv1.empty()) {
            const glm::vec2 a = mv.uv1.at(tv.v[0]), b = mv.uv1.at(tv.v[1]), c = mv.uv1.at(tv.v[2]);
            uv1At = std::uint32_t(out.size() + extra.size());
            extra.emplace_back(bits(a.x), bits(a.y), bits(b.x), bits(b.y));
            extra.emplace_back(bits(c.x), bits(c.y), 0u, 0u);
        }
        rec[1] = glm::uvec4(bits(uv[2].x), bits(uv[2].y), tv.flags, uv1At);
        std::uint32_t colorAt = 0;  // 0: no COLOR_0 (as uv1At)
        if ((tv.flags & TriangleVertices::kHasColor) && !mv.color.empty()) {
            const glm::vec4 a = mv.color.at(tv.v[0]), b = mv.color.at(tv.v[1]), c = mv.color.at(tv.v[2]);
            colorAt = std::uint32_t(out.size() + extra.size());
            extra.emplace_back(glm::packHalf2x16(glm::vec2(a.x, a.y)), glm::packHalf2x16(glm::vec2(a.z, a.w)),
                               glm::packHalf2x16(glm::vec2(b.x, b.y)), glm::packHalf2x16(glm::vec2(b.z, b.w)));
            extra.emplace_back(glm::packHalf2x16(glm::vec2(c.x, c.y)), glm::packHalf2x16(glm::vec2(c.z, c.w)), 0u, 0u);
        }
        for (int k = 0; k < 3; ++k) {
            const glm::vec3 n = (tv.flags & TriangleVertices::kHasNormal) ? mv.normal.at(tv.v[k]) : glm::vec3(0.0f);
            rec[2 + k] = glm::uvec4(bits(n.x), bits(n.y), bits(n.z), k == 0 ? colorAt : 0u);
            glm::vec4 t(0.0f);
            if ((tv.flags & TriangleVertices::kHasTangent) && !mv.tangent.empty()) t = mv.tangent.at(tv.v[k]);
            rec[5 + k] = glm::uvec4(bits(t.x), bits(t.y), bits(t.z), bits(t.w));
        }
    }
    out.insert(out.end(), extra.begin(), extra.end());
    return out;
}

}  // namespace vkp
