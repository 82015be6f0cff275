// The pieces of the glTF loader (gltf.h), one file each. Internal to host/scene.
//   gltf_document.cpp   the file -> tinygltf::Model (GLB checks, file access, image decoding, extensions)
//   gltf_uri.cpp        the buffers' and images' uris, checked and resolved before tinygltf reads them
//   gltf_compression.cpp EXT_meshopt_compression and KHR_draco_mesh_compression, decoded to plain buffers
//   gltf_accessor.cpp   validated accessor reads (strides, sparse, normalized integers)
//   gltf_mesh.cpp       primitives -> world-space triangles, vertex attributes, lights
//   gltf_material.cpp   materials, textures, samplers -> Scene (MaterialType::Pbr)
//   gltf_camera.cpp     glTF camera or a framing camera -> Camera, image size
//   gltf_scene.cpp      node hierarchy, placement of a scene's meshes (flattened or instanced), loadSceneGltf
//   gltf_include.cpp    GltfIncludes: files included by a JSON scene, each read and stored once
#pragma once
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>
#include <tiny_gltf.h>

#include "scene/file_references.h"
#include "scene/gltf.h"
#include "scene/scene.h"

namespace vkp::gltf {

/// A glTF file read and checked at the document level.
struct Document {
    std::string file;  ///< the path as given (for messages)
    tinygltf::Model model;
    std::vector<std::string> warnings;  ///< "<file>: <place>: <message>" lines
};

/// Throw InputError "<file>: <place>: <message>" (forced onto one line).
[[noreturn]] void fail(const std::string& file, const std::string& place, const std::string& message);
/// "<file>: <place>: <message>" on one line, for warnings.
std::string line(const std::string& file, const std::string& place, const std::string& message);
/// Add warning (a line()) to scene.warnings unless it is there already: for what each primitive,
/// light or include of a file would otherwise repeat.
void warnOnce(Scene& scene, std::string warning);

/// Read a .gltf or .glb (by content: GLB starts with "glTF"), its buffers and images (decoded to
/// RGBA8 with stb_image). Refuses a malformed GLB container, JSON nested deeper than 256 levels,
/// a buffer or image uri outside the file's folder and `allowed` (file_references.h), a missing or
/// unreadable buffer or image, a glTF major version other than 2, and any extension in
/// extensionsRequired that vkpath does not implement; warns about one only in extensionsUsed.
Document readDocument(const std::filesystem::path& file, const AllowedPaths& allowed = {});

/// One external file of a glTF document: the file to read and the place for messages
/// ("buffer 2: uri \"x.bin\"", the uri as the file writes it).
struct ExternalFile {
    std::filesystem::path file;  ///< canonical (file_references.h resolveReference)
    std::string place;
};
/// Every buffer and image uri of the document's JSON text that names a file (not a data: URI),
/// keyed by the path tinygltf 2.7 will ask its file callbacks for (base + "/" + its decoding of the
/// uri). Each uri is checked first: valid percent-encoding, a relative path or a file:///path URI
/// (no other scheme), resolving inside base (the document's folder, canonical) or `allowed`.
/// Throws InputError "<file>: buffer|image <i>: uri \"<uri>\": <problem>". Returns nothing for
/// text that is not a JSON object (tinygltf reports it).
std::map<std::string, ExternalFile> externalFiles(std::string_view json, const std::string& file,
                                                  const std::filesystem::path& base, const AllowedPaths& allowed);

/// What rewriteForTinygltf changed in a file that uses compressed meshes, for the decoders to undo.
struct Rewritten {
    /// EXT_meshopt_compression fallback buffers (no uri: the data exists only compressed), given a
    /// one-byte placeholder: buffer index -> the byteLength the file gives.
    std::map<std::size_t, std::uint64_t> fallbackLength;
    /// KHR_draco_mesh_compression indices accessors (no bufferView) given the stream's bufferView.
    std::vector<std::size_t> borrowedIndexViews;
};
/// The JSON text changed so that tinygltf 2.7 reads a file with compressed meshes (empty: no
/// change needed).
std::string rewriteForTinygltf(std::string_view json, const std::string& file, Rewritten& out);
/// Decode every EXT_meshopt_compression bufferView into its own buffer (the fallback buffers get
/// the bytes their views cover). Refuses malformed streams naming the bufferView.
void decodeMeshopt(Document& doc, const Rewritten& rewritten);
/// Decode every KHR_draco_mesh_compression primitive into new buffers, bufferViews and accessors
/// (copies of the primitive's, which then point at them). Refuses a mismatch naming the primitive.
void decodeDraco(Document& doc, const Rewritten& rewritten);

/// Member key of a tinygltf object value (an extension), or null.
const tinygltf::Value* member(const tinygltf::Value& object, const char* key);

/// Bytes of one component of glTF componentType type (0 for a type glTF 2.0 accessors do not have).
int componentSize(int type);

/// Extensions vkpath reads (every other one is refused when required, warned about when used).
bool extensionImplemented(const std::string& name);

/// "mesh 2 ("box") primitive 0"
std::string primitivePlace(const Document& doc, std::size_t mesh, std::size_t primitive);
/// "node 4 ("camera")"
std::string nodePlace(const Document& doc, std::size_t node);

/// One accessor, validated on construction against its bufferView and buffer (bounds with
/// strides, counts, component types, sparse indices and values), so reads cannot go out of range.
class Accessor {
public:
    /// use says what the accessor is for in messages ("POSITION of mesh 0 primitive 1"); its type
    /// must have components (1 SCALAR .. 4 VEC4) of one of the allowed TINYGLTF_COMPONENT_TYPE_*.
    Accessor(const Document& doc, int index, std::string use, int components, std::initializer_list<int> allowed);

