#include <algorithm>
#include <cmath>
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

Shape shapeAt(const Shape& s, float t) {
    Shape out = s;
    const glm::vec3 shift = t * s.velocity;
    out.p0 += shift;
    if (s.type == ShapeType::Triangle) {
        out.p1 += shift;
        out.p2 += shift;
    }
    return out;
}

}  // namespace vkp

namespace vkp {

double shapeReach(const Shape& s) {
    auto reach = [](glm::dvec3 p) { return std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}); };
    const glm::dvec3 p0(s.p0), p1(s.p1), p2(s.p2);
    switch (s.type) {
    case ShapeType::Sphere: return reach(p0) + std::abs(double(s.radius));
    case ShapeType::Quad: return std::max({reach(p0), reach(p0 + p1), reach(p0 + p2), reach(p0 + p1 + p2)});
    case ShapeType::Triangle: return std::max({reach(p0), reach(p1), reach(p2)});
    }
    return 0.0;
}

}  // namespace vkp
