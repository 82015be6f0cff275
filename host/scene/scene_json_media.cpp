// The "constant_medium" entry of "objects" (scenes/README.md "Media"): a constant-density medium
// inside a sphere or box boundary, as constant_medium of "Ray Tracing: The Next Week" (sec. 9).
#include <cmath>
#include <string>

#include "core/errors.h"
#include "scene/json_reader.h"
#include "scene/scene_json_parts.h"
#include "scene/transform.h"

namespace vkp::scenejson {

namespace {

bool finiteAsFloat(double x) { return std::isfinite(x) && std::abs(x) < 3.0e38; }

/// The boundary's region: local space (unit ball or cube [-1, 1]^3) from the file's
/// coordinates, as the inverse of file = map(centre + scale * local) with a per-axis scale.
void readBoundary(const json::Value& v, const Scene& scene, Medium& m) {
    json::Object o = v.object();
    const json::Value typeValue = o.required("type");
    const std::string type = typeValue.string();
    if (type == "quad" || type == "triangle" || type == "gltf" || type == "constant_medium") {
        typeValue.fail("a medium's boundary must be a \"sphere\" or a \"box\" (closed and convex), not a \"" + type + "\"");
    }
    o.choice("type", {"sphere", "box"});
    ObjectTransform xf;
    if (auto t = o.optional("transform")) xf = readTransform(*t);
    glm::dvec3 centre(0.0), half(1.0);
    if (type == "sphere") {
        m.boundary = Medium::Boundary::Sphere;
        centre = o.dvec3("center");
        half = glm::dvec3(o.number("radius", json::Range::above(0.0)));
    } else {
        m.boundary = Medium::Boundary::Box;
        const auto [lo, hi] = readBoxCorners(o);
        centre = 0.5 * (lo + hi);
        half = 0.5 * (hi - lo);
    }
    o.finish();
    // file = L (centre + half * local) + c  =>  local = (L^-1 (x + origin - c) - centre) / half,
    // x camera-relative.
    const glm::dmat3 inv = glm::inverse(xf.map.linear);
    const glm::dmat3 scale(glm::dvec3(1.0 / half.x, 0.0, 0.0), glm::dvec3(0.0, 1.0 / half.y, 0.0),
                           glm::dvec3(0.0, 0.0, 1.0 / half.z));
    m.toLocal = scale * inv;
    m.toLocalOffset = scale * (inv * (scene.origin - xf.map.offset) - centre);
    // Bounds: the centre's image plus, per axis, the reach of the scaled unit ball or cube.
    const glm::dvec3 mid = xf.map.point(centre) - scene.origin;
    const glm::dmat3 a = xf.map.linear * glm::dmat3(glm::dvec3(half.x, 0.0, 0.0), glm::dvec3(0.0, half.y, 0.0),
                                                    glm::dvec3(0.0, 0.0, half.z));
    for (int i = 0; i < 3; ++i) {
        const glm::dvec3 row(a[0][i], a[1][i], a[2][i]);
        const double reach = m.boundary == Medium::Boundary::Sphere ? glm::length(row)
                                                                    : std::abs(row.x) + std::abs(row.y) + std::abs(row.z);
        m.lo[i] = mid[i] - reach;
        m.hi[i] = mid[i] + reach;
    }
    bool ok = true;
    for (int i = 0; i < 3; ++i) {
        ok = ok && finiteAsFloat(m.lo[i]) && finiteAsFloat(m.hi[i]) && finiteAsFloat(m.toLocalOffset[i]);
        for (int j = 0; j < 3; ++j) ok = ok && finiteAsFloat(m.toLocal[j][i]);
    }
    if (!ok) {
        v.fail("the transformed " + type + " does not fit 32-bit floats relative to the camera (overflow or underflow)");
    }
}

}  // namespace

Medium readMedium(const json::Value& v, TextureReader& textures, Scene& scene) {
    json::Object o = v.object();
    o.choice("type", {"constant_medium"});
    if (scene.media.size() >= gpu::MAX_MEDIA) {
        v.fail("too many media: at most " + std::to_string(gpu::MAX_MEDIA) +
               " (each is tested along every ray; scenes/README.md \"Media\")");
    }
    Medium m;
    m.name = v.pointer();
    readBoundary(o.required("boundary"), scene, m);
    m.density = o.number("density", json::Range::above(0.0));
    if (!(m.density > 0.0f) || !std::isfinite(m.density))
        o.required("density").fail("must be a positive 32-bit float (got one that rounds to 0 or overflows)");
    Material mat;
    mat.name = "the medium at " + m.name;
    mat.type = MaterialType::Isotropic;
    mat.albedoTexture = textures.colourOrTexture(o.required("albedo"), json::Range::closed(0.0, 1.0), mat.albedo);
    o.finish();
    m.material = static_cast<std::uint32_t>(scene.materials.size());
    scene.materials.push_back(mat);
    return m;
}

}  // namespace vkp::scenejson
