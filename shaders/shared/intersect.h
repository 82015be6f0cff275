// Ray-primitive intersection, shared by the kernels and the host's CPU traversal (host/bvh).
// Rays: origin o and unit direction d in world units; hits are accepted for t in (tmin, tmax).
// Every function returns the hit distance t, or VKP_FAR for a miss. Acceptance tests are written
// so that a NaN (degenerate primitive, zero determinant) compares false and therefore misses.
#ifndef VKP_INTERSECT_H
#define VKP_INTERSECT_H
#include "gpu_types.h"
#include "ray_offset.h"
#include "wide_bvh.h"

VKP_BEGIN

/// Sphere of centre c and radius r. Uses the numerically careful form of Haines et al.,
/// "Precision Improvements for Ray/Sphere Intersection" (Ray Tracing Gems, ch. 7): the
/// discriminant from the distance of the centre to the ray, and the root that avoids cancellation.
VKP_FN float intersectSphere(vec3 c, float r, vec3 o, vec3 d, float tmin, float tmax) {
    vec3 f = o - c;
    float b = dot(f, d);                 // half of the usual b (d is unit length)
    vec3 l = f - b * d;                  // centre -> closest point on the ray's line
    float disc = r * r - dot(l, l);
    if (!(disc >= 0.0f)) return VKP_FAR;
    float s = sqrt(disc);
    float q = (b > 0.0f) ? -(b + s) : -(b - s);
    float cc = dot(f, f) - r * r;
    // q == 0 only when b == 0 and disc == 0, which makes cc == 0: a double root at t = 0. Writing
    // it out avoids 0/0 = NaN, on which GLSL's min/max and glm's would disagree.
    float t0 = (q != 0.0f) ? cc / q : 0.0f;
    float t1 = q;
    float tn = min(t0, t1);
    float tf = max(t0, t1);
    if (tn > tmin && tn < tmax) return tn;
    if (tf > tmin && tf < tmax) return tf;
    return VKP_FAR;
}

/// Parallelogram Q + a e1 + b e2 (a,b in [0,1]) or, with triangle = true, triangle
/// Q + a e1 + b e2 (a,b >= 0, a+b <= 1). Moller-Trumbore ("Fast, Minimum Storage Ray/Triangle
/// Intersection", 1997) with e1, e2 as edges. ab receives (a, b) of the hit point.
/// Not watertight between neighbours (a ray through a shared edge can slip between them); the
/// traversal uses intersectTriangleWatertight for triangles. Kept for quads (one parallelogram has
/// no inner edge) and for the light pdfs, which need the (a, b) of this parametrisation.
VKP_FN float intersectParallelogram(vec3 Q, vec3 e1, vec3 e2, bool triangle, vec3 o, vec3 d,
                                    float tmin, float tmax, OUT(vec2) ab) {
    vec3 pv = cross(d, e2);
    float det = dot(e1, pv);
    float inv = 1.0f / det;
    vec3 tv = o - Q;
    float a = dot(tv, pv) * inv;
    vec3 qv = cross(tv, e1);
    float b = dot(d, qv) * inv;
    float t = dot(e2, qv) * inv;
    ab = vec2(a, b);
    float limitB = triangle ? 1.0f - a : 1.0f;
    bool inside = (a >= 0.0f) && (a <= 1.0f) && (b >= 0.0f) && (b <= limitB);
    bool inRange = (t > tmin) && (t < tmax);
    return (inside && inRange) ? t : VKP_FAR;
}

// VKP_PRECISE (glsl_compat.h) forbids the GLSL compiler to contract a * b - c * d into an fma,
// which would break the exact antisymmetry of the edge functions below (and the bit-exact agreement
// with C++).

