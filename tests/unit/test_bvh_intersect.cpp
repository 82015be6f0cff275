// The slab test (shared/intersect.h intersectBox, safeInverse) on its edge cases: axis-parallel
// rays (infinite inverse direction) on a box face, 0 * inf = NaN, rays starting inside, flat
// boxes, inverted (empty) boxes; and a random comparison with a double-precision reference.
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "shared/intersect.h"
#include "shared/ray_offset.h"
#include "bvh_test_scenes.h"

namespace {

using glm::vec3;
using vkp::gpu::intersectBox;
using vkp::gpu::safeInverse;
using vkp::gpu::VKP_FAR;

constexpr float kInf = std::numeric_limits<float>::infinity();

float box(vec3 lo, vec3 hi, vec3 o, vec3 d, float tmin = 0.0f, float tmax = VKP_FAR) {
    return intersectBox(lo, hi, o, safeInverse(d), tmin, tmax);
}

TEST(BvhIntersect, SafeInverse) {
    EXPECT_EQ(safeInverse(2.0f), 0.5f);
    EXPECT_EQ(safeInverse(-4.0f), -0.25f);
    EXPECT_EQ(safeInverse(0.0f), kInf);
    EXPECT_EQ(safeInverse(-0.0f), kInf);  // the sign of zero does not matter (see intersectBox)
    EXPECT_EQ(safeInverse(1e-30f), kInf);
    EXPECT_EQ(safeInverse(-1e-30f), -kInf);
    EXPECT_EQ(safeInverse(1e-45f), kInf);  // denormal: no overflow to a wrong sign
    EXPECT_FLOAT_EQ(safeInverse(1e-19f), 1e19f);
}

TEST(BvhIntersect, OrdinaryHitsAndMisses) {
    vec3 lo(-1), hi(1);
    EXPECT_FLOAT_EQ(box(lo, hi, vec3(-5, 0, 0), vec3(1, 0, 0)), 4.0f);
    EXPECT_FLOAT_EQ(box(lo, hi, vec3(5, 0.5f, 0.5f), vec3(-1, 0, 0)), 4.0f);
    EXPECT_EQ(box(lo, hi, vec3(5, 0, 0), vec3(1, 0, 0)), VKP_FAR);           // behind
    EXPECT_EQ(box(lo, hi, vec3(-5, 0, 0), vec3(1, 0, 0), 0.0f, 3.9f), VKP_FAR);  // tmax short
    EXPECT_EQ(box(lo, hi, vec3(-5, 0, 0), vec3(1, 0, 0), 6.1f, 10.0f), VKP_FAR);  // tmin past
    vec3 diag = glm::normalize(vec3(1, 1, 1));
    EXPECT_NEAR(box(lo, hi, vec3(-3), diag), 2.0f * std::sqrt(3.0f), 1e-5f);
    EXPECT_EQ(box(lo, hi, vec3(-3, -3, 3), diag), VKP_FAR);
}

TEST(BvhIntersect, OriginInsideReturnsTmin) {
    vec3 lo(-1), hi(1);
    EXPECT_EQ(box(lo, hi, vec3(0), vec3(0, 0, 1)), 0.0f);
    EXPECT_EQ(box(lo, hi, vec3(0.3f, -0.2f, 0.9f), glm::normalize(vec3(1, 2, 3)), 0.05f), 0.05f);
    EXPECT_EQ(box(lo, hi, vec3(1, 1, 1), vec3(1, 0, 0)), 0.0f);  // on a corner, leaving
}

// Axis-parallel rays (d.y = d.z = 0, invD = inf) lying exactly in a face plane: (bmin - o) * inf
// is 0 * inf = NaN. The closed box contains the face, so these must hit.
TEST(BvhIntersect, AxisParallelRayOnFace) {
    vec3 lo(-1), hi(1);
    for (float y : {-1.0f, 1.0f}) {
        for (float z : {-1.0f, 0.0f, 1.0f}) {
            EXPECT_FLOAT_EQ(box(lo, hi, vec3(-5, y, z), vec3(1, 0, 0)), 4.0f) << y << " " << z;
            EXPECT_FLOAT_EQ(box(lo, hi, vec3(5, y, z), vec3(-1, -0.0f, -0.0f)), 4.0f) << y << " " << z;
            EXPECT_FLOAT_EQ(box(lo, hi, vec3(y, z, 7), vec3(0, 0, -1)), 6.0f) << y << " " << z;
        }
    }
    // Just outside the face: miss.
    EXPECT_EQ(box(lo, hi, vec3(-5, std::nextafter(1.0f, 2.0f), 0), vec3(1, 0, 0)), VKP_FAR);
    EXPECT_EQ(box(lo, hi, vec3(-5, 0, std::nextafter(-1.0f, -2.0f)), vec3(1, 0, 0)), VKP_FAR);
    // Parallel and outside on the other side, with a negative zero.
    EXPECT_EQ(box(lo, hi, vec3(-5, 2, 0), vec3(1, -0.0f, 0)), VKP_FAR);
    EXPECT_EQ(box(lo, hi, vec3(-5, -2, 0), vec3(1, -0.0f, 0)), VKP_FAR);
}

// Zero-thickness boxes (an axis-aligned quad's box): crossed, grazed in-plane, and missed.
TEST(BvhIntersect, FlatBoxes) {
    vec3 lo(-1, 0, -1), hi(1, 0, 1);  // flat in y
    EXPECT_FLOAT_EQ(box(lo, hi, vec3(0.5f, 3, 0.5f), vec3(0, -1, 0)), 3.0f);
    EXPECT_FLOAT_EQ(box(lo, hi, vec3(0.5f, -3, 0.5f), vec3(0, 1, 0)), 3.0f);
    EXPECT_NEAR(box(lo, hi, vec3(0, 2, 0), glm::normalize(vec3(0.3f, -1, 0.2f))),
                2.0f * glm::length(vec3(0.3f, -1, 0.2f)), 1e-5f);
    EXPECT_FLOAT_EQ(box(lo, hi, vec3(-4, 0, 0.3f), vec3(1, 0, 0)), 3.0f);  // in the plane
    EXPECT_EQ(box(lo, hi, vec3(-4, 1e-6f, 0.3f), vec3(1, 0, 0)), VKP_FAR);
    EXPECT_EQ(box(lo, hi, vec3(1.5f, 3, 0), vec3(0, -1, 0)), VKP_FAR);    // beside
    EXPECT_EQ(box(lo, hi, vec3(0, 3, 0), vec3(0, 1, 0)), VKP_FAR);        // away
    // Hitting the rim of the flat box exactly.
    EXPECT_FLOAT_EQ(box(lo, hi, vec3(1, 3, 1), vec3(0, -1, 0)), 3.0f);
    // Flat in two axes (a segment) and in three (a point).
    EXPECT_FLOAT_EQ(box(vec3(0, 0, -1), vec3(0, 0, 1), vec3(-2, 0, 0.5f), vec3(1, 0, 0)), 2.0f);
    EXPECT_FLOAT_EQ(box(vec3(1, 2, 3), vec3(1, 2, 3), vec3(1, 2, 0), vec3(0, 0, 1)), 3.0f);
    EXPECT_EQ(box(vec3(1, 2, 3), vec3(1, 2, 3), vec3(1, 2.001f, 0), vec3(0, 0, 1)), VKP_FAR);
}

// The empty child of a GpuNode (min = +max, max = -max) is never entered, whatever the ray.
TEST(BvhIntersect, InvertedBoxNeverHit) {
    vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    vkp::test::Rng rng(7);
    for (int i = 0; i < 1000; ++i) {
        vec3 o = rng.inBox(vec3(-1e3f), vec3(1e3f));
        vec3 d = rng.direction();
        if (i % 4 == 1) d = vec3(0, 0, i % 8 == 1 ? 1.0f : -1.0f);
        if (i % 4 == 2) o = vec3(0.0f);
        ASSERT_EQ(box(lo, hi, o, d, 0.0f, kInf), VKP_FAR) << i;
    }
}

// NaN inverse directions only come from NaN rays (rejected by the traversal); here the slab test
// must not crash and the C++ result must be the documented one: NaN axes are ignored.
TEST(BvhIntersect, NaNInverseIgnoresAxis) {
    float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(intersectBox(vec3(-1), vec3(1), vec3(-5, 0, 0), vec3(1, nan, nan), 0.0f, VKP_FAR), 4.0f);
}

// Random boxes and rays against a double-precision slab test: the float test must agree except
// within a relative 1e-5 of a tangency (enter == exit), and must never miss a box that the
// reference hits by more than that margin.
TEST(BvhIntersect, MatchesDoubleReference) {
    vkp::test::Rng rng(11);
    int hits = 0;
    for (int i = 0; i < 200000; ++i) {
        vec3 a = rng.inBox(vec3(-5), vec3(5)), b = rng.inBox(vec3(-5), vec3(5));
        vec3 lo = glm::min(a, b), hi = glm::max(a, b);
        if (i % 5 == 0) hi.y = lo.y;  // flat boxes
        vec3 o = rng.inBox(vec3(-8), vec3(8));
        vec3 d = rng.direction();
        if (i % 7 == 0) d[i % 3] = 0.0f;  // parallel to one slab
        double enter = 0.0, exit = 1e30;
        bool outside = false;
        for (int k = 0; k < 3; ++k) {
            if (d[k] == 0.0f) {
                if (o[k] < lo[k] || o[k] > hi[k]) outside = true;
                continue;
            }
            double t0 = (double(lo[k]) - o[k]) / d[k], t1 = (double(hi[k]) - o[k]) / d[k];
            enter = std::max(enter, std::min(t0, t1));
            exit = std::min(exit, std::max(t0, t1));
        }
        double margin = 1e-5 * std::max(1.0, std::abs(exit));
        float got = box(lo, hi, o, d);
        if (outside) {
            ASSERT_EQ(got, VKP_FAR) << i;
        } else if (enter <= exit - margin) {
            ++hits;
            ASSERT_NE(got, VKP_FAR) << i;
            ASSERT_NEAR(got, enter, 1e-5 * std::max(1.0, enter)) << i;
        } else if (enter > exit + margin) {
            ASSERT_EQ(got, VKP_FAR) << i;
        }
    }
    EXPECT_GT(hits, 3000);  // the test exercises hits, not only misses
}

// A ray starting on a sphere and tangent to it: the double root t = 0 (no 0/0 = NaN, which GLSL's
// and glm's min/max would treat differently).
TEST(BvhIntersect, SphereTangentAtOrigin) {
    EXPECT_EQ(vkp::gpu::intersectSphere(vec3(0), 1.0f, vec3(1, 0, 0), vec3(0, 1, 0), -1.0f, 10.0f), 0.0f);
    EXPECT_EQ(vkp::gpu::intersectSphere(vec3(0), 1.0f, vec3(1, 0, 0), vec3(0, 1, 0), 0.0f, 10.0f), VKP_FAR);
    EXPECT_FLOAT_EQ(vkp::gpu::intersectSphere(vec3(0), 1.0f, vec3(0, 0, -3), vec3(0, 0, 1), 0.0f, 10.0f), 2.0f);
    EXPECT_FLOAT_EQ(vkp::gpu::intersectSphere(vec3(0), -1.0f, vec3(0), vec3(0, 0, 1), 0.0f, 10.0f), 1.0f);
}

}  // namespace

