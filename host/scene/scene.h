// The scene as the host sees it after loading: world-space shapes, materials, lights, camera.
// Loaders (JSON: scene_json.cpp, glTF: gltf.h) produce it; the BVH builder and the renderer consume it.
#pragma once
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "core/image.h"
#include "scene/file_references.h"
#include "shared/kinds.h"

namespace vkp {

/// Pbr: the glTF 2.0 metallic-roughness material (with the extensions in PbrParams); only glTF
/// files produce it. The kernel renders kernelMaterial(m): the glTF BRDF unless it emits or transmits.
/// Values are the kernel's MAT_* (shaders/shared/kinds.h).
enum class MaterialType : std::uint32_t {
    Lambertian = gpu::MAT_LAMBERTIAN,
    Metal = gpu::MAT_METAL,
    Dielectric = gpu::MAT_DIELECTRIC,
    DiffuseLight = gpu::MAT_DIFFUSE_LIGHT,
    Pbr = gpu::MAT_PBR,
    Isotropic = gpu::MAT_ISOTROPIC  ///< the phase function of a Medium (no surface has it)
};

/// A texture lookup of a material: which texture of Scene::textures, which UV set, and the
/// KHR_texture_transform of the lookup (identity when absent).
struct TextureRef {
    std::int32_t texture = -1;    ///< index into Scene::textures; -1: no texture (use the factor alone)
    std::uint32_t texCoord = 0;   ///< the UV set: 0 (TEXCOORD_0) or 1 (TEXCOORD_1); the loader warns about others and uses 0
    glm::vec2 offset{0.0f};       ///< KHR_texture_transform offset (UV units)
    float rotation = 0.0f;        ///< KHR_texture_transform rotation, radians, counter-clockwise in UV space
    glm::vec2 scale{1.0f};        ///< KHR_texture_transform scale
    bool valid() const { return texture >= 0; }
    /// The UV at which to sample: T(offset) * R(rotation) * S(scale) * uv (KHR_texture_transform).
    glm::vec2 transform(glm::vec2 uv) const;
};

/// How a glTF material's alpha (baseColor alpha times the texture's) is used (glTF 2.0 sec. 3.9.4).
enum class AlphaMode : std::uint32_t { Opaque = gpu::ALPHA_OPAQUE, Mask = gpu::ALPHA_MASK, Blend = gpu::ALPHA_BLEND };

/// Parameters of a MaterialType::Pbr material (glTF 2.0 sec. 3.9 and the KHR_materials_*
/// extensions), as in the file; factors multiply their texture's value. Colours are linear RGB.
/// The emission is Material::emit (emissiveFactor x KHR_materials_emissive_strength), the index of
/// refraction Material::ior (KHR_materials_ior, default 1.5), doubleSided is Material::twoSided.
struct PbrParams {
    glm::vec4 baseColor{1.0f};             ///< baseColorFactor, RGBA (also in Material::albedo as RGB)
    TextureRef baseColorTexture;           ///< sRGB colour, alpha linear
    float metallic = 1.0f;                 ///< metallicFactor in [0,1]
    float roughness = 1.0f;                ///< roughnessFactor in [0,1] (perceptual: alpha = roughness^2)
    TextureRef metallicRoughnessTexture;   ///< linear; roughness in G, metallic in B
    TextureRef normalTexture;              ///< linear tangent-space normal map
    float normalScale = 1.0f;              ///< normalTexture.scale
    TextureRef emissiveTexture;            ///< sRGB colour, multiplies Material::emit
    float specular = 1.0f;                 ///< KHR_materials_specular specularFactor (0: pure Lambertian base)
    glm::vec3 specularColor{1.0f};         ///< KHR_materials_specular specularColorFactor
    TextureRef specularTexture;            ///< linear, factor in A
    TextureRef specularColorTexture;       ///< sRGB colour
    float transmission = 0.0f;             ///< KHR_materials_transmission transmissionFactor in [0,1]
    /// KHR_materials_volume with thicknessFactor > 0: absorption inside, -ln(attenuationColor) /
    /// attenuationDistance per channel (1/world unit; 0: none). Given to the glass that
    /// transmission becomes (transmittedMaterial).
    glm::vec3 volumeAbsorption{0.0f};
    TextureRef transmissionTexture;        ///< linear, factor in R
    float clearcoat = 0.0f;                ///< KHR_materials_clearcoat clearcoatFactor in [0,1] (0: no coat)
    TextureRef clearcoatTexture;           ///< linear, factor in R
    float clearcoatRoughness = 0.0f;       ///< clearcoatRoughnessFactor in [0,1]
    TextureRef clearcoatRoughnessTexture;  ///< linear, factor in G
    TextureRef clearcoatNormalTexture;     ///< linear tangent-space normal of the coat (else: no normal map on it)
    float clearcoatNormalScale = 1.0f;     ///< clearcoatNormalTexture.scale
    glm::vec3 sheenColor{0.0f};            ///< KHR_materials_sheen sheenColorFactor, linear, [0,1] (0: no sheen)
    TextureRef sheenColorTexture;          ///< sRGB colour
    float sheenRoughness = 0.0f;           ///< sheenRoughnessFactor in [0,1]
    TextureRef sheenRoughnessTexture;      ///< linear, factor in A
    /// The layers over the BRDF (gpu::LAYER_COAT, LAYER_SHEEN bits; shaders/shared/layers.h):
    /// those whose factor is above 0 (a texture only scales its factor).
    std::uint32_t layers() const {
        return (clearcoat > 0.0f ? gpu::LAYER_COAT : 0u) |
               (sheenColor.x > 0.0f || sheenColor.y > 0.0f || sheenColor.z > 0.0f ? gpu::LAYER_SHEEN : 0u);
    }
    AlphaMode alphaMode = AlphaMode::Opaque;
    float alphaCutoff = 0.5f;              ///< Mask: alpha < cutoff is a hole
    /// KHR_materials_unlit: the loader made it an emitter of the base colour (Material::emit, the
    /// base colour texture as emissiveTexture) that reflects nothing (docs/gltf.md).
    bool unlit = false;
};

struct Material {
    std::string name;
    MaterialType type = MaterialType::Lambertian;
    glm::vec3 albedo{0.0f};  ///< reflectance in [0,1] per channel (lambertian, metal; isotropic: the
                             ///< medium's single-scattering albedo); dielectric: 1
    glm::vec3 emit{0.0f};    ///< emitted radiance (linear RGB); lambertian or diffuse_light
    float fuzz = 0.0f;       ///< metal: radius of the fuzz sphere, in [0,1]
    float ior = 1.5f;        ///< dielectric: index of refraction (relative to the outside)
    bool fresnelExact = false;  ///< dielectric: exact Fresnel equations instead of Schlick
    /// dielectric: Beer-Lambert absorption coefficient inside it, per channel (1/world unit; 0 =
    /// clear): light travelling a distance t inside keeps exp(-absorption t) of itself.
    glm::vec3 absorption{0.0f};
    bool twoSided = false;      ///< both faces emit: diffuse_light's "two_sided"; the loader sets it
                                ///< for every emitting lambertian (which always emits from both faces);
                                ///< Pbr: glTF doubleSided (a single-sided emitter emits from its front only)
    PbrParams pbr;              ///< Pbr only
    /// JSON scenes: a texture (index into Scene::solidTextures) gives the albedo (lambertian, metal, isotropic;
    /// clamped to [0,1]) or the emitted radiance (lambertian, diffuse_light) at each point; -1:
    /// none, the constant above. With an emission texture, emit holds its upper bound
    /// (solidTextureBound), so that emits() and the pick of lights by power see it; with an
    /// albedo texture, albedo is 1 (the kernel replaces it at every hit).
    std::int32_t albedoTexture = -1;
    std::int32_t emitTexture = -1;
    bool emits() const { return emit.x > 0.0f || emit.y > 0.0f || emit.z > 0.0f; }
};

/// Values are the kernel's PRIM_* (shaders/shared/kinds.h).
enum class ShapeType : std::uint32_t { Sphere = gpu::PRIM_SPHERE, Quad = gpu::PRIM_QUAD, Triangle = gpu::PRIM_TRIANGLE };

/// One primitive in world space (its transform already applied), where it is at time 0.
///  - Sphere:   p0 = centre, radius
///  - Quad:     p0 = Q, p1 = u, p2 = v   (points Q + a u + b v, a,b in [0,1]; front face: u x v)
///  - Triangle: p0 = v0, p1 = v1, p2 = v2 (front face: counter-clockwise, (v1-v0) x (v2-v0))
struct Shape {
    ShapeType type = ShapeType::Sphere;
    glm::vec3 p0{0.0f}, p1{0.0f}, p2{0.0f};
    float radius = 0.0f;
    /// Motion blur ("Ray Tracing: The Next Week", sec. 2): the displacement over the shutter
    /// interval (world units). At time t in [0,1) the shape is moved by t velocity (its positions:
    /// a sphere's centre, a quad's Q, a triangle's vertices; shapeAt). 0: it does not move. JSON
    /// scenes only (a sphere's "center1", any object's "motion"); always 0 in InstancedMesh.
    glm::vec3 velocity{0.0f};
    bool moves() const { return velocity.x != 0.0f || velocity.y != 0.0f || velocity.z != 0.0f; }
    std::uint32_t material = 0;  ///< index into Scene::materials
    bool sampled = false;        ///< in the light list: emits, or "sample": true
    /// Triangles from glTF meshes: index into Scene::triangleVertices (their shading attributes);
    /// kNoAttributes for every other shape.
    std::uint32_t attributes = kNoAttributes;
    static constexpr std::uint32_t kNoAttributes = 0xffffffffu;
};

/// The shading attributes of one mesh triangle: its three corners as indices into
/// Scene::vertices, in the order of Shape p0, p1, p2, and which attributes its primitive had.
/// 16 bytes (one uvec4 texel on the GPU).
struct TriangleVertices {
    std::uint32_t v[3] = {0, 0, 0};
    std::uint32_t flags = 0;  ///< kHasNormal | kHasUv | kHasTangent | kHasUv1 | kHasColor (the kernel's ATTR_*, shared/kinds.h)
    static constexpr std::uint32_t kHasNormal = gpu::ATTR_HAS_NORMAL;    ///< else shade with the geometric (flat) normal
    static constexpr std::uint32_t kHasUv = gpu::ATTR_HAS_UV;            ///< else UV = (0,0)
    static constexpr std::uint32_t kHasTangent = gpu::ATTR_HAS_TANGENT;  ///< from the file, or generated for a normal map
    static constexpr std::uint32_t kHasUv1 = gpu::ATTR_HAS_UV1;          ///< TEXCOORD_1 (else none: no texture may use it)
    static constexpr std::uint32_t kHasColor = gpu::ATTR_HAS_COLOR;      ///< COLOR_0 (else white, opaque)
};

/// Per-vertex shading attributes of mesh triangles, in world space, structure of arrays. normal
/// has one entry per vertex; uv and tangent are either empty (no triangle has them) or as long as
/// normal (zeros where a triangle's primitive lacked them: see TriangleVertices::flags).
struct MeshVertices {
    std::vector<glm::vec3> normal;   ///< unit length (zero where the primitive had no NORMAL)
    std::vector<glm::vec2> uv;       ///< TEXCOORD_0 (glTF convention: v down, (0,0) = top left of the image)
    std::vector<glm::vec2> uv1;      ///< TEXCOORD_1 (as uv: empty, or as long as normal)
    std::vector<glm::vec4> tangent;  ///< xyz unit tangent, w = +-1: bitangent = w * cross(normal, tangent.xyz)
    std::vector<glm::vec4> color;    ///< COLOR_0, linear RGBA (alpha 1 for a VEC3 accessor), >= 0 (as uv: empty or as long as normal)
    std::size_t size() const { return normal.size(); }
};

enum class TextureWrap : std::uint32_t { Repeat = 0, ClampToEdge = 1, MirroredRepeat = 2 };

/// A decoded image: RGBA, 8 bits per channel, rows top to bottom (as stored in the file); or, for
/// a high-dynamic-range image of a JSON texture (.hdr, .exr, .pfm), one packed RGB9E5 value per
/// texel in the same 4 bytes (shared/texture_sample.h packRgb9e5; linear RGB, no alpha).
struct TextureImage {
    std::string name;  ///< for messages: the file's image name or URI
    std::uint32_t width = 0, height = 0;
    std::vector<std::uint8_t> rgba8;  ///< width * height * 4 bytes
    bool rgb9e5 = false;              ///< the texels are RGB9E5, not RGBA8
};

/// An image with its sampler, as one material slot uses it.
struct Texture {
    std::uint32_t image = 0;  ///< index into Scene::images
    TextureWrap wrapS = TextureWrap::Repeat, wrapT = TextureWrap::Repeat;
    bool nearest = false;     ///< magFilter NEAREST (default: bilinear)
    bool srgb = false;        ///< colour data (base colour, emissive, specular colour): decode sRGB to linear
};

/// A texture of a JSON scene ("Ray Tracing: The Next Week", sec. 4-5; scenes/README.md
/// "Textures"), evaluated by shaders/shared/solid_texture.h. Kinds are its STEX_*.
struct SolidTexture {
    std::uint32_t kind = gpu::STEX_SOLID;
    glm::vec3 colour{1.0f};   ///< solid: the colour; the others: a factor (linear RGB, >= 0)
    float scale = 1.0f;       ///< checker: the cell size (world units); noise kinds: the frequency
    std::uint32_t even = 0;   ///< checker: index into Scene::solidTextures of the even cells' texture
    std::uint32_t odd = 0;    ///< ... and of the odd cells'
    std::uint32_t texture = 0;  ///< image: index into Scene::textures
};

/// The largest value, per channel, that texture t of `scene` takes anywhere (images: their
/// largest texel; checker: the larger of its two sides). Noise kinds use |noise| <= sqrt(3) (each
/// corner's term is a unit gradient dotted with an offset of length <= sqrt(3), and the Hermite
/// weights sum to 1), so |turb| <= 2 sqrt(3); marble <= 1.
glm::vec3 solidTextureBound(const std::vector<SolidTexture>& textures, const std::vector<TextureImage>& images,
                            const std::vector<Texture>& samplers, std::uint32_t t);

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
    /// Russian roulette may end a path once it has this many rays (camera ray included); below, never.
    std::uint32_t rouletteDepth = 3;
    glm::vec3 background{0.0f};  ///< radiance of escaping rays (linear RGB)
    std::uint32_t seed = 0;
};