/// Watertight ray/triangle test (Woop, Benthin, Wald, "Watertight Ray/Triangle Intersection",
/// JCGT 2(1), 2013, sec. 3): the ray is made the +z axis of a sheared frame (z = the axis of the
/// largest |d| component, x and y the next two cyclically, swapped when d_z < 0), the vertices are
/// moved into it, and the 2D edge functions u, v, w of the projected triangle decide the hit.
/// Watertight: a vertex's sheared coordinates depend only on the vertex and the ray, and the edge
/// function of an edge seen from the neighbour is computed from the same two vertices in the other
/// order, which in IEEE arithmetic gives exactly the negated value (no fma contraction: VKP_PRECISE).
/// So a ray can never pass between two triangles that share an edge (bit-identical vertices);
/// exactly on the edge it hits both. The paper's double-precision fallback for u, v or w == 0 is
/// left out: it only improves which of the two is reported, not watertightness.
/// ab receives the barycentric weights (of v1, of v2): the hit point is v0 + a (v1 - v0) +
/// b (v2 - v0). A triangle of zero area in the sheared frame (det = u + v + w = 0) is missed.
VKP_FN float intersectTriangleWatertight(vec3 v0, vec3 v1, vec3 v2, vec3 o, vec3 d, float tmin,
                                         float tmax, OUT(vec2) ab) {
    vec3 ad = abs(d);
    int kz = (ad.x > ad.y) ? ((ad.x > ad.z) ? 0 : 2) : ((ad.y > ad.z) ? 1 : 2);
    int kx = (kz == 2) ? 0 : kz + 1;
    int ky = (kx == 2) ? 0 : kx + 1;
    if (d[kz] < 0.0f) {
        int k = kx;
        kx = ky;
        ky = k;
    }
    float sz = 1.0f / d[kz];
    float sx = d[kx] * sz;
    float sy = d[ky] * sz;
    vec3 A = v0 - o;
    vec3 B = v1 - o;
    vec3 C = v2 - o;
    VKP_PRECISE float axs = A[kx] - sx * A[kz];
    VKP_PRECISE float ays = A[ky] - sy * A[kz];
    VKP_PRECISE float bxs = B[kx] - sx * B[kz];
    VKP_PRECISE float bys = B[ky] - sy * B[kz];
    VKP_PRECISE float cxs = C[kx] - sx * C[kz];
    VKP_PRECISE float cys = C[ky] - sy * C[kz];
    VKP_PRECISE float u = cxs * bys - cys * bxs;
    VKP_PRECISE float v = axs * cys - ays * cxs;
    VKP_PRECISE float w = bxs * ays - bys * axs;
    bool neg = (u < 0.0f) || (v < 0.0f) || (w < 0.0f);
    bool pos = (u > 0.0f) || (v > 0.0f) || (w > 0.0f);
    float det = u + v + w;
    float tScaled = u * (sz * A[kz]) + v * (sz * B[kz]) + w * (sz * C[kz]);
    float inv = 1.0f / det;
    float t = tScaled * inv;
    ab = vec2(v * inv, w * inv);
    bool hit = !(neg && pos) && (det != 0.0f) && (t > tmin) && (t < tmax);
    return hit ? t : VKP_FAR;
}

/// True when the triangle (v0, v1, v2) has zero area as vkpath defines it (scenes/README.md:
/// edges parallel to within about 1e-6 radians, |e1 x e2|^2 <= 1e-12 |e1|^2 |e2|^2 in float, or a
/// normal whose square underflows): such a triangle is never hit (primNormal could not normalise
/// its normal). Decided once per triangle when it is packed (host/bvh/flatten.cpp packShape sets
/// GpuPrim::p1.w to 1), not at every test: intersectPrim reads the flag.
VKP_FN bool triangleHasZeroArea(vec3 v0, vec3 v1, vec3 v2) {
    vec3 e1 = v1 - v0;
    vec3 e2 = v2 - v0;
    vec3 n = cross(e1, e2);
    return !(dot(n, n) > (1.0e-12f * dot(e1, e1)) * dot(e2, e2)) || !(dot(n, n) > 0.0f);
}

