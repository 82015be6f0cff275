#include "scene/transform.h"

#include <cmath>
#include <numbers>

#include "scene/json_reader.h"

namespace vkp {

namespace {

/// sin and cos of an angle in degrees, exact at multiples of 90 degrees (so rotate_y 90 maps an
/// axis-aligned box onto an axis-aligned box, without 6e-17 residues).
void sinCosDeg(double deg, double& s, double& c) {
    double r = std::fmod(deg, 360.0);
    if (r < 0.0) r += 360.0;
    if (r == 0.0) { s = 0.0; c = 1.0; return; }
    if (r == 90.0) { s = 1.0; c = 0.0; return; }
    if (r == 180.0) { s = 0.0; c = -1.0; return; }
    if (r == 270.0) { s = -1.0; c = 0.0; return; }
    const double rad = r * std::numbers::pi / 180.0;
    s = std::sin(rad);
    c = std::cos(rad);
}

}  // namespace

Affine Affine::translate(glm::dvec3 t) { return {glm::dmat3(1.0), t}; }

Affine Affine::scale(glm::dvec3 s) {
    glm::dmat3 m(0.0);
    m[0][0] = s.x;
    m[1][1] = s.y;
    m[2][2] = s.z;
    return {m, glm::dvec3(0.0)};
}

// glm matrices are column-major: m[col][row]. Each map below is written as its rows.
Affine Affine::rotateX(double deg) {
    double s, c;
    sinCosDeg(deg, s, c);
    glm::dmat3 m(1.0);  // y' = c y - s z, z' = s y + c z
    m[1][1] = c; m[2][1] = -s;
    m[1][2] = s; m[2][2] = c;
    return {m, glm::dvec3(0.0)};
}

Affine Affine::rotateY(double deg) {
    double s, c;
    sinCosDeg(deg, s, c);
    glm::dmat3 m(1.0);  // x' = c x + s z, z' = -s x + c z
    m[0][0] = c; m[2][0] = s;
    m[0][2] = -s; m[2][2] = c;
    return {m, glm::dvec3(0.0)};
}

Affine Affine::rotateZ(double deg) {
    double s, c;
    sinCosDeg(deg, s, c);
    glm::dmat3 m(1.0);  // x' = c x - s y, y' = s x + c y
    m[0][0] = c; m[1][0] = -s;
    m[0][1] = s; m[1][1] = c;
    return {m, glm::dvec3(0.0)};
}

ObjectTransform readTransform(const json::Value& list) {
    ObjectTransform out;
    for (const json::Value& step : list.array()) {
        json::Object o = step.object();
        if (o.value().json().size() != 1) {
            step.fail("must have exactly one key: translate, rotate_x, rotate_y, rotate_z or scale (got " +
                      std::to_string(o.value().json().size()) + ")");
        }
        Affine a;
        if (auto t = o.optional("translate")) {
            a = Affine::translate(t->dvec3());
        } else if (auto rx = o.optional("rotate_x")) {
            a = Affine::rotateX(rx->real());
        } else if (auto ry = o.optional("rotate_y")) {
            a = Affine::rotateY(ry->real());
        } else if (auto rz = o.optional("rotate_z")) {
            a = Affine::rotateZ(rz->real());
        } else if (auto sc = o.optional("scale")) {
            glm::dvec3 s;
            if (sc->json().is_array()) {
                s = sc->dvec3();
                for (std::size_t i = 0; i < 3; ++i) {
                    if (s[static_cast<int>(i)] == 0.0) sc->element(i).fail("must not be 0");
                }
            } else {
                s = glm::dvec3(sc->real());
                if (s.x == 0.0) sc->fail("must not be 0");
            }
            const glm::dvec3 m = glm::abs(s);
            if (m.x == m.y && m.y == m.z) {
                out.uniformScale *= m.x;
            } else if (out.nonUniformAt.empty()) {
                out.nonUniformAt = sc->pointer();
            }
            a = Affine::scale(s);
        }
        o.finish();  // the one key was none of the above
        out.map = out.map.then(a);
    }
    return out;
}

}  // namespace vkp