// ---- Accuracy of the sphere test far from the origin and for large radii, watertight triangles,
// zero-area triangles and reprojected hit points (issue "accurate and numerically stable").
namespace {

using glm::dvec3;

/// Near root of |o + t d - c| = r in double precision (d unit), or -1 on a miss.
double sphereRef(dvec3 c, double r, dvec3 o, dvec3 d) {
    const dvec3 f = o - c;
    const double b = glm::dot(f, d);
    const double disc = r * r - glm::dot(f - b * d, f - b * d);
    if (disc < 0) return -1;
    const double q = -b - (b > 0 ? -1.0 : 1.0) * std::sqrt(disc);  // the root without cancellation
    const double t0 = (glm::dot(f, f) - r * r) / q, t1 = q;
    return std::min(t0, t1) > 0 ? std::min(t0, t1) : std::max(t0, t1);
}

/// The textbook quadratic (b^2 - c with c = |f|^2 - r^2), for contrast.
float sphereNaive(vec3 c, float r, vec3 o, vec3 d) {
    const vec3 f = o - c;
    const float b = glm::dot(f, d), cc = glm::dot(f, f) - r * r, disc = b * b - cc;
    if (disc < 0) return VKP_FAR;
    return -b - std::sqrt(disc);
}

/// Unit in the last place of |x| (float).
double ulpOf(double x) { return std::ldexp(1.0, std::ilogb(float(std::abs(x))) - 23); }

// A unit sphere 1e4 away from the ray origin (a distant camera), far from the world origin:
// Haines et al.'s form gets t to a few ulps of t (double-precision reference with the same float
// inputs); the textbook quadratic, whose |f|^2 = 1e8 swamps r^2 = 1, misses a third of the rays.
TEST(BvhIntersect, SphereAccurateFromFarAway) {
    vkp::test::Rng rng(31);
    double worst = 0;
    int naiveMisses = 0, hits = 0;
    for (int i = 0; i < 20000; ++i) {
        const vec3 c = rng.inBox(vec3(-1e5f), vec3(1e5f));
        const vec3 o = c + 1e4f * rng.direction();
        const vec3 target = c + 0.99f * rng.direction();  // not within float resolution (~1e-3) of the silhouette
        const vec3 d = glm::normalize(target - o);
        const double ref = sphereRef(dvec3(c), 1.0, dvec3(o), dvec3(d));
        if (ref < 0) continue;
        ++hits;
        const float t = vkp::gpu::intersectSphere(c, 1.0f, o, d, 0.0f, VKP_FAR);
        ASSERT_NE(t, VKP_FAR) << i;
        worst = std::max(worst, std::abs(t - ref) / ulpOf(ref));
        naiveMisses += sphereNaive(c, 1.0f, o, d) == VKP_FAR;
    }
    std::printf("unit sphere seen from 1e4 away: error of t %.1f ulps; the textbook form misses %d of %d rays\n", worst,
                naiveMisses, hits);
    EXPECT_GT(hits, 15000);
    EXPECT_LE(worst, 8.0);
    EXPECT_GT(naiveMisses, hits / 10) << "teeth: the textbook form should fail here";
}

// A sphere of radius 1e4 (and 1e3): rays from 0.5 above its surface get t to within a few ulps of
// the coordinates' magnitude (|f|^2 - r^2 cancels there: that is float's resolution at 1e4), and
// rays leaving points of its surface moved off it by offsetRayOrigin never hit it again.
TEST(BvhIntersect, SphereAccurateForLargeRadius) {
    vkp::test::Rng rng(32);
    for (float r : {1e3f, 1e4f}) {
        double worst = 0;
        int selfHits = 0, inwardMisses = 0;
        for (int i = 0; i < 20000; ++i) {
            const vec3 n = rng.direction();
            const vec3 c = rng.inBox(vec3(-100.0f), vec3(100.0f));
            const vec3 o = c + (r + 0.5f) * n;
            const vec3 d = glm::normalize(-n + 0.3f * rng.direction());
            const double ref = sphereRef(dvec3(c), r, dvec3(o), dvec3(d));
            if (ref > 0) {
                const float t = vkp::gpu::intersectSphere(c, r, o, d, 0.0f, VKP_FAR);
                ASSERT_NE(t, VKP_FAR) << i;
                worst = std::max(worst, std::abs(t - ref) / ulpOf(glm::length(o)));
            }
            // A point of the surface (reprojected, as primHitPoint does), offset out / in.
            const vec3 x = c + r * glm::normalize(o - c);
            const vec3 out = glm::normalize(n + rng.direction() * 0.99f);
            if (glm::dot(out, n) > 0.0f)
                selfHits += vkp::gpu::intersectSphere(c, r, vkp::gpu::offsetRayOrigin(x, n, 1.0f), out, 0.0f, VKP_FAR) < VKP_FAR;
            const vec3 in = glm::normalize(-n + rng.direction() * 0.99f);
            if (glm::dot(in, n) < 0.0f) {
                const float t = vkp::gpu::intersectSphere(c, r, vkp::gpu::offsetRayOrigin(x, -n, 1.0f), in, 0.0f, VKP_FAR);
                const double chord = -2.0 * double(r) * glm::dot(dvec3(in), dvec3(n));
                inwardMisses += !(std::abs(t - chord) < 1e-3 * chord + 4.0 * ulpOf(r));
            }
        }
        std::printf("sphere of radius %g: error of t from 0.5 above it %.1f ulps of |o|; offset rays: %d self-hits, %d wrong chords\n",
                    r, worst, selfHits, inwardMisses);
        EXPECT_LE(worst, 8.0);
        EXPECT_EQ(selfHits, 0);
        EXPECT_EQ(inwardMisses, 0);
    }
}

// Rays through a shared edge or a shared vertex of a closed (planar) fan of triangles hit at least
// one of them (intersectTriangleWatertight with bit-identical shared vertices). Moller-Trumbore
// lets some through (teeth).
TEST(BvhIntersect, WatertightSharedEdgesAndVertices) {
    const vec3 centre(0.25f, -0.5f, 0.0f);
    std::vector<vec3> rim;
    for (int k = 0; k < 12; ++k) rim.push_back(vec3(std::cos(k * 0.5236f), std::sin(k * 0.5236f), 0.0f));
    vkp::test::Rng rng(33);
    int rays = 0, mtMisses = 0;
    for (int i = 0; i < 20000; ++i) {
        const int k = int(rng.below(12));
        // Through the centre (a vertex shared by all) or a point of a spoke (an edge shared by two).
        const vec3 target = (i % 2 == 0) ? centre : centre + rng.uniform(0.01f, 0.99f) * (rim[k] - centre);
        const vec3 o = target + rng.uniform(0.5f, 3.0f) * (rng.direction() + vec3(0, 0, 1.5f));
        const vec3 d = glm::normalize(target - o);
        bool hit = false, mt = false;
        for (int j = 0; j < 12; ++j) {
            glm::vec2 ab;
            const vec3 b = rim[j], c = rim[(j + 1) % 12];
            hit = hit || vkp::gpu::intersectTriangleWatertight(centre, b, c, o, d, 0.0f, VKP_FAR, ab) < VKP_FAR;
            mt = mt || vkp::gpu::intersectParallelogram(centre, b - centre, c - centre, true, o, d, 0.0f, VKP_FAR, ab) < VKP_FAR;
        }
        ++rays;
        mtMisses += !mt;
        ASSERT_TRUE(hit) << "ray " << i << " slipped through the fan";
    }
    std::printf("rays through shared edges and vertices that slip through: watertight 0, Moller-Trumbore %d of %d\n", mtMisses, rays);
    EXPECT_GT(mtMisses, 0);
}

// Zero-area triangles (collinear or coincident vertices, or edges parallel within 1e-6 radians as
// the loader defines it) are never hit, whatever the ray.
TEST(BvhIntersect, ZeroAreaTrianglesAreNeverHit) {
    vkp::test::Rng rng(34);
    const vkp::Shape degenerate[] = {vkp::test::triangle(vec3(0, 0, 0), vec3(1, 0, 0), vec3(2, 0, 0)),
                                     vkp::test::triangle(vec3(1, 1, 1), vec3(1, 1, 1), vec3(1, 1, 1)),
                                     vkp::test::triangle(vec3(-1, 2, 0.5f), vec3(0.5f, 2, 0.5f), vec3(-1, 2, 0.5f)),
                                     vkp::test::triangle(vec3(0.1f, 0.2f, 0.3f), vec3(0.3f, 0.6f, 0.9f), vec3(0.7f, 1.4f, 2.1f))};
    for (const vkp::Shape& s : degenerate) {
        const vkp::gpu::GpuPrim p = vkp::packShape(s, 0);
        for (int i = 0; i < 20000; ++i) {
            const vec3 target = s.p0 + rng.uniform() * (s.p2 - s.p0) + rng.uniform() * (s.p1 - s.p0);
            const vec3 o = target + 3.0f * rng.direction();
            glm::vec2 ab;
            ASSERT_EQ(vkp::gpu::intersectPrim(p, o, glm::normalize(target - o), 0.0f, VKP_FAR, ab), VKP_FAR) << i;
        }
    }
}

// primHitPoint puts the hit point on the primitive to within ulps of the primitive's coordinates,
// however far the ray came from; o + t d is off by ulps of |o|.
TEST(BvhIntersect, ReprojectedHitPointsLieOnTheSurface) {
    vkp::test::Rng rng(35);
    const vkp::gpu::GpuPrim sphere = vkp::packShape(vkp::test::sphere(vec3(0.5f, -0.25f, 0.125f), 1.0f), 0);
    const vkp::gpu::GpuPrim quad = vkp::packShape(vkp::test::quad(vec3(-1, -1, 0.3f), vec3(2, 0, 0.1f), vec3(0, 2, -0.2f)), 0);
    double worstSphere = 0, worstQuad = 0, worstRaw = 0;
    for (int i = 0; i < 20000; ++i) {
        const vec3 o = 1e4f * rng.direction();
        for (const vkp::gpu::GpuPrim* p : {&sphere, &quad}) {
            const vec3 target = p == &sphere ? vec3(0.5f, -0.25f, 0.125f) + 0.9f * rng.direction()
                                             : vec3(-1, -1, 0.3f) + rng.uniform() * vec3(2, 0, 0.1f) + rng.uniform() * vec3(0, 2, -0.2f);
            const vec3 d = glm::normalize(target - o);
            glm::vec2 ab;
            const float t = vkp::gpu::intersectPrim(*p, o, d, 0.0f, VKP_FAR, ab);
            if (t == VKP_FAR) continue;
            const vec3 x = vkp::gpu::primHitPoint(*p, o, d, t, ab), raw = o + t * d;
            auto distance = [&](vec3 y) {
                if (p == &sphere) return std::abs(glm::length(dvec3(y) - dvec3(0.5, -0.25, 0.125)) - 1.0);
                const dvec3 n = glm::normalize(glm::cross(dvec3(2, 0, 0.1), dvec3(0, 2, -0.2)));
                return std::abs(glm::dot(dvec3(y) - dvec3(-1, -1, 0.3), n));
            };
            (p == &sphere ? worstSphere : worstQuad) = std::max(p == &sphere ? worstSphere : worstQuad, distance(x));
            worstRaw = std::max(worstRaw, distance(raw));
        }
    }
    std::printf("distance from the surface, rays from 1e4 away: reprojected sphere %.2e, quad %.2e; o + t d %.2e\n", worstSphere,
                worstQuad, worstRaw);
    EXPECT_LT(worstSphere, 4e-7);
    EXPECT_LT(worstQuad, 4e-7);
    EXPECT_GT(worstRaw, 1e-5);  // teeth: without reprojection the error is that of |o| ~ 1e4
}

}  // namespace
