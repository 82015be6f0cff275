// The ray-origin policy (shared/ray_offset.h) against the book's fixed t_min = 0.001, measured on
// the host with the shared intersection code and the CPU twin of the traversal (label stress).
//
// Experiment, for cornell-classic at scale 1, scaled by 1e-4 and 1e5, and moved 1e4 and 1e5 from
// the origin (scenes/stress/): 100k camera rays (random pixel positions, the kernel's camera) are
// traced; at each hit a cosine-distributed direction leaves the surface, and the first surface the
// new ray hits is compared with the truth, found in double precision from the exact hit point of
// the camera ray (brute force over the quads, the surface left excluded). A secondary ray is wrong
// when it finds another surface than the truth (or none):
//  - ours: origin spawnRayOrigin(prim, primHitPoint(...), normal), t in (0, inf);
//  - the book's: origin o + t d, t in (0.001, inf);
//  - (reported, not asserted) ours without recomputing the hit point: offsetRayOrigin(o + t d).
//    o + t d errs by ulps of |o|, which on the plane x = 0 seen from x ~ 300 exceed the 2^-16 offset
//    used near 0: the ray starts behind the wall and hits it again (cornell-classic's red wall).
// Ours must be wrong in at most 1e-4 of the rays at every scale and offset (rounding can only
// matter for rays that graze an edge); the book's is wrong in >= 1% of them in each of the four
// stressed scenes: it skips true hits within 0.001 (scale 1e-4: light leaks through corners) or
// finds the surface it leaves (scale 1e5, moved 1e4 and 1e5: rounding there exceeds 0.001).
// Shadow rays (shadowRayTo) are checked the same way: a ray between two random points of the
// scene's surfaces with nothing in between must be unoccluded; the book's (from o + t d, t in
// (0.001, 0.999 d)) is not.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "bvh/flatten.h"
#include "traverse_binary_cpu.h"
#include "bvh_test_scenes.h"
#include "render/gpu_arrays.h"
#include "render/gpu_scene.h"
#include "shared/intersect.h"
#include "shared/ray_offset.h"
#include "shared/scatter.h"
#include "file_frame.h"
#include "test_paths.h"