/// An environment map ("environment" in the JSON format): an equirectangular image of radiance
/// from infinitely far away (mapping: shaders/shared/environment_map.h). Without one, a non-zero
/// RenderSettings::background is the environment (the same light with constant radiance).
struct Environment {
    std::filesystem::path file;  ///< as resolved (relative to the scene file); empty: no map
    Image image;                 ///< radiance x strength, linear RGB, row 0 = the top (+y)
    float strength = 1.0f;       ///< already applied to image
    float rotateY = 0.0f;        ///< degrees about +y, like an object's rotate_y
    bool hasMap() const { return !image.empty(); }
};

/// An equirectangular radiance map (.hdr, .exr or .pfm: linear; row 0 = +y) read from file, scaled
/// by strength (finite, >= 0) and turned by rotateY degrees about +y. Throws InputError with one
/// line that does not name the file (the caller says where it was named) when it cannot be read, is
/// display-encoded (PNG), has no pixels, holds a negative, NaN or infinite value, or overflows
/// when scaled.
Environment readEnvironmentMap(const std::filesystem::path& file, float strength, float rotateY);

/// A mesh stored once in object space and drawn by several instances: a glTF mesh that two or more
/// nodes of the scene use, or of a file a JSON scene includes several times (and that does not emit:
/// lights are sampled in world space, so emissive meshes are always flattened). The loaders make
/// these only when asked (GltfOptions::instancing, SceneJsonOptions::instancing);
/// host/bvh/two_level.h builds one bottom-level BVH per mesh.
struct InstancedMesh {
    std::string name;           ///< for messages, e.g. "mesh 0 (\"bunny\")"
    std::vector<Shape> shapes;  ///< object-space triangles; Shape::attributes index Scene::triangleVertices
                                ///< as for world-space triangles, but their normals and tangents are in
                                ///< object space (the kernel transforms them at a hit)
};

