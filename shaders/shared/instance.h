// Instances of a shared mesh (two-level BVH): the GPU record of one instance and the arithmetic
// that maps rays into its object space and its hits back into the world. Compiled as C++ (host
// packing, the CPU twin host/bvh/traverse_wide_cpu.cpp) and as GLSL (lib/traverse_wide.glsl,
// pathtrace.comp), so both sides round the same way.
//
// Design (pbrt-v4 sec. 7.1.4 "Object Instancing"; Wald et al., "Ray Tracing Animated Scenes using
// Coherent Grid Traversal" / the two-level BVH of most GPU ray tracers): a mesh used by several
// glTF nodes is stored once, in object space, with its own BVH (the bottom level); each node is
// one leaf primitive of the top-level BVH (kind PRIM_INSTANCE) that names a GpuInstance. On
// reaching it, the traversal maps the ray's origin and direction into object space with the
// world-to-object matrix, without renormalising the direction, so a hit's t is the same distance
// parameter in both spaces and closest-hit culling carries across instances; then it traverses the
// bottom level and continues.
#ifndef VKP_INSTANCE_H
#define VKP_INSTANCE_H
#include "gpu_types.h"
#include "intersect.h"

VKP_BEGIN

// ---- One instance (7 texels, 112 bytes) -------------------------------------------------------
// info.x: root node of its mesh's bottom-level BVH in the 4-wide node array (shared/wide_bvh.h),
// info.y: the same in the binary node array (FlatBvh::nodes: traversed only by the layout
// benchmark's binary kernel, shaders/tests/traverse_binary.glsl), info.z: flags (INSTANCE_MIRROR),
// info.w: the mesh's index (Scene::meshes; for messages and statistics).
// w2o0..2: rows of the world-to-object affine map, object = (dot(row.xyz, world) + row.w) per row;
// o2w0..2: rows of the object-to-world map (the node's world matrix), the same convention.
// Both are the double-precision matrix and its inverse, each rounded to float once.
// A PRIM_INSTANCE primitive (gpu_types.h) has header PRIM_INSTANCE | (instance index << 2) and
// NaN coordinates, so a traversal that does not know instances never hits it.
struct GpuInstance {
    uvec4 info;
    vec4 w2o0;
    vec4 w2o1;
    vec4 w2o2;
    vec4 o2w0;
    vec4 o2w1;
    vec4 o2w2;
};
const uint GPU_INSTANCE_TEXELS = 7u;
const uint INSTANCE_MIRROR = 1u;        // the world matrix has a negative determinant (glTF 2.0 sec. 3.7.4)
const uint GPU_NO_INSTANCE = 0xffffffffu;  // a hit on a top-level primitive (world space)

/// r0..r2 (rows of a 3x4 affine map) applied to point p: r.xyz . p + r.w per row, summed left to
/// right without fma contraction (VKP_PRECISE), so the C++ twin rounds the same way.
VKP_FN vec3 affinePoint(vec4 r0, vec4 r1, vec4 r2, vec3 p) {
    VKP_PRECISE float x = r0.x * p.x + r0.y * p.y + r0.z * p.z + r0.w;
    VKP_PRECISE float y = r1.x * p.x + r1.y * p.y + r1.z * p.z + r1.w;
    VKP_PRECISE float z = r2.x * p.x + r2.y * p.y + r2.z * p.z + r2.w;
    return vec3(x, y, z);
}
/// The linear part of the map applied to vector v (directions, tangents).
VKP_FN vec3 affineVector(vec4 r0, vec4 r1, vec4 r2, vec3 v) {
    VKP_PRECISE float x = r0.x * v.x + r0.y * v.y + r0.z * v.z;
    VKP_PRECISE float y = r1.x * v.x + r1.y * v.y + r1.z * v.z;
    VKP_PRECISE float z = r2.x * v.x + r2.y * v.y + r2.z * v.z;
    return vec3(x, y, z);
}
/// The transpose of the linear part applied to v: for the world-to-object rows this is the
/// inverse transpose of the object-to-world map, which takes normals into the world (unnormalised).
VKP_FN vec3 affineTransposeVector(vec4 r0, vec4 r1, vec4 r2, vec3 v) {
    VKP_PRECISE float x = r0.x * v.x + r1.x * v.y + r2.x * v.z;
    VKP_PRECISE float y = r0.y * v.x + r1.y * v.y + r2.y * v.z;
    VKP_PRECISE float z = r0.z * v.x + r1.z * v.y + r2.z * v.z;
    return vec3(x, y, z);
}

/// The ray's origin and direction in the instance's object space (the direction not renormalised:
/// t is shared with the world ray).
VKP_FN vec3 instanceRayOrigin(GpuInstance inst, vec3 o) { return affinePoint(inst.w2o0, inst.w2o1, inst.w2o2, o); }
VKP_FN vec3 instanceRayDirection(GpuInstance inst, vec3 d) { return affineVector(inst.w2o0, inst.w2o1, inst.w2o2, d); }

VKP_FN bool instanceMirrored(GpuInstance inst) { return (inst.info.z & INSTANCE_MIRROR) != 0u; }

