#include "bvh/tlas.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace vkp {

namespace {
/// The largest float <= x (x finite in float range), and the smallest float >= x.
float floatDown(double x) {
    float f = float(x);
    return double(f) > x ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
}
float floatUp(double x) {
    float f = float(x);
    return double(f) < x ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
}
}  // namespace

Aabb transformedBounds(const Aabb& box, const glm::dmat4& m) {
    if (box.empty()) return Aabb{};
    glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
    for (int c = 0; c < 8; ++c) {
        const glm::dvec3 p((c & 1) ? box.hi.x : box.lo.x, (c & 2) ? box.hi.y : box.lo.y, (c & 4) ? box.hi.z : box.lo.z);
        const glm::dvec3 w(m * glm::dvec4(p, 1.0));
        lo = glm::min(lo, w);
        hi = glm::max(hi, w);
    }
    const glm::dvec3 mag = glm::max(glm::abs(lo), glm::abs(hi));
    const double pad = std::ldexp(std::max({mag.x, mag.y, mag.z, hi.x - lo.x, hi.y - lo.y, hi.z - lo.z}), -16);
    Aabb out;
    for (int k = 0; k < 3; ++k) {
        out.lo[k] = floatDown(lo[k] - pad);
        out.hi[k] = floatUp(hi[k] + pad);
    }
    return out;
}

TopLevelItems topLevelItems(const Scene& scene, std::span<const Aabb> meshBounds) {
    TopLevelItems items;
    items.shapeCount = scene.shapes.size();
    items.boxes.reserve(scene.shapes.size() + scene.instances.size());
    for (const Shape& s : scene.shapes) items.boxes.push_back(shapeBounds(s));
    for (const MeshInstance& inst : scene.instances) {
        if (inst.mesh >= meshBounds.size()) throw std::invalid_argument("topLevelItems: an instance names a mesh without a box");
        items.boxes.push_back(transformedBounds(meshBounds[inst.mesh], inst.objectToWorld));
    }
    items.centroids.reserve(items.boxes.size());
    for (const Aabb& b : items.boxes) items.centroids.push_back(b.empty() ? glm::vec3(0.0f) : 0.5f * (b.lo + b.hi));
    return items;
}

}  // namespace vkp