/// Header word of a packed primitive (see GpuPrim).
VKP_FN uint primKind(GpuPrim p) { return floatBitsToUint(p.p0.w) & 3u; }
VKP_FN uint primMaterial(GpuPrim p) { return floatBitsToUint(p.p0.w) >> 2u; }
/// Light index of a primitive, or -1 when it is not in the light list.
VKP_FN int primLight(GpuPrim p) { return int(floatBitsToUint(p.p2.w)) - 1; }

/// Primitive p moved by `shift` (world units): a sphere's centre, a quad's Q and all three of a
/// triangle's vertices; radius, edges and header unchanged (w components are never touched: they
/// hold bits). Motion blur: shift = time x GpuMotion::v (lib/bindings.glsl fetchPrim).
VKP_FN GpuPrim primMoved(GpuPrim p, vec3 shift) {
    GpuPrim q = p;
    q.p0.x += shift.x;
    q.p0.y += shift.y;
    q.p0.z += shift.z;
    if (primKind(p) == PRIM_TRIANGLE) {
        q.p1.x += shift.x;
        q.p1.y += shift.y;
        q.p1.z += shift.z;
        q.p2.x += shift.x;
        q.p2.y += shift.y;
        q.p2.z += shift.z;
    }
    return q;
}

// A kernel compiled for a scene without some primitive kind defines VKP_HAS_SPHERES, VKP_HAS_QUADS
// or VKP_HAS_TRIANGLES as a boolean expression, usually a specialization constant, before including
// this header. They are tested in plain `if`s, so a false constant removes that kind's code from
// intersectPrim when the pipeline is created (on lavapipe every reachable branch body runs, see
// docs/design.md "Every reachable branch runs": a scene of quads only would otherwise run the
// triangle test too at every primitive, and a mesh the quad test). Primitives of a compiled-out
// kind are never hit.
#ifndef VKP_HAS_SPHERES
#define VKP_HAS_SPHERES true
#endif
#ifndef VKP_HAS_QUADS
#define VKP_HAS_QUADS true
#endif
#ifndef VKP_HAS_TRIANGLES
#define VKP_HAS_TRIANGLES true
#endif

/// First edge of a quad or triangle (world units): quad u as stored, triangle v1 - v0.
VKP_FN vec3 primEdge1(GpuPrim p) {
    vec3 e = vec3(p.p1.x, p.p1.y, p.p1.z);
    return (primKind(p) == PRIM_TRIANGLE) ? e - vec3(p.p0.x, p.p0.y, p.p0.z) : e;
}
/// Second edge of a quad or triangle (world units): quad v as stored, triangle v2 - v0.
VKP_FN vec3 primEdge2(GpuPrim p) {
    vec3 e = vec3(p.p2.x, p.p2.y, p.p2.z);
    return (primKind(p) == PRIM_TRIANGLE) ? e - vec3(p.p0.x, p.p0.y, p.p0.z) : e;
}

/// Any packed primitive. ab receives the surface parameters of the hit (quads, triangles; (0,0)
/// for spheres).
VKP_FN float intersectPrim(GpuPrim p, vec3 o, vec3 d, float tmin, float tmax, OUT(vec2) ab) {
    uint kind = primKind(p);
    ab = vec2(0.0f);
    float t = VKP_FAR;
    vec3 p0 = vec3(p.p0.x, p.p0.y, p.p0.z);
    vec3 p1 = vec3(p.p1.x, p.p1.y, p.p1.z);
    vec3 p2 = vec3(p.p2.x, p.p2.y, p.p2.z);
    if (VKP_HAS_SPHERES && kind == PRIM_SPHERE) {
        t = intersectSphere(p0, p.p1.w, o, d, tmin, tmax);
    }
    if (VKP_HAS_TRIANGLES && kind == PRIM_TRIANGLE) {
        // The three vertices are stored as given, so neighbours that share a vertex test the
        // bit-identical point and the watertight test keeps its guarantee through the BVH.
        // Zero-area triangles (triangleHasZeroArea, flagged in p1.w when packed) are never hit.
        t = intersectTriangleWatertight(p0, p1, p2, o, d, tmin, tmax, ab);
        if (p.p1.w != 0.0f) t = VKP_FAR;
    }
    if (VKP_HAS_QUADS && kind == PRIM_QUAD) {
        t = intersectParallelogram(p0, p1, p2, false, o, d, tmin, tmax, ab);
    }
    return t;
}

