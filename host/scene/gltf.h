// glTF 2.0 scenes (.gltf with external or embedded buffers, .glb) -> Scene, read with Debian's
// tinygltf. What is read and how it maps to the Scene is in scenes/README.md ("glTF").
#pragma once
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <tuple>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace vkp {

/// Choices of the command line for a glTF scene.
struct GltfOptions {
    std::optional<std::uint32_t> scene;   ///< --gltf-scene N (default: the file's "scene", else scene 0)
    std::optional<std::uint32_t> camera;  ///< --camera N: index into the file's cameras (default: the first
                                          ///< perspective camera a node of the scene uses)
    /// --width / --height: both given: that size; one given: the other follows the camera's aspect
    /// ratio; none: 512 pixels on the long side.
    std::optional<std::uint32_t> width, height;
    /// --instancing auto: a mesh that two or more nodes use, and that does not emit, is stored once
    /// in object space (Scene::meshes) with one Scene::instances entry per node, for a two-level
    /// BVH. false (--instancing flatten): every node's triangles are placed in the world (Scene::shapes).
    bool instancing = false;
    /// --allow-path: folders besides the file's own that its buffers and images may be in
    /// (file_references.h).
    AllowedPaths allowPaths;
};

/// Default long side of the image, in pixels, when neither the file nor the options give a size.
inline constexpr std::uint32_t kGltfDefaultImageSide = 512;
/// Most triangles one load may produce (counted over every node that instances a mesh; a mesh
/// stored once for instancing counts once).
inline constexpr std::uint64_t kGltfMaxTriangles = 1ull << 26;
/// Most vertices one load may produce (over every instanced primitive).
inline constexpr std::uint64_t kGltfMaxVertices = 1ull << 26;

/// Load a glTF 2.0 file as a whole scene: the triangles of the chosen scene's node hierarchy
/// (world space), its materials (MaterialType::Pbr) and textures, emissive triangles as lights,
/// and a camera (the file's, or one that frames the scene's bounds). Render settings are the JSON
/// defaults. Warnings (e.g. an extension used but not supported) go to Scene::warnings.
/// Throws InputError with one line "<file>: <place>: <what is wrong>", where place names the
/// mesh / primitive / accessor / material / node / image.
Scene loadSceneGltf(const std::filesystem::path& file, const GltfOptions& options = {});

/// How a glTF file is placed into an existing scene (the JSON object {"type": "gltf", ...}).
struct GltfInclude {
    glm::dmat4 transform{1.0};              ///< applied after the file's node transforms
    std::optional<std::uint32_t> material;  ///< every triangle gets this Scene material instead of the file's
    std::optional<std::uint32_t> sceneIndex;  ///< default: the file's default scene
    /// Motion blur: every triangle's displacement over the shutter interval (Shape::velocity,
    /// world units). A moving include is never instanced: its triangles are placed in the world,
    /// where each moves on its own (an instance's triangles are in object space).
    glm::dvec3 velocity{0.0};
};

/// The glTF files a JSON scene includes (objects {"type": "gltf", ...}). Each distinct (canonical
/// file path, scene, material override) is read once and its materials and textures are appended
/// to the scene once; every include places its scene again under its transform. With instancing,
/// a mesh that the file draws at least twice in all (nodes using it x includes of the file) and
/// that does not emit is stored once in object space (Scene::meshes), with one Scene::instances
/// entry per node and include (include transform x node world matrix); every other mesh (and
/// every mesh without instancing, and every mesh of a moving include) is placed in the world per
/// include, emissive triangles as lights.
class GltfIncludes {
public:
    /// scene receives every include; it is kept by reference and must not move while this lives.
    /// allowed: folders besides each included file's own that its buffers and images may be in.
    GltfIncludes(Scene& scene, bool instancing, AllowedPaths allowed = {});
    ~GltfIncludes();
    GltfIncludes(const GltfIncludes&) = delete;
    GltfIncludes& operator=(const GltfIncludes&) = delete;

    /// Announce an include before the first append(), once per include that append() will get, so
    /// that a file included n times is known to be drawn n times. Never throws for a bad file.
    void expect(const std::filesystem::path& file, const GltfInclude& include);
    /// Place one include (the file is read at its first include). Throws InputError like
    /// loadSceneGltf: one line "<file>: <place>: <what is wrong>".
    void append(const std::filesystem::path& file, const GltfInclude& include);

private:
    struct File;
    /// canonical path, scene, material (-1: none), velocity (a moving include is placed apart)
    using Key = std::tuple<std::string, std::int64_t, std::int64_t, double, double, double>;
    static Key key(const std::filesystem::path& file, const GltfInclude& include);
    Scene& scene_;
    bool instancing_;
    AllowedPaths allowed_;
    std::map<Key, std::unique_ptr<File>> files_;
};

}  // namespace vkp
