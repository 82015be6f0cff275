// GltfIncludes (gltf.h): glTF files placed by a JSON scene, each distinct file read and stored once,
// every include adding its placements (instances of the shared meshes, world-space triangles of the rest).
#include <system_error>

#include "scene/gltf_parts.h"

namespace vkp {

/// One distinct include: its document and placement state while includes of it remain.
struct GltfIncludes::File {
    std::uint32_t expected = 0;  ///< includes announced by expect()
    std::uint32_t appended = 0;  ///< includes placed so far
    std::unique_ptr<gltf::Document> doc;
    std::unique_ptr<gltf::PlacementState> state;
};

GltfIncludes::GltfIncludes(Scene& scene, bool instancing, AllowedPaths allowed)
    : scene_(scene), instancing_(instancing), allowed_(std::move(allowed)) {}
GltfIncludes::~GltfIncludes() = default;

GltfIncludes::Key GltfIncludes::key(const std::filesystem::path& file, const GltfInclude& include) {
    std::error_code ec;
    std::filesystem::path canonical = std::filesystem::canonical(file, ec);
    if (ec) canonical = file.lexically_normal();
    return {canonical.string(), include.sceneIndex ? std::int64_t(*include.sceneIndex) : -1,
            include.material ? std::int64_t(*include.material) : -1, include.velocity.x, include.velocity.y,
            include.velocity.z};
}

void GltfIncludes::expect(const std::filesystem::path& file, const GltfInclude& include) {
    std::unique_ptr<File>& f = files_[key(file, include)];
    if (!f) f = std::make_unique<File>();
    ++f->expected;
}

void GltfIncludes::append(const std::filesystem::path& file, const GltfInclude& include) {
    std::unique_ptr<File>& f = files_[key(file, include)];
    if (!f) f = std::make_unique<File>();
    const bool first = !f->doc;
    if (first) {
        f->doc = std::make_unique<gltf::Document>(gltf::readDocument(file, allowed_));
        scene_.warnings.insert(scene_.warnings.end(), f->doc->warnings.begin(), f->doc->warnings.end());
        f->state = std::make_unique<gltf::PlacementState>(
            gltf::PlacementState{gltf::MaterialMapper(*f->doc, scene_, include.material)});
    }
    Scene ignoredWarnings;  // a later include repeats the first one's warnings about nodes
    const gltf::Instances inst = gltf::traverse(*f->doc, include.sceneIndex, include.transform, first ? scene_ : ignoredWarnings);
    // Motion blur moves world-space triangles: a moving include is not instanced.
    const bool moving = include.velocity != glm::dvec3(0.0);
    const std::size_t firstShape = scene_.shapes.size();
    gltf::appendInstances(*f->doc, inst, *f->state, instancing_ && !moving, std::max<std::uint32_t>(f->expected, 1), scene_);
    for (std::size_t i = firstShape; i < scene_.shapes.size(); ++i) scene_.shapes[i].velocity = glm::vec3(include.velocity);
    gltf::appendLights(*f->doc, inst, scene_);
    // The last announced include: the document is no longer needed (an include not announced would
    // read the file again, as a file of its own).
    if (++f->appended >= f->expected) {
        f->state.reset();
        f->doc.reset();
        f->appended = 0;
        f->expected = 0;
    }
}

}  // namespace vkp