/// The hit point of the ray o + t d on primitive p (ab: intersectPrim's surface parameters),
/// recomputed from the primitive instead of o + t d, whose error grows with the distance |o|
/// travelled (a camera far away): a parallelogram's or triangle's Q + a e1 + b e2 and a sphere's
/// c + R (x - c) / |x - c| err by a few ulps of the primitive's own coordinates, which is what
/// offsetRayOrigin's offset is sized for (Wachter and Binder, Ray Tracing Gems ch. 6, sec. 6.2.1).
VKP_FN vec3 primHitPoint(GpuPrim p, vec3 o, vec3 d, float t, vec2 ab) {
    vec3 p0 = vec3(p.p0.x, p.p0.y, p.p0.z);
    vec3 x = o + t * d;
    if (primKind(p) == PRIM_SPHERE) {
        vec3 f = x - p0;
        float len = length(f);
        return (len > 0.0f) ? p0 + f * (p.p1.w / len) : x;
    }
    return p0 + ab.x * primEdge1(p) + ab.y * primEdge2(p);
}

/// The surface parameters (a, b) of a point x on flat primitive p, x = Q + a e1 + b e2 (least
/// squares in the plane of e1, e2, so a point a little off the plane still gets the parameters of
/// its projection); (0, 0) for a sphere or a degenerate primitive. Used where a point was sampled
/// rather than hit (next-event estimation of a textured light).
VKP_FN vec2 primAbAt(GpuPrim p, vec3 x) {
    if (primKind(p) == PRIM_SPHERE) return vec2(0.0f);
    vec3 e1 = primEdge1(p);
    vec3 e2 = primEdge2(p);
    vec3 v = x - vec3(p.p0.x, p.p0.y, p.p0.z);
    float d00 = dot(e1, e1);
    float d01 = dot(e1, e2);
    float d11 = dot(e2, e2);
    float den = d00 * d11 - d01 * d01;
    if (!(den > 0.0f)) return vec2(0.0f);
    return vec2((d11 * dot(v, e1) - d01 * dot(v, e2)) / den, (d00 * dot(v, e2) - d01 * dot(v, e1)) / den);
}

/// Geometric normal (unit, the primitive's front side: outward for spheres, e1 x e2 otherwise)
/// at hit point x.
VKP_FN vec3 primNormal(GpuPrim p, vec3 x) {
    if (primKind(p) == PRIM_SPHERE) return (x - vec3(p.p0.x, p.p0.y, p.p0.z)) / p.p1.w;
    return normalize(cross(primEdge1(p), primEdge2(p)));
}

/// Extra distance (world units, >= 0) by which a ray leaving point Q + a e1 + b e2 (ab = (a, b), from
/// intersectPrim) of flat primitive p must start off its plane, on top of offsetRayOrigin's step.
/// offsetRayOrigin's step is relative to the hit point's own coordinates, but the error of a point
/// computed on a quad or triangle is set by the terms that made it: per coordinate i about
/// gamma(4) (|Q_i| + |a e1_i| + |b e2_i|), gamma(n) = n eps / (1 - n eps), eps = 2^-24; what
/// matters is its component along the unit normal n, dot(|n|, that) (pbrt-v4 sec. 6.8.4-6.8.6,
/// "pError" and OffsetRayOrigin). On a large tilted plane through the origin the hit point's
/// coordinates along the normal are near 0 while that error is ulps of 100s: without this term
/// 0.08% of the rays leaving scenes/stress/tilted-quad.json hit it again. For a plane aligned with
/// the axes it is 0 (the coordinate along the normal is exact). The factor 2^-21 = 8 eps covers
/// gamma(4) and the next intersection test's own rounding of the origin's side of the plane.
/// Spheres: 0 (their points' error scales with |x|, which offsetRayOrigin covers).
VKP_FN float primOffsetDistance(GpuPrim p, vec2 ab, vec3 n) {
    if (primKind(p) == PRIM_SPHERE) return 0.0f;
    vec3 err = abs(vec3(p.p0.x, p.p0.y, p.p0.z)) + abs(ab.x * primEdge1(p)) + abs(ab.y * primEdge2(p));
    return dot(abs(n), err) * (1.0f / 2097152.0f);
}

