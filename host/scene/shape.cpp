#include <numbers>

#include "scene/scene.h"

namespace vkp {

float shapeArea(const Shape& s) {
    switch (s.type) {
    case ShapeType::Sphere: return 4.0f * std::numbers::pi_v<float> * s.radius * s.radius;
    case ShapeType::Quad: return glm::length(glm::cross(s.p1, s.p2));
    case ShapeType::Triangle: return 0.5f * glm::length(glm::cross(s.p1 - s.p0, s.p2 - s.p0));
    }
    return 0.0f;
}

}  // namespace vkp
