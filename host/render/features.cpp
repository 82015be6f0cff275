#include "render/features.h"

#include <bit>
#include <cstdio>
#include <iterator>
#include <stdexcept>

#include "render/environment.h"
#include "render/texture_pack.h"
#include "shared/kernel_interface.h"

namespace vkp {

namespace {
/// "a+b+c" of the names of the bits set in mask (names indexed by bit).
template <std::size_t N>
std::string bitNames(std::uint32_t mask, const char* const (&names)[N]) {
    std::string out;
    for (std::uint32_t i = 0; i < N; ++i)
        if ((mask >> i) & 1u) {
            if (!out.empty()) out += '+';
            out += names[i];
        }
    return out.empty() ? "none" : out;
}
std::uint32_t bit(std::uint32_t i) { return 1u << i; }
/// Names of the bits of the LIGHTS mask: the primitive kinds, then punctual lights.
constexpr const char* kLightKindNames[] = {"sphere", "quad", "triangle", "instance", "punctual"};
static_assert(std::size(kLightKindNames) == gpu::LIGHT_KIND_PUNCTUAL + 1 && gpu::LIGHT_KIND_PUNCTUAL == gpu::PRIM_KIND_COUNT,
              "a name per bit of the LIGHTS mask");
/// Names of the bits of the LAYERS mask (gpu::LAYER_COAT = bit 0, LAYER_SHEEN = bit 1).
constexpr const char* kLayerNames[] = {"clearcoat", "sheen"};
static_assert(gpu::LAYER_COAT == 1u && gpu::LAYER_SHEEN == 2u, "a name per bit of the LAYERS mask");
}  // namespace

std::vector<SpecConstant> Features::specTable() const {
    const auto on = [](bool b, const char* label) { return b ? std::string(label) : std::string(); };
    std::string materialsLabel = "materials:" + (materials ? bitNames(materials, gpu::kMaterialTypeNames) : std::string());
    if (emitters) materialsLabel += materials ? "+emission" : "emission";
    if (!materials && !emitters) materialsLabel += "none";
    std::string minSize;
    if (lightSampling == LightSampling::Auto && solidAngleMinSize != kSolidAngleMinSize) {
        char buf[48];
        std::snprintf(buf, sizeof buf, "solid-angle-min:%g", double(solidAngleMinSize));
        minSize = buf;
    }
    // One entry per constant_id, in id order (shaders/lib/spec_constants.glsl).
    const SpecConstant table[] = {
        {VKP_SPEC_SHAPES, "SHAPES", shapes, "prims:" + bitNames(shapes, gpu::kPrimKindNames)},
        {VKP_SPEC_MATERIALS, "MATERIALS", materials, materialsLabel},
        {VKP_SPEC_HAS_EMITTERS, "HAS_EMITTERS", emitters, ""},  // in the materials label
        {VKP_SPEC_LIGHTS, "LIGHTS", lights, "lights:" + bitNames(lights, kLightKindNames)},
        {VKP_SPEC_SAMPLER, "SAMPLER", std::uint32_t(sampler), std::string("sampler:") + samplerName(sampler)},
        {VKP_SPEC_SEQUENCE, "SEQUENCE", std::uint32_t(sequence), std::string("sequence:") + sequenceName(sequence)},
        {VKP_SPEC_SOLID_ANGLE_LIGHTS, "SOLID_ANGLE_LIGHTS", lightSampling != LightSampling::Area,
         lightSampling != LightSampling::Auto ? std::string("light-sampling:") + lightSamplingName(lightSampling) : ""},
        {VKP_SPEC_SOLID_ANGLE_MIN_SIZE, "SOLID_ANGLE_MIN_SIZE",
         std::bit_cast<std::uint32_t>(lightSampling == LightSampling::Auto ? solidAngleMinSize : 0.0f), minSize},
        {VKP_SPEC_HAS_DEFOCUS, "HAS_DEFOCUS", defocus, on(defocus, "defocus")},
        {VKP_SPEC_HAS_ENV, "HAS_ENV", environment, on(environment, environmentMap ? "env:map" : "env:constant")},
        {VKP_SPEC_HAS_ENV_MAP, "HAS_ENV_MAP", environmentMap, ""},  // in the HAS_ENV label
        {VKP_SPEC_HAS_VERTEX_ATTRIBUTES, "HAS_VERTEX_ATTRIBUTES", vertexAttributes, on(vertexAttributes, "vertex-attributes")},
        {VKP_SPEC_HAS_TEXTURES, "HAS_TEXTURES", textures, on(textures, "textures")},
        {VKP_SPEC_HAS_EXTENSION_TEXTURES, "HAS_EXTENSION_TEXTURES", extensionTextures,
         on(extensionTextures, "extension-textures")},
        {VKP_SPEC_HAS_TEXCOORD1, "HAS_TEXCOORD1", texCoord1, on(texCoord1, "texcoord1")},
        {VKP_SPEC_HAS_ALPHA, "HAS_ALPHA", alpha, on(alpha, "alpha")},
        {VKP_SPEC_HAS_INSTANCES, "HAS_INSTANCES", instances, on(instances, "instances")},
        {VKP_SPEC_HAS_VERTEX_COLORS, "HAS_VERTEX_COLORS", vertexColors, on(vertexColors, "vertex-colors")},
        {VKP_SPEC_LAYERS, "LAYERS", layers, layers ? "layers:" + bitNames(layers, kLayerNames) : ""},
        {VKP_SPEC_WORKGROUP_X, "WORKGROUP_X", workgroupX, ""},  // the image does not depend on it
        {VKP_SPEC_WORKGROUP_Y, "WORKGROUP_Y", workgroupY, ""},
        {VKP_SPEC_HAS_ABSORPTION, "HAS_ABSORPTION", absorption, on(absorption, "absorption")},
        {VKP_SPEC_HAS_SOLID_TEXTURES, "HAS_SOLID_TEXTURES", solidTextures, on(solidTextures, "json-textures")},
        {VKP_SPEC_HAS_MOTION, "HAS_MOTION", motion, on(motion, "motion")},
        {VKP_SPEC_HAS_AOV, "HAS_AOV", aov, on(aov, "aov")},
        {VKP_SPEC_PIXEL_SLOTS, "PIXEL_SLOTS", pixelSlots, ""},  // the image does not depend on it
    };
    static_assert(std::size(table) == VKP_SPEC_COUNT, "one entry per specialization constant");
    std::vector<SpecConstant> out(std::begin(table), std::end(table));
    for (std::uint32_t i = 0; i < out.size(); ++i)
        if (out[i].id != i) throw std::logic_error(std::string("Features::specTable: ") + out[i].name + " out of id order");
    return out;
}

std::vector<std::uint32_t> Features::specConstants() const {
    std::vector<std::uint32_t> values;
    for (const SpecConstant& c : specTable()) values.push_back(c.value);
    return values;
}

std::string Features::name() const {
    std::string out;
    for (const SpecConstant& c : specTable())
        if (!c.label.empty()) out += (out.empty() ? "" : " ") + c.label;
    return out;
}

Features sceneFeatures(const Scene& scene, const RenderOptions& options) {
    Features f;
    f.sampler = options.sampler;
    f.sequence = options.sequence;
    f.lightSampling = options.lightSampling;
    f.solidAngleMinSize = options.solidAngleMinSize;
    f.workgroupX = options.workgroupX;
    f.workgroupY = options.workgroupY;
    f.aov = options.aov;
    const std::uint32_t surfaceKinds = bit(gpu::PRIM_SPHERE) | bit(gpu::PRIM_QUAD) | bit(gpu::PRIM_TRIANGLE);
    if (options.fullVariant) {
        f.shapes = surfaceKinds;
        f.lights = surfaceKinds | bit(gpu::LIGHT_KIND_PUNCTUAL);
        f.materials = bit(gpu::MAT_TYPE_COUNT) - 1u;
        f.emitters = f.defocus = f.environment = f.environmentMap = true;
        f.vertexAttributes = f.textures = f.extensionTextures = f.texCoord1 = f.alpha = f.instances = f.vertexColors = true;
        f.layers = gpu::LAYER_COAT | gpu::LAYER_SHEEN;
        f.absorption = f.solidTextures = f.motion = true;
        return f;
    }
    std::vector<bool> used(scene.materials.size(), false);
    forEachShape(scene, [&](const Shape& s) {
        f.shapes |= bit(std::uint32_t(s.type));
        used[s.material] = true;
        if (s.sampled) f.lights |= bit(std::uint32_t(s.type));
        f.motion |= s.moves();
    });
    for (const Medium& m : scene.media) used[m.material] = true;  // their isotropic materials: MAT_ISOTROPIC compiles media in
    if (!scene.punctualLights.empty()) f.lights |= bit(gpu::LIGHT_KIND_PUNCTUAL);
    f.instances = !scene.instances.empty();
    for (std::size_t i = 0; i < scene.materials.size(); ++i) {
        if (!used[i]) continue;
        const Material m = kernelMaterial(scene.materials[i]);  // what the kernel renders it as
        // diffuse_light has no bit of its own: it never scatters, and HAS_EMITTERS compiles it in.
        if (m.type != MaterialType::DiffuseLight) f.materials |= bit(std::uint32_t(m.type));
        if (transmissionTextured(m)) {  // glass (or metal) where its texture says so
            const Material t = transmittedMaterial(m);
            f.materials |= bit(std::uint32_t(t.type));
        }
        f.emitters |= m.emits() || m.type == MaterialType::DiffuseLight;
        if (m.type == MaterialType::Pbr) f.layers |= m.pbr.layers();
        f.absorption |= m.type == MaterialType::Dielectric && m.absorption != glm::vec3(0.0f);
        f.solidTextures |= m.albedoTexture >= 0 || m.emitTexture >= 0;
    }
    f.defocus = scene.camera.defocusAngle > 0.0f;
    f.environment = hasEnvironmentLight(scene);
    f.environmentMap = scene.environment.hasMap();
    f.textures = sceneHasTextures(scene);
    f.extensionTextures = sceneHasExtensionTextures(scene);
    f.texCoord1 = f.textures && sceneHasTexCoord1(scene);
    f.alpha = sceneHasAlpha(scene);
    f.vertexColors = sceneHasVertexColors(scene);
    f.vertexAttributes = f.textures || f.alpha || f.vertexColors || sceneHasVertexAttributes(scene);  // textures need the UVs
    return f;
}

}  // namespace vkp
