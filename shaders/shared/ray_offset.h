// Spawning secondary rays without self-intersection and without a scene-scale epsilon.
//
// Policy (Wachter and Binder, "A Fast and Robust Method for Avoiding Self-Intersection", Ray
// Tracing Gems, 2019, ch. 6):
//  1. The hit point is recomputed from the primitive (intersect.h primHitPoint: Q + a e1 + b e2,
//     or the sphere's centre + R * unit direction), so that its error is a few ulps of the
//     primitive's own coordinates, whatever the distance the ray travelled.
//  2. The new ray starts at that point moved off the surface along the geometric normal, on the
//     side the ray leaves to: for quads and triangles first by a distance proportional to the
//     primitive's own size and position (intersect.h primOffsetDistance, spawnRayOrigin: their
//     points' error is set by the primitive, not by the point), then (offsetRayOrigin) by 256 ulps
//     of each coordinate (an integer step
//     on the float's bit pattern, so the offset is relative and works at any scale and distance
//     from the origin), or by 2^-16 absolute for coordinates below 2^-5, where ulps become too
//     small to cover the absolute error of the arithmetic that produced them. Both of those
//     constants are lengths sized for a scene about one unit across; a smaller scene scales them
//     by its own size (rayOffsetScale), so that a Cornell box of 5.6e-4 units is not offset by
//     3% of its size.
//  3. Rays start at t = 0: no t_min. A shadow ray runs between two such offset points
//     (shadowRayTo), so neither its start nor its end surface can be hit, without a relative
//     epsilon on its length.
// A fixed t_min (the book's 0.001) is a length in scene units: too large for a scene scaled by 1e-4
// (it skips real hits within 0.001: light leaks in corners) and too small for one scaled by 1e5 or
// moved 1e5 from the origin (rounding there is ~0.01: rays hit the surface they leave).
// tests/stress/test_stress_ray_offset.cpp measures both policies on the shared intersection code.
#ifndef VKP_RAY_OFFSET_H
#define VKP_RAY_OFFSET_H
#include "glsl_compat.h"

VKP_BEGIN

/// The scale of offsetRayOrigin's absolute floor for a scene whose geometry lies within `extent`
/// world units of the origin (the camera, in vkpath's camera-relative space; the largest absolute
/// coordinate of the scene's bounds): 1 for extent >= 1, where the floor of Wachter and Binder
/// (sized for scenes about a unit across) is far below the scene's own size, else the power of two
/// at or above extent, so that a scene scaled down by 2^-k is offset exactly as the same scene
/// at its original size scaled down by 2^-k (a power of two scales floats exactly). 1 for an
/// empty, zero-sized or non-finite extent.
VKP_FN float rayOffsetScale(float extent) {
    if (!(extent > 0.0f) || !(extent < 1.0f)) return 1.0f;
    float s = 1.0f;
    while (s * 0.5f >= extent && s > 1e-30f) s *= 0.5f;
    return s;
}

/// Move hit point p off its surface along the geometric normal n (unit, pointing to the side the
/// new ray leaves on), by an amount that grows with |p| so that it stays above the rounding error of
/// the intersection at any scale or distance from the origin. Wachter and Binder, "A Fast and Robust
/// Method for Avoiding Self-Intersection", Ray Tracing Gems (2019), ch. 6: integer ULP offsets far
/// from the origin, a tiny absolute offset near it. scale (rayOffsetScale, a power of two in
/// (0, 1]) scales that near-origin region and offset with a scene smaller than a unit; 1 is the
/// paper's constants.
VKP_FN vec3 offsetRayOrigin(vec3 p, vec3 n, float scale) {
    const float origin = scale * (1.0f / 32.0f);
    const float floatScale = scale * (1.0f / 65536.0f);
    const float intScale = 256.0f;
    ivec3 of = ivec3(int(intScale * n.x), int(intScale * n.y), int(intScale * n.z));
    vec3 pi = vec3(intBitsToFloat(floatBitsToInt(p.x) + ((p.x < 0.0f) ? -of.x : of.x)),
                   intBitsToFloat(floatBitsToInt(p.y) + ((p.y < 0.0f) ? -of.y : of.y)),
                   intBitsToFloat(floatBitsToInt(p.z) + ((p.z < 0.0f) ? -of.z : of.z)));
    return vec3(abs(p.x) < origin ? p.x + floatScale * n.x : pi.x,
                abs(p.y) < origin ? p.y + floatScale * n.y : pi.y,
                abs(p.z) < origin ? p.z + floatScale * n.z : pi.z);
}

/// Shadow ray from xo (a shading point already moved off its surface by offsetRayOrigin) to the
/// point y of a light whose geometric normal at y is ny (unit, either orientation). Returns the
/// unit direction (xyz) and the length (w) to trace with t in (0, w) (world units):
///  - y is moved off the light towards xo by offsetRayOrigin (its own rounding, a few ulps of |y|),
///  - the direction is that of the segment between the two offset points (not the direction that
///    was sampled from the unoffset shading point: from xo it would meet the light's plane early by
///    the offset / cos, which a far-away scene turns into a whole-light false occlusion),
///  - the length is cut by 2^-14 of itself: the distance an intersection routine computes along a
///    ray errs by a few ulps of t itself, 2^-14 allows for 1 / |cos| up to ~100 at the light.
/// yExtra: the light primitive's primOffsetDistance (intersect.h), added along the normal first;
/// scale: the scene's rayOffsetScale. xo == y after offsetting gives length 0 (no ray).
VKP_FN vec4 shadowRayTo(vec3 xo, vec3 y, vec3 ny, float yExtra, float scale) {
    vec3 towards = xo - y;
    vec3 side = (dot(towards, ny) >= 0.0f) ? ny : -ny;
    vec3 yo = offsetRayOrigin(y + yExtra * side, side, scale);
    vec3 s = yo - xo;
    float len = length(s);
    return (len > 0.0f) ? vec4(s / len, len * (1.0f - 1.0f / 16384.0f)) : vec4(0.0f, 0.0f, 1.0f, 0.0f);
}

VKP_END
#endif
