// Camera-relative space (docs/design.md "Camera-relative space"): moving a loaded scene's frame.
#include <cmath>

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
    scene.origin += by;
}

}  // namespace vkp