namespace vkp::test {
namespace {

using glm::dvec3;
using glm::vec3;

/// Closest quad hit in double precision (shape index, -1 on a miss, and distance), skipping `skip`;
/// edgeDistance receives the distance of the hit point from the quad's boundary over |cos| of the
/// ray with the quad (how far the ray may be displaced before it misses the quad).
struct TrueHit {
    int shape = -1;
    double t = 1e300, edgeDistance = 0.0;
};
TrueHit trueHit(const Scene& s, const dvec3& o, const dvec3& d, int skip) {
    TrueHit h;
    for (std::size_t i = 0; i < s.shapes.size(); ++i) {
        const Shape& q = s.shapes[i];
        if (int(i) == skip || q.type != ShapeType::Quad) continue;
        const dvec3 Q(q.p0), u(q.p1), v(q.p2), n = glm::cross(u, v);
        const double dn = glm::dot(d, n);
        if (dn == 0.0) continue;
        const double t = glm::dot(Q - o, n) / dn;
        if (!(t > 0.0) || t >= h.t) continue;
        const dvec3 p = o + t * d - Q;
        const double nn = glm::dot(n, n);
        const double a = glm::dot(glm::cross(p, v), n) / nn, b = glm::dot(glm::cross(u, p), n) / nn;
        if (a >= 0 && a <= 1 && b >= 0 && b <= 1) {
            h.shape = int(i);
            h.t = t;
            const double cosine = std::abs(dn) / std::sqrt(nn);
            h.edgeDistance = std::min(std::min(a, 1 - a) * glm::length(u), std::min(b, 1 - b) * glm::length(v)) * cosine;
        }
    }
    return h;
}

struct Tally {
    long rays = 0, oursWrong = 0, bookWrong = 0, oursOther = 0, rawWrong = 0, relOnlyWrong = 0;
    long shadowRays = 0, oursShadowWrong = 0, bookShadowWrong = 0, oursShadowOther = 0;
};

/// Classifies a secondary ray's result against the truth from the exact hit point, the ray's origin
/// having been displaced by `shift`: wrong when it hits the surface it left (a planar quad never
/// sees itself) or skips the true first hit (misses it, or finds another surface farther than the
/// true distance + 4 shift / cos) although that hit is more than 4 shift from the hit quad's
/// boundary (measured across the ray). The other disagreements (a displaced ray passing on the
/// other side of an edge) are counted apart: they are the geometry of the offset, not failures.
void classify(int self, const TrueHit& truth, int got, double gotT, double shift, double cosine, long& wrong, long& other) {
    if (got == truth.shape) return;
    const bool selfHit = got == self;
    const bool skipped = truth.shape >= 0 && (got < 0 || gotT > truth.t + 4.0 * shift / cosine + 1e-6 * truth.t) &&
                         truth.edgeDistance > 4.0 * shift;
    if (selfHit || skipped) ++wrong;
    else ++other;
}

/// fileFrame: run in the file's coordinates (inFileFrame) instead of the loader's camera-relative
/// frame, for a case whose geometry is defined by where it lies against the file's origin.
Tally experiment(const std::string& file, int n, bool fileFrame = false) {
    Scene scene = fileFrame ? inFileFrame(loadSceneJson(file)) : loadSceneJson(file);
    const FlatBvh bvh = buildFlatBvh(scene);
    const float offsetScale = gpu::rayOffsetScale(sceneExtent(bvh));  // as packGpuArrays gives the kernel
    gpu::GpuFrame f{};
    packCamera(scene.camera, f);
    const vec3 origin(f.origin), p00(f.pixel00), du(f.pixelDu), dv(f.pixelDv);
    Rng rng(2024);
    Tally tally;
    std::vector<vec3> points, normals;  // surface points (exact, rounded to float) for the shadow rays
    std::vector<int> pointShapes;
    std::vector<gpu::GpuPrim> pointPrims;
    for (int i = 0; i < n; ++i) {
        const vec3 target = p00 + rng.uniform(-0.5f, float(scene.camera.width) - 0.5f) * du +
                            rng.uniform(-0.5f, float(scene.camera.height) - 0.5f) * dv;
        const vec3 d = glm::normalize(target - origin);
        const TraceResult cam = traceClosestCpu(bvh, origin, d, 0.0f, gpu::VKP_FAR);
        if (!cam.hit) continue;
        const int shape = int(bvh.primToShape[cam.prim]);
        const gpu::GpuPrim& prim = bvh.prims[cam.prim];
        const vec3 ng = gpu::primNormal(prim, origin + cam.t * d);
        const vec3 ns = glm::dot(d, ng) < 0.0f ? ng : -ng;
        // Exact hit point of the camera ray on that shape (double).
        const Shape& q = scene.shapes[std::size_t(shape)];
        const dvec3 nq = glm::cross(dvec3(q.p1), dvec3(q.p2));
        const dvec3 od(origin), dd(d);
        const dvec3 xTrue = od + dd * (glm::dot(dvec3(q.p0) - od, nq) / glm::dot(dd, nq));
        // A cosine direction around the normal facing the camera ray.
        const vec3 w = gpu::sampleLambertian(ns, glm::vec2(rng.uniform(), rng.uniform()));
        const TrueHit truth = trueHit(scene, xTrue, dvec3(w), shape);
        const double cosine = std::max(1e-3, double(glm::dot(w, ns)));
        ++tally.rays;
        // Ours.
        const vec3 xo = gpu::spawnRayOrigin(prim, cam.ab, gpu::primHitPoint(prim, origin, d, cam.t, cam.ab), ns, offsetScale);
        const TraceResult ours = traceClosestCpu(bvh, xo, w, 0.0f, gpu::VKP_FAR);
        const double shift = glm::length(dvec3(xo) - xTrue);
        classify(shape, truth, ours.hit ? int(bvh.primToShape[ours.prim]) : -1, ours.t, shift, cosine, tally.oursWrong,
                 tally.oursOther);
        // Ours without the primitive's term (offsetRayOrigin's relative step only).
        const vec3 xRel = gpu::offsetRayOrigin(gpu::primHitPoint(prim, origin, d, cam.t, cam.ab), ns, offsetScale);
        const TraceResult rel = traceClosestCpu(bvh, xRel, w, 0.0f, gpu::VKP_FAR);
        long relOther = 0;
        classify(shape, truth, rel.hit ? int(bvh.primToShape[rel.prim]) : -1, rel.t, glm::length(dvec3(xRel) - xTrue),
                 cosine, tally.relOnlyWrong, relOther);
        // Ours without recomputing the hit point (o + t d, then the offset).
        const vec3 xRaw = gpu::offsetRayOrigin(origin + cam.t * d, ns, offsetScale);
        const TraceResult raw = traceClosestCpu(bvh, xRaw, w, 0.0f, gpu::VKP_FAR);
        long rawOther = 0;
        classify(shape, truth, raw.hit ? int(bvh.primToShape[raw.prim]) : -1, raw.t, glm::length(dvec3(xRaw) - xTrue), cosine,
                 tally.rawWrong, rawOther);
        // The book's.
        const vec3 xBook = origin + cam.t * d;
        const TraceResult book = traceClosestCpu(bvh, xBook, w, 0.001f, gpu::VKP_FAR);
        long bookOther = 0;
        classify(shape, truth, book.hit ? int(bvh.primToShape[book.prim]) : -1, book.t, glm::length(dvec3(xBook) - xTrue),
                 cosine, tally.bookWrong, bookOther);
        points.push_back(vec3(xTrue));
        pointShapes.push_back(shape);
        pointPrims.push_back(prim);
        normals.push_back(ns);
    }
    // Shadow rays between pairs of surface points that see each other (double-precision truth).
    // Wrong: blocked by the surface of either end. Blocked by a third surface: counted apart.
    for (std::size_t i = 0; i + 1 < points.size(); i += 2) {
        const dvec3 a(points[i]), b(points[i + 1]);
        const double len = glm::length(b - a);
        if (!(len > 0)) continue;
        const dvec3 dir = (b - a) / len;
        if (glm::dot(dir, dvec3(normals[i])) <= 0 || glm::dot(-dir, dvec3(normals[i + 1])) <= 0) continue;
        const TrueHit blocker = trueHit(scene, a, dir, pointShapes[i]);
        if (blocker.shape != pointShapes[i + 1] || std::abs(blocker.t - len) > 1e-6 * len) continue;  // occluded: skip
        ++tally.shadowRays;
        auto endpointHit = [&](const TraceResult& r) {
            return r.hit && (int(bvh.primToShape[r.prim]) == pointShapes[i] || int(bvh.primToShape[r.prim]) == pointShapes[i + 1]);
        };
        const vec3 xo = gpu::spawnRayOrigin(pointPrims[i], glm::vec2(1.0f), points[i], normals[i], offsetScale);
        const glm::vec4 sr = gpu::shadowRayTo(xo, points[i + 1], normals[i + 1],
                                              gpu::primOffsetDistance(pointPrims[i + 1], glm::vec2(1.0f), normals[i + 1]), offsetScale);
        const TraceResult ours = traceAnyCpu(bvh, xo, vec3(sr), 0.0f, sr.w);
        tally.oursShadowWrong += endpointHit(ours);
        tally.oursShadowOther += ours.hit && !endpointHit(ours);
        const vec3 db = glm::normalize(points[i + 1] - points[i]);
        const TraceResult book = traceAnyCpu(bvh, points[i], db, 0.001f, 0.999f * glm::length(points[i + 1] - points[i]));
        tally.bookShadowWrong += endpointHit(book);
    }
    std::printf("%-26s %6ld secondary rays wrong: ours %4ld (%.4f%%; +%ld past an edge), without the primitive term %5ld "
                "(%.2f%%), ours from o + t d %5ld (%.2f%%), "
                "t_min 0.001 %6ld (%.2f%%) | %5ld shadow rays falsely occluded: ours %ld (+%ld), 0.999 d %4ld (%.2f%%)\n",
                std::filesystem::path(file).filename().c_str(), tally.rays, tally.oursWrong, 100.0 * tally.oursWrong / tally.rays,
                tally.oursOther, tally.relOnlyWrong, 100.0 * tally.relOnlyWrong / tally.rays, tally.rawWrong, 100.0 * tally.rawWrong / tally.rays, tally.bookWrong, 100.0 * tally.bookWrong / tally.rays, tally.shadowRays, tally.oursShadowWrong,
                tally.oursShadowOther, tally.bookShadowWrong, 100.0 * tally.bookShadowWrong / std::max(1L, tally.shadowRays));
    return tally;
}

TEST(StressRayOffset, OffsetPolicyHoldsAtEveryScaleWhereAFixedTminFails) {
    const int n = 100000;
    const Tally unit = experiment((scenesDir() / "cornell-classic.json").string(), n);
    EXPECT_LE(unit.oursWrong, unit.rays / 10000);
    EXPECT_LE(unit.oursShadowWrong, unit.shadowRays / 10000);
    // The scaled scenes are where a fixed t_min fails. The moved ones are loaded camera-relative
    // (docs/design.md "Camera-relative space"): their floats are cornell-classic's, so the book's
    // t_min fails there no more than at the origin (before camera-relative space it did, from 1e5 on).
    struct Case {
        const char* name;
        bool bookFails;
    };
    for (const Case c : {Case{"cornell-scale-1e-4.json", true}, Case{"cornell-scale-1e-6.json", true}, Case{"cornell-scale-1e5.json", true},
                         Case{"cornell-translate-1e4.json", false}, Case{"cornell-translate-1e5.json", false},
                         Case{"cornell-translate-1e7.json", false}}) {
        const Tally t = experiment((scenesDir() / "stress" / c.name).string(), n);
        ASSERT_GT(t.rays, n / 2) << c.name;
        EXPECT_LE(t.oursWrong, t.rays / 10000) << c.name;
        EXPECT_LE(t.oursShadowWrong, t.shadowRays / 10000) << c.name;
        if (c.bookFails) {
            EXPECT_TRUE(t.bookWrong >= t.rays / 200 || t.bookShadowWrong >= t.shadowRays / 200)
                << c.name << ": the book's t_min should fail here in >= 0.5% of the rays";
        } else {
            EXPECT_LE(t.bookWrong, std::max(2 * unit.bookWrong, t.rays / 10000)) << c.name << ": camera-relative, as at the origin";
        }
    }
}

// A large tilted quad through the origin (scenes/stress/tilted-quad.json): the hit points'
// coordinates along the normal are near 0, their error is ulps of the quad's size. The primitive
// term of spawnRayOrigin (primOffsetDistance) is what keeps leaving rays off it: without it, 79 of
// 100k camera-ray hits (0.08%) send their secondary ray back into the quad (the test wants >= 0.05%,
// five times the 1e-4 allowed for ours; deterministic: fixed seed); in a render some pixels were
// 4% too dark.
TEST(StressRayOffset, PrimitiveTermKeepsRaysOffALargeTiltedQuad) {
    const int n = 100000;
    // In the file's frame, where the quad passes through the origin (camera-relative, its plane is
    // about 59 units from the frame's origin, the camera, and the relative step alone covers its
    // rounding error: 0 of 100k rays wrong without the primitive term).
    const Tally t = experiment((scenesDir() / "stress" / "tilted-quad.json").string(), n, true);
    ASSERT_GT(t.rays, n / 2);
    EXPECT_LE(t.oursWrong, t.rays / 10000);
    EXPECT_GE(t.relOnlyWrong, t.rays / 2000) << "the relative step alone should fail here";
}

}  // namespace
}  // namespace vkp::test
