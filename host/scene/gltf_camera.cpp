// glTF cameras -> the book's camera (lookfrom / lookat / vup / vfov). A glTF camera looks along
// its node's local -Z with +Y up (glTF 2.0 sec. 3.10.1); yfov is the vertical field of view in radians.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/errors.h"
#include "scene/gltf_parts.h"
#include "scene/scene_json_parts.h"

namespace vkp::gltf {

namespace {

std::uint32_t clampSide(double x) {
    return std::uint32_t(std::clamp(std::round(x), 1.0, double(scenejson::kMaxImageSide)));
}

}  // namespace

void imageSize(double aspect, const GltfOptions& options, Camera& camera) {
    if (!(aspect > 0.0) || !std::isfinite(aspect)) aspect = 1.0;
    if (options.width && options.height) {
        camera.width = *options.width;
        camera.height = *options.height;
    } else if (options.width) {
        camera.width = *options.width;
        camera.height = clampSide(*options.width / aspect);
    } else if (options.height) {
        camera.height = *options.height;
        camera.width = clampSide(*options.height * aspect);
    } else if (aspect >= 1.0) {
        camera.width = kGltfDefaultImageSide;
        camera.height = clampSide(kGltfDefaultImageSide / aspect);
    } else {
        camera.height = kGltfDefaultImageSide;
        camera.width = clampSide(kGltfDefaultImageSide * aspect);
    }
}

Camera cameraFromGltf(const Document& doc, std::size_t c, const glm::dmat4& world, const GltfOptions& options) {
    const auto& cameras = doc.model.cameras;
    if (c >= cameras.size()) {
        fail(doc.file, "camera " + std::to_string(c), "does not exist (the file has " + std::to_string(cameras.size()) + " cameras)");
    }
    const tinygltf::Camera& g = cameras[c];
    const std::string place = "camera " + std::to_string(c) + (g.name.empty() ? "" : " (\"" + g.name + "\")");
    if (g.type != "perspective") {
        fail(doc.file, place, "is " + (g.type.empty() ? std::string("of no type") : g.type) +
                                  ": vkpath renders perspective cameras only");
    }
    const double yfov = g.perspective.yfov;
    if (!(yfov > 0.0 && yfov < std::numbers::pi)) {
        fail(doc.file, place + "/perspective/yfov", "must be in (0, pi) radians (got " + std::to_string(yfov) + ")");
    }
    const double aspect = g.perspective.aspectRatio;  // 0: not given
    if (!(aspect >= 0.0) || !std::isfinite(aspect)) {
        fail(doc.file, place + "/perspective/aspectRatio", "must be > 0 (got " + std::to_string(aspect) + ")");
    }

    const glm::dvec3 origin(world * glm::dvec4(0.0, 0.0, 0.0, 1.0));
    const glm::dvec3 forward = glm::dmat3(world) * glm::dvec3(0.0, 0.0, -1.0);
    const glm::dvec3 up = glm::dmat3(world) * glm::dvec3(0.0, 1.0, 0.0);
    const double fl = glm::length(forward), ul = glm::length(up);
    if (!(fl > 0.0) || !(ul > 0.0) || !std::isfinite(fl) || !std::isfinite(ul) ||
        scenejson::parallelOrZero(glm::vec3(forward), glm::vec3(up)) || !std::isfinite(float(glm::length(origin)))) {
        fail(doc.file, place, "its node's transform leaves no view direction and up vector (zero scale?)");
    }
    Camera cam;
    cam.lookfrom = glm::vec3(origin);
    cam.lookat = glm::vec3(origin + forward / fl);  // unit distance: the glTF camera has no focus distance
    cam.vup = glm::vec3(up / ul);
    cam.vfov = float(yfov * 180.0 / std::numbers::pi);
    cam.defocusAngle = 0.0f;
    cam.focusDist = glm::length(cam.lookat - cam.lookfrom);
    imageSize(aspect, options, cam);
    return cam;
}

Camera framingCamera(const std::string& file, glm::dvec3 lo, glm::dvec3 hi, const GltfOptions& options,
                     glm::dvec3& position) {
    Camera size;
    imageSize(1.0, options, size);
    try {
        return vkp::framingCamera(file, lo, hi, size.width, size.height, position);
    } catch (const InputError&) {
        fail(file, "cameras", "the file has no camera and its scene is too large to frame in 32-bit floats");
    }
}

}  // namespace vkp::gltf
