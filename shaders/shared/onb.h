// Orthonormal bases ("Ray Tracing: The Rest of Your Life" (RTTROYL), chapter "Orthonormal Bases").
// Convention everywhere in the shared code: in a local frame the z axis is the normal (or the axis
// of a cone), x = s, y = t; (s, t, n) is right-handed.
#ifndef VKP_ONB_H
#define VKP_ONB_H
#include "glsl_compat.h"

VKP_BEGIN

/// A right-handed orthonormal frame: s x t = n. All three are unit vectors in world space.
struct Onb {
    vec3 s;
    vec3 t;
    vec3 n;
};

/// Frame with z axis n (n must be unit length). Branchless construction of Duff, Burgess,
/// Christensen, Hery, Kensler, Liani, Villemin, "Building an Orthonormal Basis, Revisited",
/// JCGT 6(1), 2017, listing 3; continuous except across n.z = 0 and accurate for every unit n
/// (no catastrophic cancellation near n = (0,0,-1)). sign(-0) is taken as +1, which is harmless:
/// the formula is valid for either sign whenever |n.z| < 1.
VKP_FN Onb onbFromNormal(vec3 n) {
    float sgn = (n.z >= 0.0f) ? 1.0f : -1.0f;
    float a = -1.0f / (sgn + n.z);
    float b = n.x * n.y * a;
    Onb f;
    f.s = vec3(1.0f + sgn * n.x * n.x * a, sgn * b, -sgn * n.x);
    f.t = vec3(b, sgn + n.y * n.y * a, -n.y);
    f.n = n;
    return f;
}

/// Local coordinates (x along s, y along t, z along n) -> world vector.
VKP_FN vec3 toWorld(Onb f, vec3 v) { return v.x * f.s + v.y * f.t + v.z * f.n; }

/// World vector -> local coordinates (dot products with s, t, n).
VKP_FN vec3 toLocal(Onb f, vec3 v) { return vec3(dot(v, f.s), dot(v, f.t), dot(v, f.n)); }

VKP_END
#endif
