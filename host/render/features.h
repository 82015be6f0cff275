// The shader variant a scene needs: which primitive, material and light kinds its pipeline
// compiles in (specialization constants of shaders/lib/bindings.glsl, in the same order).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace vkp {

enum class Sampler : std::uint32_t { Bsdf = 0, Light = 1, Mixture = 2, Mis = 3 };
const char* samplerName(Sampler s);
/// Every sampler, for tests and benchmarks that must cover them all.
inline constexpr Sampler kAllSamplers[] = {Sampler::Bsdf, Sampler::Light, Sampler::Mixture, Sampler::Mis};
/// "bsdf" | "light" | "mixture" | "mis" -> Sampler; false if unknown.
bool parseSampler(const std::string& name, Sampler& out);

/// Where a sample's random numbers come from (shaders/shared/sample_stream.h): independent hashed
/// random numbers per dimension, or Owen-scrambled Sobol' points (the default).
enum class Sequence : std::uint32_t { Random = 0, Sobol = 1 };
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

struct Features {
    bool spheres = false, parallelograms = false;  ///< primitive kinds present
    bool lambertian = false, metal = false, dielectric = false, emitters = false;
    bool pbr = false;  ///< glTF metallic-roughness materials (MaterialType::Pbr after kernelMaterial)
    bool sphereLights = false, quadLights = false, triangleLights = false;  ///< kinds in the light list
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

    /// Values for constant_id 0..24, in the order of shaders/lib/bindings.glsl (13-15: lib/surface.glsl,
    /// lib/alpha.glsl; 17: SOLID_ANGLE_LIGHTS; 18: HAS_INSTANCES; 19, 20: the workgroup size,
    /// pathtrace.comp; 21: SOLID_ANGLE_MIN_SIZE, a float's bits; 22: HAS_TRIANGLE_LIGHTS;
    /// 23: HAS_EXTENSION_TEXTURES, 24: HAS_TEXCOORD1, lib/surface.glsl).
    std::vector<std::uint32_t> specConstants() const;
    /// A readable name of the variant, e.g. "quad+sphere lambertian+dielectric+emit lights:quad+sphere mixture".
    std::string name() const;
};

/// The variant for `scene` rendered with `sampler`. `full` compiles in everything (the comparison
/// pipeline of `--variant full`).
Features sceneFeatures(const Scene& scene, Sampler sampler, bool full = false);

}  // namespace vkp
