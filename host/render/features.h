// The shader variant a scene needs: which primitive, material and light kinds its pipeline
// compiles in, as the specialization constants of shaders/lib/spec_constants.glsl (ids:
// shaders/shared/kernel_interface.h).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "render/render_options.h"
#include "scene/scene.h"

namespace vkp {

/// One specialization constant of the kernel: its constant_id, its GLSL name, its value (a bool
/// as 0/1, a float as its bits) and what it adds to the variant's readable name ("" for nothing).
struct SpecConstant {
    std::uint32_t id;
    const char* name;
    std::uint32_t value;
    std::string label;
};

struct Features {
    std::uint32_t shapes = 0;     ///< bit gpu::PRIM_* for each primitive kind present
    std::uint32_t materials = 0;  ///< bit gpu::MAT_* for each kernel material type (kernelMaterial) used
    std::uint32_t lights = 0;     ///< bit gpu::PRIM_* for each kind in the light list
    bool emitters = false;        ///< some material emits (diffuse_light, or emission on another type)
    bool defocus = false;
    bool environment = false;     ///< escaping rays see radiance (a map or a constant background)
    bool environmentMap = false;  ///< ... from a map (else constant)
    bool vertexAttributes = false;  ///< mesh triangles shade with UVs / interpolated normals (render/texture_pack.h)
    bool textures = false;          ///< some material reads a texture
    bool texCoord1 = false;         ///< ... a texture through TEXCOORD_1 (lib/surface.glsl)
    bool extensionTextures = false;  ///< ... a KHR_materials_specular or _transmission texture (lib/surface.glsl)
    bool alpha = false;             ///< some material has alphaMode MASK or BLEND (lib/alpha.glsl)
    bool instances = false;         ///< two-level BVH: the scene has instanced meshes (shared/instance.h)
    bool vertexColors = false;      ///< glTF COLOR_0 tints some MAT_PBR material (lib/surface.glsl)
    std::uint32_t layers = 0;       ///< gpu::LAYER_* over some MAT_PBR material (shared/layers.h)
    bool absorption = false;        ///< some dielectric absorbs inside (Material::absorption)
    bool solidTextures = false;     ///< some material has a JSON texture (Material::albedoTexture, emitTexture)
    bool motion = false;            ///< some shape moves (Shape::velocity: motion blur)
    bool aov = false;               ///< the kernel adds feature values to the AOV sums (RenderOptions::aov)
    /// An invocation may take several pixels (Renderer: dispatches that add fewer samples per pixel
    /// than it wants per invocation, on a CPU device). The renderer sets it for its second pipeline.
    bool pixelSlots = false;
    Sampler sampler = Sampler::Mis;
    Sequence sequence = Sequence::Sobol;
    LightSampling lightSampling = LightSampling::Auto;
    float solidAngleMinSize = kSolidAngleMinSize;  ///< for LightSampling::Auto (`--solid-angle-min`)
    /// The kernel's workgroup size (`--workgroup`); 0x0 until a device is known: the renderer runs
    /// kernelWorkgroup's (render/workgroup.h), which is what specConstants() then holds.
    std::uint32_t workgroupX = 0, workgroupY = 0;

    bool hasShape(std::uint32_t kind) const { return (shapes >> kind) & 1u; }
    bool hasMaterial(std::uint32_t type) const { return (materials >> type) & 1u; }
    bool hasLight(std::uint32_t kind) const { return (lights >> kind) & 1u; }

    /// Every specialization constant, in id order (VKP_SPEC_COUNT entries, checked): the one
    /// table the pipeline's specialization data and name() are built from.
    std::vector<SpecConstant> specTable() const;
    /// The values of specTable(): constant_id i = specConstants()[i].
    std::vector<std::uint32_t> specConstants() const;
    /// A readable name of the variant from the table's labels, e.g.
    /// "prims:sphere+quad materials:lambertian+dielectric+emission lights:quad sampler:mis sequence:sobol".
    std::string name() const;
};

/// The variant of the kernel that `scene` needs when rendered with `options`: what the scene uses
/// (kinds, materials, lights, textures...) and the options that are specialization constants
/// (sampler, sequence, light sampling, workgroup). options.fullVariant compiles in everything
/// (`--variant full`, for comparison).
Features sceneFeatures(const Scene& scene, const RenderOptions& options = {});

}  // namespace vkp