/// One placement of an InstancedMesh: the node's world matrix (affine, non-singular, finite).
struct MeshInstance {
    std::uint32_t mesh = 0;          ///< index into Scene::meshes
    glm::dmat4 objectToWorld{1.0};   ///< column-major, last row (0, 0, 0, 1)
};

/// A point, spot or directional light (KHR_lights_punctual; the JSON scenes' point_light,
/// spot_light, directional_light): a delta light, sampled by next-event estimation only, never hit
/// by rays (shaders/shared/punctual_light.h). Radiometric units, linear RGB.
struct PunctualLight {
    enum class Kind : std::uint32_t { Point = gpu::PUNCTUAL_POINT, Spot = gpu::PUNCTUAL_SPOT, Directional = gpu::PUNCTUAL_DIRECTIONAL };
    Kind kind = Kind::Point;
    std::string name;              ///< for messages and `vkpath info`, e.g. "light 0 (\"Lamp\")" or "/objects/3"
    glm::vec3 position{0.0f};      ///< point, spot: world units, camera-relative (Scene::origin)
    glm::vec3 direction{0.0f, 0.0f, -1.0f};  ///< spot: its axis; directional: the way the light travels (unit)
    glm::vec3 intensity{0.0f};     ///< point, spot: W/sr; directional: irradiance on a surface facing it, W/m^2
    float innerCone = 0.0f;        ///< spot: radians, 0 <= inner < outer
    float outerCone = 0.785398163f;  ///< spot: radians, <= pi/2 (glTF's default: pi/4)
    /// Emitted power in W (Rec. 709 luminance of the intensity): 4 pi I (point), 2 pi I times the
    /// falloff's solid-angle integral / 2 pi (spot), E pi r^2 for a directional light over a disk
    /// of the scene's bounding radius r (sceneRadius, given).
    double power(double sceneRadius) const;
};

