// Object transforms of the JSON scene format: a list of translate / rotate_x|y|z / scale steps,
// applied in list order, composed into one affine map (scenes/README.md "Transforms").
#pragma once
#include <string>

#include <glm/glm.hpp>

namespace vkp {

namespace json {
class Value;
}

/// An affine map p -> linear * p + offset, in double precision (composed steps stay exact
/// enough that a box corner lands where the book puts it).
struct Affine {
    glm::dmat3 linear{1.0};
    glm::dvec3 offset{0.0};

    glm::dvec3 point(glm::dvec3 p) const { return linear * p + offset; }
    glm::dvec3 vector(glm::dvec3 v) const { return linear * v; }
    /// This map followed by next.
    Affine then(const Affine& next) const { return {next.linear * linear, next.linear * offset + next.offset}; }
    bool mirrors() const { return glm::determinant(linear) < 0.0; }

    static Affine translate(glm::dvec3 t);
    static Affine scale(glm::dvec3 s);
    /// Right-handed rotations by deg degrees (counter-clockwise looking from +axis to the origin).
    /// rotate_y: x' = cos x + sin z, z' = -sin x + cos z (rotate_y of "The Next Week", chapter "Instances").
    static Affine rotateX(double deg);
    static Affine rotateY(double deg);
    static Affine rotateZ(double deg);
};

/// A parsed "transform" list.
struct ObjectTransform {
    Affine map;
    /// Factor on lengths when every scale step is uniform in magnitude (|sx| = |sy| = |sz|):
    /// the product of |s|. A sphere's radius is multiplied by it.
    double uniformScale = 1.0;
    /// JSON pointer of the first scale step that is not uniform (empty if none): a sphere refuses it.
    std::string nonUniformAt;
};

/// Read a "transform" list: an array of one-key objects {"translate":[x,y,z]}, {"rotate_x":deg},
/// {"rotate_y":deg}, {"rotate_z":deg}, {"scale":s} or {"scale":[x,y,z]} (no zero factor); the
/// first step is applied first. Throws InputError at the offending step.
ObjectTransform readTransform(const json::Value& list);

}  // namespace vkp