    std::size_t count() const { return count_; }
    int components() const { return components_; }  ///< 1 (SCALAR) .. 4 (VEC4)
    int componentType() const { return componentType_; }
    bool normalized() const { return normalized_; }

    /// Every element as floats, count() * components() values: normalized integers map to [0,1] or
    /// [-1,1] (glTF 2.0 sec. 3.11), other integers to their value; sparse substitution applied.
    std::vector<float> floats() const;
    /// Every element of a SCALAR accessor of unsigned integers (indices), sparse substitution applied.
    std::vector<std::uint32_t> uints() const;

    [[noreturn]] void fail(const std::string& message) const;
    std::string place() const;

private:
    template <class Out>
    void readDense(Out* out) const;
    template <class Out>
    void applySparse(Out* out) const;

    const Document* doc_;
    int index_;
    std::string use_;
    std::size_t count_ = 0;
    int components_ = 0;
    int componentType_ = 0;
    bool normalized_ = false;
    const std::uint8_t* data_ = nullptr;  ///< first element; null: no bufferView (zeros)
    std::size_t stride_ = 0;
    // sparse (count 0: none)
    std::size_t sparseCount_ = 0;
    const std::uint8_t* sparseIndices_ = nullptr;
    int sparseIndexType_ = 0;
    const std::uint8_t* sparseValues_ = nullptr;
};

/// Turns glTF materials into Scene materials on first use (or maps every one to an override).
class MaterialMapper {
public:
    MaterialMapper(const Document& doc, Scene& scene, std::optional<std::uint32_t> override);
    /// Scene material index for glTF material index m (-1: the glTF default material).
    std::uint32_t material(int m);

private:
    TextureRef textureRef(const tinygltf::TextureInfo& info, bool srgb, const std::string& place);
    TextureRef textureRef(int index, int texCoord, const tinygltf::ExtensionMap& extensions, bool srgb,
                          const std::string& place);
    /// A textureInfo inside an extension, {"index", "texCoord", "extensions"}, which tinygltf leaves as a value.
    TextureRef extensionTexture(const tinygltf::Value* object, const char* key, bool srgb, const std::string& place);
    std::uint32_t texture(int index, bool srgb, const std::string& place);
    Material convert(int m);

