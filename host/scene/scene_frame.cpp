// Camera-relative space (docs/design.md "Camera-relative space"): moving a loaded scene's frame.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "core/errors.h"
#include "scene/scene.h"

namespace vkp {

void moveOrigin(Scene& scene, glm::dvec3 by, std::string_view why) {
    if (by == glm::dvec3(0.0)) return;
    auto move = [&](glm::vec3& p, std::size_t shape) {
        p = glm::vec3(glm::dvec3(p) - by);
        if (!allFinite(p)) {
            throw InputError(scene.path.string() + ": " + std::string(why) + ": shape " + std::to_string(shape) +
                             " is outside the range of 32-bit floats relative to the camera");
        }
    };
    for (std::size_t i = 0; i < scene.shapes.size(); ++i) {
        Shape& s = scene.shapes[i];
        move(s.p0, i);  // a quad's p1, p2 and a sphere's radius are not positions
        if (s.type == ShapeType::Triangle) {
            move(s.p1, i);
            move(s.p2, i);
        }
    }
    for (MeshInstance& mi : scene.instances) mi.objectToWorld[3] -= glm::dvec4(by, 0.0);
    for (PunctualLight& l : scene.punctualLights) {
        if (l.kind == PunctualLight::Kind::Directional) continue;
        l.position = glm::vec3(glm::dvec3(l.position) - by);
        if (!allFinite(l.position)) {
            throw InputError(scene.path.string() + ": " + std::string(why) + ": " + l.name +
                             " is outside the range of 32-bit floats relative to the camera");
        }
    }
    for (Medium& m : scene.media) {  // local = T x_old + o = T (x_new + by) + o
        m.toLocalOffset += m.toLocal * by;
        m.lo -= by;
        m.hi -= by;
    }
    scene.origin += by;
}

namespace {
/// Grows [lo, hi] by shape s (a sphere's box, a quad's four corners, a triangle's three).
void growByShape(const Shape& s, glm::dvec3& lo, glm::dvec3& hi) {
    auto at = [&](glm::dvec3 p) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    };
    const glm::dvec3 p0(s.p0), p1(s.p1), p2(s.p2);
    switch (s.type) {
        case ShapeType::Sphere:
            at(p0 - glm::dvec3(s.radius));
            at(p0 + glm::dvec3(s.radius));
            break;
        case ShapeType::Quad:  // p1, p2: the edges u, v
            at(p0);
            at(p0 + p1);
            at(p0 + p2);
            at(p0 + p1 + p2);
            break;
        case ShapeType::Triangle:
            at(p0);
            at(p1);
            at(p2);
            break;
    }
}

constexpr double kHuge = std::numeric_limits<double>::max();
}  // namespace

std::pair<glm::dvec3, glm::dvec3> sceneBounds(const Scene& scene) {
    glm::dvec3 lo(kHuge), hi(-kHuge);
    for (const Shape& s : scene.shapes) {
        growByShape(s, lo, hi);
        if (s.moves()) growByShape(shapeAt(s, 1.0f), lo, hi);  // and where it ends (motion blur)
    }
    // An instanced mesh's object-space box once, then its eight corners per instance: a box of
    // the placed mesh, at the cost of the instances and not of their triangles.
    std::vector<std::pair<glm::dvec3, glm::dvec3>> meshBoxes(scene.meshes.size(), {glm::dvec3(kHuge), glm::dvec3(-kHuge)});
    for (std::size_t m = 0; m < scene.meshes.size(); ++m)
        for (const Shape& s : scene.meshes[m].shapes) growByShape(s, meshBoxes[m].first, meshBoxes[m].second);
    for (const MeshInstance& mi : scene.instances) {
        const auto& [mlo, mhi] = meshBoxes.at(mi.mesh);
        if (!(mlo.x <= mhi.x)) continue;  // an empty mesh
        for (int corner = 0; corner < 8; ++corner) {
            const glm::dvec3 p((corner & 1) ? mhi.x : mlo.x, (corner & 2) ? mhi.y : mlo.y, (corner & 4) ? mhi.z : mlo.z);
            const glm::dvec3 w(mi.objectToWorld * glm::dvec4(p, 1.0));
            lo = glm::min(lo, w);
            hi = glm::max(hi, w);
        }
    }
    return {lo, hi};
}

Camera framingCamera(const std::string& file, glm::dvec3 lo, glm::dvec3 hi, std::uint32_t width, std::uint32_t height,
                     glm::dvec3& position) {
    Camera cam;
    cam.width = width;
    cam.height = height;
    glm::dvec3 centre(0.0);
    double radius = 1.0;
    if (lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z) {
        centre = 0.5 * (lo + hi);
        radius = std::max(0.5 * glm::length(hi - lo), 1e-3 * std::max(1.0, glm::length(centre)));
    }
    constexpr double kVfovDeg = 40.0;
    const double vHalf = kVfovDeg * std::numbers::pi / 360.0;
    const double hHalf = std::atan(std::tan(vHalf) * double(cam.width) / double(cam.height));
    // The bounding sphere of the box fits inside the narrower of the two half angles, with 5% to spare.
    const double dist = 1.05 * radius / std::sin(std::min(vHalf, hHalf));
    position = centre + glm::dvec3(0.0, 0.0, dist);  // looking along -z, as glTF assets expect
    cam.lookfrom = glm::vec3(0.0f);
    cam.lookat = glm::vec3(centre - position);
    cam.vup = glm::vec3(0.0f, 1.0f, 0.0f);
    cam.vfov = float(kVfovDeg);
    cam.focusDist = float(dist);
    if (!std::isfinite(position.x) || !std::isfinite(position.y) || !std::isfinite(position.z) ||
        !std::isfinite(cam.focusDist)) {
        throw InputError(file + ": the scene has no camera and is too large to frame in 32-bit floats");
    }
    return cam;
}

}  // namespace vkp