/// A constant-density medium ("Ray Tracing: The Next Week", sec. 9; the JSON scenes'
/// constant_medium; shaders/shared/medium.h): the region inside a convex boundary, a sphere or a
/// box under an affine map (an ellipsoid or a parallelepiped), where light is extinguished at the
/// rate density per unit length and scattered isotropically with its material's albedo. The
/// boundary is no surface: nothing is rendered where it lies.
struct Medium {
    enum class Boundary : std::uint32_t { Sphere = gpu::MEDIUM_SPHERE, Box = gpu::MEDIUM_BOX };
    Boundary boundary = Boundary::Sphere;
    /// From camera-relative world space to the boundary's local space, in which the region is
    /// the unit ball (Sphere) or the cube [-1, 1]^3 (Box): local = toLocal * x + toLocalOffset.
    glm::dmat3 toLocal{1.0};
    glm::dvec3 toLocalOffset{0.0};
    float density = 0.0f;        ///< extinction per world unit, > 0
    std::uint32_t material = 0;  ///< index into Scene::materials: its MaterialType::Isotropic material
    glm::dvec3 lo{0.0}, hi{0.0};  ///< camera-relative bounding box of the region (world units)
    std::string name;            ///< for messages: where the file declares it, e.g. "/objects/7"
};

struct Scene {
    std::filesystem::path path;  ///< file it was loaded from (for messages)
    /// Camera-relative space (pbrt-v4's "camera-world" frame): every position of this Scene
    /// (shapes, camera, instance matrices) is relative to this point of the file's coordinates,
    /// the camera's position, computed in double before anything became float; a point's
    /// file coordinates are origin + its position here. A translation only: directions (the
    /// environment map's among them) are those of the file. docs/design.md "Camera-relative space".
    glm::dvec3 origin{0.0};
    Camera camera;
    RenderSettings render;
    Environment environment;
    std::vector<Material> materials;
    std::vector<Shape> shapes;
    std::vector<std::uint32_t> lights;  ///< indices into shapes of every sampled shape, in file order
    std::vector<PunctualLight> punctualLights;  ///< point, spot and directional lights, in file order
    /// Shared meshes and their instances (two-level BVH); empty unless a glTF file was loaded (or
    /// included) with instancing. Never lights: an instanced mesh does not emit.
    std::vector<InstancedMesh> meshes;
    std::vector<MeshInstance> instances;
    std::vector<TriangleVertices> triangleVertices;  ///< glTF triangles' corners (Shape::attributes)
    MeshVertices vertices;                           ///< their per-vertex attributes
    std::vector<TextureImage> images;
    std::vector<Texture> textures;                   ///< TextureRef::texture indexes this
    std::vector<SolidTexture> solidTextures;         ///< JSON textures (Material::albedoTexture, emitTexture)
    std::vector<Medium> media;                       ///< constant-density media (JSON scenes), at most gpu::MAX_MEDIA
    /// Problems that did not stop loading (e.g. an unsupported glTF extension that is only used),
    /// one line each, "<file>: <place>: <message>"; the command line prints them as warnings.
    std::vector<std::string> warnings;
};

