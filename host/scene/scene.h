// The scene as the host sees it after loading: world-space shapes, materials, lights, camera.
// Loaders (JSON, later glTF) produce it; the BVH builder and the renderer consume it.
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

namespace vkp {

enum class MaterialType : std::uint32_t { Lambertian = 0, Metal = 1, Dielectric = 2, DiffuseLight = 3 };

struct Material {
    std::string name;
    MaterialType type = MaterialType::Lambertian;
    glm::vec3 albedo{0.0f};  ///< reflectance in [0,1] per channel (lambertian, metal); dielectric: 1
    glm::vec3 emit{0.0f};    ///< emitted radiance (linear RGB); lambertian or diffuse_light
    float fuzz = 0.0f;       ///< metal: radius of the fuzz sphere, in [0,1]
    float ior = 1.5f;        ///< dielectric: index of refraction (relative to the outside)
    bool fresnelExact = false;  ///< dielectric: exact Fresnel equations instead of Schlick
    bool twoSided = false;      ///< both faces emit: diffuse_light's "two_sided"; the loader sets it
                                ///< for every emitting lambertian (which always emits from both faces)
    bool emits() const { return emit.x > 0.0f || emit.y > 0.0f || emit.z > 0.0f; }
};

enum class ShapeType : std::uint32_t { Sphere = 0, Quad = 1, Triangle = 2 };

/// One primitive in world space (its transform already applied).
///  - Sphere:   p0 = centre, radius
///  - Quad:     p0 = Q, p1 = u, p2 = v   (points Q + a u + b v, a,b in [0,1]; front face: u x v)
///  - Triangle: p0 = v0, p1 = v1, p2 = v2 (front face: counter-clockwise, (v1-v0) x (v2-v0))
struct Shape {
    ShapeType type = ShapeType::Sphere;
    glm::vec3 p0{0.0f}, p1{0.0f}, p2{0.0f};
    float radius = 0.0f;
    std::uint32_t material = 0;  ///< index into Scene::materials
    bool sampled = false;        ///< in the light list: emits, or "sample": true
};

/// The book's camera ("Ray Tracing in One Weekend", sec. 13).
struct Camera {
    glm::vec3 lookfrom{0.0f, 0.0f, 0.0f};
    glm::vec3 lookat{0.0f, 0.0f, -1.0f};
    glm::vec3 vup{0.0f, 1.0f, 0.0f};
    float vfov = 90.0f;           ///< vertical field of view, degrees, in (0,180)
    std::uint32_t width = 400;    ///< pixels
    std::uint32_t height = 400;   ///< pixels
    float defocusAngle = 0.0f;    ///< degrees; 0 = pinhole
    float focusDist = 1.0f;       ///< world units; the loader defaults it to |lookfrom - lookat|
};

struct RenderSettings {
    std::uint32_t spp = 64;
    std::uint32_t maxDepth = 50;
    glm::vec3 background{0.0f};  ///< radiance of escaping rays (linear RGB)
    std::uint32_t seed = 0;
};

struct Scene {
    std::filesystem::path path;  ///< file it was loaded from (for messages)
    Camera camera;
    RenderSettings render;
    std::vector<Material> materials;
    std::vector<Shape> shapes;
    std::vector<std::uint32_t> lights;  ///< indices into shapes of every sampled shape, in file order
};

/// Load a scene in vkpath's JSON format (scenes/README.md). Throws InputError with one line
/// "<file>: <json pointer>: <what is wrong>" on any bad input.
Scene loadSceneJson(const std::filesystem::path& file);

/// The same from text already in memory; file is only used in messages and Scene::path.
Scene parseSceneJson(std::string_view text, const std::filesystem::path& file);

/// Surface area in world units^2: 4 pi r^2 (sphere), |u x v| (quad), |e1 x e2| / 2 (triangle).
float shapeArea(const Shape& s);

}  // namespace vkp