/// Origin of a ray leaving hit point x (from primHitPoint, surface parameters ab) of primitive p, on
/// the side of unit normal n: moved off the plane by primOffsetDistance, then by offsetRayOrigin
/// (scale: the scene's rayOffsetScale, shared/ray_offset.h).
VKP_FN vec3 spawnRayOrigin(GpuPrim p, vec2 ab, vec3 x, vec3 n, float scale) {
    return offsetRayOrigin(x + primOffsetDistance(p, ab, n) * n, n, scale);
}

/// spawnRayOrigin with `extra` world units (>= 0) added to primOffsetDistance: the rounding an
/// instance's transform adds (shared/instance.h instanceOffsetDistance). extra = 0 gives
/// spawnRayOrigin's point bit for bit.
VKP_FN vec3 spawnRayOriginExtra(GpuPrim p, vec2 ab, vec3 x, vec3 n, float extra, float scale) {
    return offsetRayOrigin(x + (primOffsetDistance(p, ab, n) + extra) * n, n, scale);
}

/// True when point x lies in the plane of flat primitive p, within the rounding band that
/// primOffsetDistance bounds for any point of p: from there p subtends no solid angle, so light
/// sampling must not pick it (a direction "towards" it is tangent to x's surface up to rounding, and
/// its pdf cannot be evaluated consistently: the book's mixture then weighted such samples by
/// 2 albedo).
VKP_FN bool inPrimPlane(GpuPrim p, vec3 x) {
    if (primKind(p) == PRIM_SPHERE) return false;
    vec3 n = normalize(cross(primEdge1(p), primEdge2(p)));
    float band = primOffsetDistance(p, vec2(1.0f, 1.0f), n);
    return abs(dot(x - vec3(p.p0.x, p.p0.y, p.p0.z), n)) <= band;
}

/// 1/x for the slab test: +-infinity when |x| <= 1e-20 (the sign of x; +inf for +-0), so the result
/// never depends on how a device divides by zero or overflows (a reciprocal refined by Newton steps
/// can turn 1/0 into NaN). A ray with |d.x| <= 1e-20 is treated as parallel to the x slabs.
/// NaN gives +inf (meaningless but harmless: the traversal rejects rays with NaN up front).
VKP_FN float safeInverse(float x) {
    float inf = uintBitsToFloat(0x7f800000u);
    float big = (x < 0.0f) ? -inf : inf;
    return (abs(x) > 1.0e-20f) ? 1.0f / x : big;
}
VKP_FN vec3 safeInverse(vec3 d) {
    return vec3(safeInverse(d.x), safeInverse(d.y), safeInverse(d.z));
}

/// Factor applied to a box's exit distance so that rounding in the slab test never rejects a box
/// whose primitive the exact test hits (Ize, "Robust BVH Ray Traversal", JCGT 2(2), 2013, sec. 3):
/// 1 + 2 gamma(n), gamma(n) = n eps / (1 - n eps), eps = 2^-24. Each distance (b - o) * invD has a
/// rounded subtraction and product (eps each) and the reciprocal 1 / d. Ize's n = 3 takes the
/// reciprocal correctly rounded (eps), as lavapipe and the host compute it; Vulkan allows a division
/// 2.5 ulp (up to 5 eps relative), and GPUs use that, so n = 7 here: 1 + 14 eps = 1 + 8.3e-7,
/// rounded up to the float 1 + 8 * 2^-23.
const float VKP_BOX_EXIT_SCALE = 1.00000095f;