    const Document& doc_;
    Scene& scene_;
    std::optional<std::uint32_t> override_;
    std::vector<std::int64_t> materialIndex_;  ///< glTF material -> Scene index (-1: not yet), last: default
    std::vector<std::int64_t> imageIndex_;     ///< glTF image -> Scene::images index
    std::vector<std::int64_t> textureIndex_;   ///< (glTF texture, srgb) -> Scene::textures index
};

/// Triangles and vertices a primitive yields (after strip / fan conversion), from accessor counts
/// only. Points and lines (modes 0-3) yield nothing (drawn = false: vkpath renders surfaces);
/// refuses an unknown mode and a missing POSITION.
struct PrimitiveSize {
    std::uint64_t triangles = 0;
    std::uint64_t vertices = 0;
    bool drawn = true;
};
/// True for the modes vkpath skips (POINTS, LINES, LINE_LOOP, LINE_STRIP).
bool pointsOrLines(int mode);
/// "POINTS", "LINES", ... "TRIANGLE_FAN" ("unknown" for other values).
const char* primitiveModeName(int mode);
PrimitiveSize primitiveSize(const Document& doc, std::size_t mesh, std::size_t primitive);

/// Append one instance of a primitive, placed by world (column vectors, p_world = world * p), to
/// scene: shapes (triangles, winding flipped when det(world) < 0 so the front stays the side the
/// glTF front maps to), TriangleVertices, MeshVertices, and the light list for emitting materials.
/// Refuses bad indices, non-finite positions, normals or coordinates out of float range.
void appendPrimitive(const Document& doc, std::size_t mesh, std::size_t primitive, const glm::dmat4& world,
                     std::uint32_t material, Scene& scene);

/// The camera of glTF camera c placed by its node's world matrix; the image size from options
/// and the camera's aspectRatio. Refuses orthographic cameras and invalid perspective values.
Camera cameraFromGltf(const Document& doc, std::size_t c, const glm::dmat4& world, const GltfOptions& options);
/// A camera looking along -z at the centre of [lo, hi] (vfov 40 degrees) that sees all of it
/// (file: for the message when that does not fit in floats). The camera is expressed relative to
/// its own position (lookfrom = 0), which is returned as position, in the frame of lo and hi.
Camera framingCamera(const std::string& file, glm::dvec3 lo, glm::dvec3 hi, const GltfOptions& options,
                     glm::dvec3& position);
/// Width and height: both options; one of them and the aspect ratio (width / height, > 0); or
/// kGltfDefaultImageSide on the long side.
void imageSize(double aspect, const GltfOptions& options, Camera& camera);

/// One node that draws a mesh, with its world matrix (root * hierarchy, column vectors).
struct MeshInstance {
    std::size_t node = 0;
    std::size_t mesh = 0;
    glm::dmat4 world{1.0};
};
/// One node that carries a camera, with its world matrix.
struct CameraInstance {
    std::size_t node = 0;
    std::size_t camera = 0;
    glm::dmat4 world{1.0};
};
/// One node that carries a KHR_lights_punctual light, with its world matrix.
struct LightInstance {
    std::size_t node = 0;
    std::size_t light = 0;  ///< index into the model's lights
    glm::dmat4 world{1.0};
};
struct Instances {
    std::vector<MeshInstance> meshes;     ///< in depth-first order of the hierarchy
    std::vector<CameraInstance> cameras;  ///< in depth-first order of the hierarchy
    std::vector<LightInstance> lights;    ///< in depth-first order of the hierarchy
};

/// The punctual lights placed by inst.lights (KHR_lights_punctual), appended to scene.punctualLights
/// in radiometric units (candela and lux / kLumensPerWatt), positioned by their nodes' world
/// matrices (already camera-relative) and pointing along the node's -Z. Throws InputError naming
/// the light (and the node) for a light vkpath cannot render.
void appendLights(const Document& doc, const Instances& inst, Scene& scene);

/// Every mesh and camera instance of the chosen scene (sceneIndex; default: the file's "scene",
/// else 0), with world matrices root * hierarchy. Warnings (skins) go to out.warnings.
Instances traverse(const Document& doc, std::optional<std::uint32_t> sceneIndex, const glm::dmat4& root, Scene& out);

/// What one file's placements share: its materials (mapped once into the scene), which meshes are
/// stored once (decided at the first placement) and where (Scene::meshes index, -1: not yet).
struct PlacementState {
    MaterialMapper materials;
    bool decided = false;
    std::vector<std::vector<std::uint32_t>> meshMaterials;  ///< scene material per primitive, per shared mesh
    std::vector<char> shared;                               ///< per glTF mesh: stored once, drawn by instances
    std::vector<std::int64_t> meshSlot;                     ///< per glTF mesh: index into Scene::meshes
};

/// Append one placement (inst: the traversed nodes, already under the placement's root matrix) of
/// a file to scene: the triangles of unshared meshes in world space, and, with instancing, the
/// meshes drawn at least twice (nodes using it x includes, the file placed `includes` times) and
/// not emitting stored once in object space (at their first use) plus one Scene::instances entry
/// per node. The first call decides what is shared and gives the warnings about morph targets and
/// animations. Refuses more than kGltfMaxTriangles / kGltfMaxVertices new triangles / vertices in
/// one call (a mesh already stored counts 0). Returns the world bounds of what was placed.
std::pair<glm::dvec3, glm::dvec3> appendInstances(const Document& doc, const Instances& inst, PlacementState& state,
                                                  bool instancing, std::uint32_t includes, Scene& scene);

}  // namespace vkp::gltf
