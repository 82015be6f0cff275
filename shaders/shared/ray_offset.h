// Spawning secondary rays without self-intersection and without a scene-scale epsilon.
#ifndef VKP_RAY_OFFSET_H
#define VKP_RAY_OFFSET_H
#include "glsl_compat.h"

VKP_BEGIN

/// Move hit point p off its surface along the geometric normal n (unit, pointing to the side the
/// new ray leaves on), by an amount that grows with |p| so that it stays above the rounding error of
/// the intersection at any scale or distance from the origin. Wachter and Binder, "A Fast and Robust
/// Method for Avoiding Self-Intersection", Ray Tracing Gems (2019), ch. 6: integer ULP offsets far
/// from the origin, a tiny absolute offset near it.
VKP_FN vec3 offsetRayOrigin(vec3 p, vec3 n) {
    const float origin = 1.0f / 32.0f;
    const float floatScale = 1.0f / 65536.0f;
    const float intScale = 256.0f;
    ivec3 of = ivec3(int(intScale * n.x), int(intScale * n.y), int(intScale * n.z));
    vec3 pi = vec3(intBitsToFloat(floatBitsToInt(p.x) + ((p.x < 0.0f) ? -of.x : of.x)),
                   intBitsToFloat(floatBitsToInt(p.y) + ((p.y < 0.0f) ? -of.y : of.y)),
                   intBitsToFloat(floatBitsToInt(p.z) + ((p.z < 0.0f) ? -of.z : of.z)));
    return vec3(abs(p.x) < origin ? p.x + floatScale * n.x : pi.x,
                abs(p.y) < origin ? p.y + floatScale * n.y : pi.y,
                abs(p.z) < origin ? p.z + floatScale * n.z : pi.z);
}

VKP_END
#endif
