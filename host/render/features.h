// The shader variant a scene needs: which primitive, material and light kinds its pipeline
// compiles in, as the specialization constants of shaders/lib/spec_constants.glsl (ids:
// shaders/shared/kernel_interface.h).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "scene/scene.h"
#include "shared/kinds.h"

namespace vkp {

enum class Sampler : std::uint32_t {
    Bsdf = gpu::SAMPLER_BSDF,
    Light = gpu::SAMPLER_LIGHT,
    Mixture = gpu::SAMPLER_MIXTURE,
    Mis = gpu::SAMPLER_MIS
};
const char* samplerName(Sampler s);
/// Every sampler, for tests and benchmarks that must cover them all.
inline constexpr Sampler kAllSamplers[] = {Sampler::Bsdf, Sampler::Light, Sampler::Mixture, Sampler::Mis};
/// "bsdf" | "light" | "mixture" | "mis" -> Sampler; false if unknown.
bool parseSampler(const std::string& name, Sampler& out);

/// Where a sample's random numbers come from (shaders/shared/sample_stream.h): independent hashed
/// random numbers per dimension, or Owen-scrambled Sobol' points (the default).
enum class Sequence : std::uint32_t { Random = gpu::SEQUENCE_RANDOM, Sobol = gpu::SEQUENCE_SOBOL };
const char* sequenceName(Sequence s);
/// "random" | "sobol" -> Sequence; false if unknown.
bool parseSequence(const std::string& name, Sequence& out);

/// How next-event estimation picks an emitter: in proportion to its power (default; alias table,
/// render/light_table.h) or uniformly among the emitters (`--light-pick uniform`, for comparison).
enum class LightPick : std::uint32_t { Power = 0, Uniform = 1 };
const char* lightPickName(LightPick p);
/// "power" | "uniform" -> LightPick; false if unknown.
bool parseLightPick(const std::string& name, LightPick& out);

/// How next-event estimation samples a point on a quad or triangle light: uniformly in the solid
/// angle it subtends (Urena et al. 2013 for rectangles, Arvo 1995 for triangles) or uniformly in
/// area (the book's). `Auto` (default) samples in solid angle only from points where the light
/// looks at least Features::solidAngleMinSize large (shared/rect_sampling.h apparentSize), in area
/// elsewhere; `SolidAngle` wherever the spherical warps are precise; `Area` everywhere (for
/// comparison). `mixture` always samples area, as the book does.
enum class LightSampling : std::uint32_t { SolidAngle = 0, Area = 1, Auto = 2 };
const char* lightSamplingName(LightSampling s);
/// "auto" | "solid-angle" | "area" -> LightSampling; false if unknown.
bool parseLightSampling(const std::string& name, LightSampling& out);

/// Default apparent size (sr: light area / squared distance to its centre) from which `auto`
/// light sampling switches from area to solid-angle sampling. Measured at equal time on the bench
/// scenes (README "Numbers on this machine", "Solid angle or area").
inline constexpr float kSolidAngleMinSize = 0.1f;

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
    Sampler sampler = Sampler::Mis;
    Sequence sequence = Sequence::Sobol;
    LightSampling lightSampling = LightSampling::Auto;
    float solidAngleMinSize = kSolidAngleMinSize;  ///< for LightSampling::Auto (`--solid-angle-min`)
    std::uint32_t workgroupX = 8, workgroupY = 8;  ///< the kernel's workgroup size (`--workgroup`)

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

/// The variant for `scene` rendered with `sampler`. `full` compiles in everything (the comparison
/// pipeline of `--variant full`).
Features sceneFeatures(const Scene& scene, Sampler sampler, bool full = false);

}  // namespace vkp
