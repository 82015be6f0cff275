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

struct Features {
    bool spheres = false, parallelograms = false;  ///< primitive kinds present
    bool lambertian = false, metal = false, dielectric = false, emitters = false;
    bool pbr = false;  ///< glTF metallic-roughness materials (MaterialType::Pbr after kernelMaterial)
    bool sphereLights = false, parallelogramLights = false;  ///< kinds in the light list
    bool defocus = false;
    bool environment = false;     ///< escaping rays see radiance (a map or a constant background)
    bool environmentMap = false;  ///< ... from a map (else constant)
    bool vertexAttributes = false;  ///< mesh triangles shade with UVs / interpolated normals (render/texture_pack.h)
    bool textures = false;          ///< some material reads a texture
    bool alpha = false;             ///< some material has alphaMode MASK or BLEND (lib/alpha.glsl)
    bool instances = false;         ///< two-level BVH: the scene has instanced meshes (shared/instance.h)
    Sampler sampler = Sampler::Mis;
    Sequence sequence = Sequence::Sobol;

    /// Values for constant_id 0..18, in the order of shaders/lib/bindings.glsl (13-15: lib/surface.glsl,
    /// lib/alpha.glsl; 17 reserved, 0; 18: HAS_INSTANCES).
    std::vector<std::uint32_t> specConstants() const;
    /// A readable name of the variant, e.g. "quad+sphere lambertian+dielectric+emit lights:quad+sphere mixture".
    std::string name() const;
};

/// The variant for `scene` rendered with `sampler`. `full` compiles in everything (the comparison
/// pipeline of `--variant full`).
Features sceneFeatures(const Scene& scene, Sampler sampler, bool full = false);

}  // namespace vkp