/// An object-space triangle of the instance's mesh placed in the world, as the flattening loader
/// would place it: vertices by the object-to-world map, and under a mirror (negative determinant)
/// v1 and v2 swapped, so that e1 x e2 is again the front face (glTF 2.0 sec. 3.7.4). The surface
/// parameters of a hit then swap too: instanceWorldAb.
VKP_FN GpuPrim instanceWorldPrim(GpuInstance inst, GpuPrim p) {
    vec3 v0 = affinePoint(inst.o2w0, inst.o2w1, inst.o2w2, vec3(p.p0.x, p.p0.y, p.p0.z));
    vec3 v1 = affinePoint(inst.o2w0, inst.o2w1, inst.o2w2, vec3(p.p1.x, p.p1.y, p.p1.z));
    vec3 v2 = affinePoint(inst.o2w0, inst.o2w1, inst.o2w2, vec3(p.p2.x, p.p2.y, p.p2.z));
    bool mirror = instanceMirrored(inst);
    GpuPrim w;
    w.p0 = vec4(v0.x, v0.y, v0.z, p.p0.w);
    vec3 a = mirror ? v2 : v1;
    vec3 b = mirror ? v1 : v2;
    w.p1 = vec4(a.x, a.y, a.z, p.p1.w);
    w.p2 = vec4(b.x, b.y, b.z, p.p2.w);
    return w;
}
/// Surface parameters on instanceWorldPrim of a hit with object-space parameters ab.
VKP_FN vec2 instanceWorldAb(GpuInstance inst, vec2 ab) { return instanceMirrored(inst) ? vec2(ab.y, ab.x) : ab; }

/// Object-space normal n (any length) in the world, unit length: by the inverse transpose.
VKP_FN vec3 instanceNormalToWorld(GpuInstance inst, vec3 n) {
    vec3 w = affineTransposeVector(inst.w2o0, inst.w2o1, inst.w2o2, n);
    float len = length(w);
    return (len > 0.0f) ? w / len : w;
}
/// Object-space tangent (xyz, w = handedness) in the world: xyz by the linear map, unit length;
/// the handedness flips under a mirror (as the flattening loader does).
VKP_FN vec4 instanceTangentToWorld(GpuInstance inst, vec4 t) {
    vec3 w = affineVector(inst.o2w0, inst.o2w1, inst.o2w2, vec3(t.x, t.y, t.z));
    float len = length(w);
    if (len > 0.0f) w = w / len;
    return vec4(w.x, w.y, w.z, instanceMirrored(inst) ? -t.w : t.w);
}

/// Extra distance (world units, >= 0) by which a ray leaving an instanced triangle must start off
/// its world plane, on top of primOffsetDistance of the world triangle (intersect.h) and
/// offsetRayOrigin's step. Two roundings come with the transform (pbrt-v4 sec. 6.8.6 bounds a
/// transformed point's error by gamma(3) (|M| |p| + |t|) per coordinate):
///  - the world triangle's vertices are M v + t rounded: gamma (|M| |x_o| + |t|) along the world
///    normal n (unit), x_o the object-space hit point;
///  - the next ray's origin is mapped back into object space, W x + t_w rounded: an error of
///    gamma (|W| |x| + |t_w|), plus the object triangle's own rounding there (primOffsetDistance
///    of the object triangle), both along the object normal n_o. An object-space distance
///    s along n_o is a world distance s / |W^T n_o| (the plane's normal transforms by W^T), so that
///    part is divided by |W^T n_o|.
/// gamma is 8 eps = 2^-21, as in primOffsetDistance (gamma(4) and the next test's rounding).
/// pObj, ab: the object-space triangle and the hit's surface parameters on it; x: the world hit
/// point; n: the world geometric normal (unit).
VKP_FN float instanceOffsetDistance(GpuInstance inst, GpuPrim pObj, vec2 ab, vec3 x, vec3 n) {
    const float g = 1.0f / 2097152.0f;
    vec3 xo = primHitPoint(pObj, vec3(0.0f), vec3(0.0f), 0.0f, ab);  // v0 + a e1 + b e2 (triangles)
    vec3 no = cross(primEdge1(pObj), primEdge2(pObj));
    float lo = length(no);
    no = (lo > 0.0f) ? no / lo : vec3(0.0f, 0.0f, 1.0f);
    vec3 axo = abs(xo);
    vec3 worldErr = vec3(dot(abs(vec3(inst.o2w0.x, inst.o2w0.y, inst.o2w0.z)), axo) + abs(inst.o2w0.w),
                         dot(abs(vec3(inst.o2w1.x, inst.o2w1.y, inst.o2w1.z)), axo) + abs(inst.o2w1.w),
                         dot(abs(vec3(inst.o2w2.x, inst.o2w2.y, inst.o2w2.z)), axo) + abs(inst.o2w2.w));
    vec3 ax = abs(x);
    vec3 objErr = vec3(dot(abs(vec3(inst.w2o0.x, inst.w2o0.y, inst.w2o0.z)), ax) + abs(inst.w2o0.w),
                       dot(abs(vec3(inst.w2o1.x, inst.w2o1.y, inst.w2o1.z)), ax) + abs(inst.w2o1.w),
                       dot(abs(vec3(inst.w2o2.x, inst.w2o2.y, inst.w2o2.z)), ax) + abs(inst.w2o2.w));
    float k = length(affineTransposeVector(inst.w2o0, inst.w2o1, inst.w2o2, no));  // |W^T n_o| > 0
    float objDist = primOffsetDistance(pObj, ab, no) + g * dot(abs(no), objErr);
    return g * dot(abs(n), worldErr) + ((k > 0.0f) ? objDist / k : 0.0f);
}

VKP_END
#endif
