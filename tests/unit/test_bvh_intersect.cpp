// The slab test (shared/intersect.h intersectBox, safeInverse) on its edge cases: axis-parallel
// rays (infinite inverse direction) on a box face, 0 * inf = NaN, rays starting inside, flat
// boxes, inverted (empty) boxes; and a random comparison with a double-precision reference.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "shared/intersect.h"
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
