// The sections of a JSON scene (scenes/README.md), one reader each. Internal to host/scene.
#pragma once
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "scene/json_reader.h"
#include "scene/scene.h"

namespace vkp::scenejson {

/// Largest image side, in pixels.
inline constexpr std::uint32_t kMaxImageSide = 16384;
/// Largest spp: the accumulation buffer counts samples in a float, exact up to 2^24.
inline constexpr std::uint32_t kMaxSpp = 1u << 24;
/// Largest max_depth (the shader's loop guard ends longer paths anyway).
inline constexpr std::uint32_t kMaxDepth = 1024;

/// "camera": the book's camera; focus_dist defaults to |lookfrom - lookat|. lookfrom (read in
/// double) is returned as origin, the camera-relative frame's origin in the file's coordinates;
/// the camera itself is expressed in that frame (lookfrom = 0, lookat = lookat - lookfrom).
Camera readCamera(const json::Value& v, glm::dvec3& origin);
/// "render": spp, max_depth, background, seed (all optional).
RenderSettings readRender(const json::Value& v);
/// "textures" (name -> texture) and every colour that may be a texture (scenes/README.md
/// "Textures"): appends Scene::solidTextures, and the images of image textures to Scene::images and
/// Scene::textures, as materials use them. Image files must resolve inside the scene's folder or
/// `allowed` (file_references.h); each is read once.
class TextureReader {
public:
    TextureReader(Scene& scene, std::filesystem::path sceneFile, AllowedPaths allowed, std::optional<json::Value> named);
    /// A colour ([r, g, b], each in range: sets colour, returns -1) or a texture (an object, or the
    /// name of one in "textures"; its colours in range): its index into Scene::solidTextures
    /// (colour set to 1).
    std::int32_t colourOrTexture(const json::Value& v, const json::Range& range, glm::vec3& colour);
    /// Reads the named textures no material used (their mistakes are errors too), then drops
    /// what they added.
    void finish();

private:
    std::uint32_t texture(const json::Value& v, const json::Range& range);
    std::uint32_t named(const json::Value& v, const json::Range& range);
    std::uint32_t image(const json::Value& fileValue, bool nearest);
    std::uint32_t add(SolidTexture t);

    Scene& scene_;
    std::filesystem::path sceneFile_;
    AllowedPaths allowed_;
    std::map<std::string, json::Value> named_;
    std::map<std::pair<std::string, std::pair<double, double>>, std::uint32_t> done_;  // (name, range) -> texture
    std::set<std::string> resolving_;                                                  // names being read (cycles)
    std::map<std::pair<std::string, bool>, std::uint32_t> images_;                      // (path, nearest) -> Scene::textures
    std::vector<std::uint32_t> depth_;  // per solid texture: checkers on its longest way to a colour
};

/// A box's "min" and "max" corners of object o, each max above its min (else the one-line error
/// at the offending max element): the "box" object's and a medium's box boundary's.
std::pair<glm::dvec3, glm::dvec3> readBoxCorners(json::Object& o);
/// {"type": "constant_medium", "boundary": sphere or box, "density": d, "albedo": colour or
/// texture} of "objects" (scenes/README.md "Media"): the medium, whose isotropic material it
/// appends to Scene::materials. At most gpu::MAX_MEDIA per scene.
Medium readMedium(const json::Value& v, TextureReader& textures, Scene& scene);
/// "materials": name -> material, appended in file order; index maps a name to its position.
/// Colours that may be textures are read through `textures`.
void readMaterials(const json::Value& v, Scene& scene, std::map<std::string, std::uint32_t>& index, TextureReader& textures);
/// "objects": appends world-space shapes, media (their colours and textures read through
/// `textures`) and the light list; included glTF files through
/// GltfIncludes (each file read once; with instancing, meshes drawn twice or more stored once).
/// Included files must resolve inside the scene's folder or options.allowPaths (file_references.h).
void readObjects(const json::Value& v, const std::map<std::string, std::uint32_t>& index,
                 const SceneJsonOptions& options, TextureReader& textures, Scene& scene);

/// "environment": file (resolved against sceneFile's folder, and inside it or `allowed`; read with
/// core/image_io), strength, rotate_y. Image problems are reported at /environment/file.
Environment readEnvironment(const json::Value& v, const std::filesystem::path& sceneFile, const AllowedPaths& allowed);

/// |a x b| <= 1e-6 |a| |b| (in double): a and b are parallel (to float precision) or one of them
/// is zero (also true for NaN).
bool parallelOrZero(glm::dvec3 a, glm::dvec3 b);
inline bool parallelOrZero(glm::vec3 a, glm::vec3 b) { return parallelOrZero(glm::dvec3(a), glm::dvec3(b)); }

}  // namespace vkp::scenejson