/// Choices of the command line for a JSON scene.
struct SceneJsonOptions {
    /// --instancing auto: a mesh of an included glTF file that is drawn two or more times (by several
    /// nodes, or by one node of a file included several times) and does not emit is stored once in
    /// object space (Scene::meshes) with one Scene::instances entry per placement. false (--instancing
    /// flatten, the library's default): every placement's triangles are in Scene::shapes.
    bool instancing = false;
    /// The image size a scene without "camera" is framed for (its framing camera, as a glTF file
    /// without one gets): one of them alone makes a square; neither: kGltfDefaultImageSide square.
    std::optional<std::uint32_t> width, height;
    /// --allow-path: folders besides the JSON file's own that its included glTF files and its
    /// environment map may be in (file_references.h); an included glTF file's buffers and images
    /// may be in its own folder or these.
    AllowedPaths allowPaths;
};

/// Load a scene in vkpath's JSON format (scenes/README.md). Throws InputError with one line
/// "<file>: <json pointer>: <what is wrong>" on any bad input (inside an included glTF file:
/// "<file>: /objects/<i>: <glTF file>: <place>: <what is wrong>").
Scene loadSceneJson(const std::filesystem::path& file, const SceneJsonOptions& options = {});

/// The same from text already in memory; file is only used in messages and Scene::path.
Scene parseSceneJson(std::string_view text, const std::filesystem::path& file, const SceneJsonOptions& options = {});