/// Slab test of a ray against the closed box [bmin, bmax] with invD = safeInverse(d) (Kay & Kajiya
/// 1986; Williams et al., "An Efficient and Robust Ray-Box Intersection Algorithm", 2005).
/// Returns the entry distance max(tmin, box entry), or VKP_FAR if the box is missed in
/// [tmin, tmax]. A flat box (bmin.x == bmax.x) is hit where the ray crosses its plane.
/// Robustness: the near/far plane of each axis is chosen by the sign of invD, never by min/max of
/// the two distances; a product 0 * inf = NaN (a ray parallel to an axis lying exactly in a slab
/// plane) is then ignored, which counts that plane as inside (the box is closed). Every fold starts
/// from tmin/tmax and keeps the old value when the comparison involves NaN, so GLSL (whose min/max
/// return the non-NaN operand on lavapipe) and C++ (glm::min may return NaN) agree bit for bit.
/// An inverted box (bmin > bmax, the empty child of GpuNode) is always missed.
VKP_FN float intersectBox(vec3 bmin, vec3 bmax, vec3 o, vec3 invD, float tmin, float tmax) {
    float enter = tmin;
    float exit = tmax;
    float n0 = (((invD.x >= 0.0f) ? bmin.x : bmax.x) - o.x) * invD.x;
    float f0 = (((invD.x >= 0.0f) ? bmax.x : bmin.x) - o.x) * invD.x;
    float n1 = (((invD.y >= 0.0f) ? bmin.y : bmax.y) - o.y) * invD.y;
    float f1 = (((invD.y >= 0.0f) ? bmax.y : bmin.y) - o.y) * invD.y;
    float n2 = (((invD.z >= 0.0f) ? bmin.z : bmax.z) - o.z) * invD.z;
    float f2 = (((invD.z >= 0.0f) ? bmax.z : bmin.z) - o.z) * invD.z;
    enter = (n0 > enter) ? n0 : enter;
    enter = (n1 > enter) ? n1 : enter;
    enter = (n2 > enter) ? n2 : enter;
    exit = (f0 < exit) ? f0 : exit;
    exit = (f1 < exit) ? f1 : exit;
    exit = (f2 < exit) ? f2 : exit;
    return (enter <= exit * VKP_BOX_EXIT_SCALE) ? enter : VKP_FAR;
}

/// Entry distances of the ray o + t d (invD = safeInverse(d)), t in (tmin, tmax), into the four
/// child boxes of the 4-wide node n (shared/wide_bvh.h): intersectBox per child, VKP_FAR where a box
/// is missed or the slot unused. The one box test of the 4-wide traversals (lib/traverse_wide_loop.glsl,
/// its CPU twin host/bvh/traverse_wide_cpu.cpp, the bench's 8-wide halves).
VKP_FN vec4 intersectWideChildren(GpuWideNode n, vec3 o, vec3 invD, float tmin, float tmax) {
    vec4 tb;
    tb.x = intersectBox(vec3(n.loX.x, n.loY.x, n.loZ.x), vec3(n.hiX.x, n.hiY.x, n.hiZ.x), o, invD, tmin, tmax);
    tb.y = intersectBox(vec3(n.loX.y, n.loY.y, n.loZ.y), vec3(n.hiX.y, n.hiY.y, n.hiZ.y), o, invD, tmin, tmax);
    tb.z = intersectBox(vec3(n.loX.z, n.loY.z, n.loZ.z), vec3(n.hiX.z, n.hiY.z, n.hiZ.z), o, invD, tmin, tmax);
    tb.w = intersectBox(vec3(n.loX.w, n.loY.w, n.loZ.w), vec3(n.hiX.w, n.hiY.w, n.hiZ.w), o, invD, tmin, tmax);
    return tb;
}

VKP_END
#endif