/// What the kernel renders for m: m itself, except for an emitting Pbr (diffuse_light) and a
/// transmitting one (exact-Fresnel glass); see host/scene/gltf_kernel_material.cpp. Used by the
/// GPU packing and should be used by anything that chooses kernel features from material types.
Material kernelMaterial(const Material& m);

/// The name of a texture slot of Pbr material m that reads TEXCOORD_1 ("baseColorTexture", ...),
/// or null if none does.
const char* texCoord1Slot(const Material& m);

/// True for a non-emitting Pbr material with transmissionFactor > 0 and a transmissionTexture:
/// the kernel renders it as the glTF BRDF (kernelMaterial) where factor x texture R is 0 and as
/// transmittedMaterial(m) where it is above 0, deciding per hit (lib/surface.glsl).
bool transmissionTextured(const Material& m);

/// What a transmitting Pbr material renders as (transmission > 0, whatever the amount): exact-
/// Fresnel clear glass of index m.ior, or with KHR_materials_ior 0 the book's fuzzy metal (F0 =
/// base colour, fuzz = roughness^2).
Material transmittedMaterial(const Material& m);

/// Calls f(shape) for every shape the scene draws: Scene::shapes (world space) and the triangles of
/// every instanced mesh (object space, once per mesh). For what depends on kinds and materials only.
template <class F>
void forEachShape(const Scene& scene, F&& f) {
    for (const Shape& s : scene.shapes) f(s);
    for (const InstancedMesh& m : scene.meshes)
        for (const Shape& s : m.shapes) f(s);
}

/// Largest |coordinate| a loader places, relative to the camera (Scene::origin): the BVH computes
/// boxes and box centres in float (lo + hi must not overflow 3.4e38), so every shape's bounding box
/// must lie within +-1e38 of the camera. The loaders refuse a shape beyond it, naming it.
inline constexpr double kMaxSceneCoordinate = 1e38;

/// The largest |coordinate| of s's bounding box, computed in double (no overflow): a sphere's
/// centre +- radius, a quad's four corners, a triangle's vertices.
double shapeReach(const Shape& s);

/// Every component of p is finite (a position that fits a float).
inline bool allFinite(glm::vec3 p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

/// Re-express the scene's shapes and instance matrices relative to the point origin + by (in
/// double, rounded to float once): Scene::origin grows by by. The camera is not moved (the caller
/// sets it in the new frame). Throws InputError "<file>: <why>: shape i is outside the range of
/// 32-bit floats relative to the camera" if a moved position overflows.
void moveOrigin(Scene& scene, glm::dvec3 by, std::string_view why);

/// The box (in the scene's frame, double) of every placed shape (a moving one at times 0 and 1) and of every instance (the box
/// of its mesh's object-space box, placed: it may be looser than the placed triangles' own);
/// lo > hi when there is none.
std::pair<glm::dvec3, glm::dvec3> sceneBounds(const Scene& scene);

/// A camera for a scene that has none (glTF files without a camera, JSON scenes without "camera"):
/// vfov 40 degrees, looking along -z at the centre of [lo, hi] from where the box's bounding sphere
/// fits the narrower half angle of a width x height image with 5% to spare. The camera is expressed
/// relative to its own position (lookfrom = 0), which is returned as position, in the frame of lo
/// and hi. Throws InputError naming file when that position does not fit 32-bit floats.
Camera framingCamera(const std::string& file, glm::dvec3 lo, glm::dvec3 hi, std::uint32_t width, std::uint32_t height,
                     glm::dvec3& position);

/// Surface area in world units^2: 4 pi r^2 (sphere), |u x v| (quad), |e1 x e2| / 2 (triangle).
float shapeArea(const Shape& s);

/// s where it is at time t (motion blur): its positions moved by t s.velocity in float, as the
/// kernel moves them (shared/intersect.h primMoved); t = 1 gives the end of the shutter interval.
Shape shapeAt(const Shape& s, float t);

}  // namespace vkp
