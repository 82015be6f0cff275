// Helpers for the BVH tests: deterministic scene and ray generators (fixed seeds, portable: no
// std:: distributions, whose output differs between standard libraries) and a brute-force tracer.
#pragma once
#include <cmath>
#include <cstdint>
#include <random>
#include <limits>
#include <vector>

#include <glm/glm.hpp>

#include "bvh/flatten.h"
#include "scene/scene.h"
#include "shared/intersect.h"

namespace vkp::test {

/// Uniform floats in [0,1) from a fixed-seed Mersenne twister (24 random bits each).
class Rng {
public:
    explicit Rng(std::uint32_t seed) : g_(seed) {}
    float uniform() { return static_cast<float>(g_() >> 8) * (1.0f / 16777216.0f); }
    float uniform(float lo, float hi) { return lo + (hi - lo) * uniform(); }
    glm::vec3 inBox(const glm::vec3& lo, const glm::vec3& hi) {
        return glm::vec3(uniform(lo.x, hi.x), uniform(lo.y, hi.y), uniform(lo.z, hi.z));
    }
    /// Uniform direction on the unit sphere.
    glm::vec3 direction() {
        float z = uniform(-1.0f, 1.0f);
        float phi = uniform(0.0f, 6.2831853f);
        float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
        return glm::vec3(r * std::cos(phi), r * std::sin(phi), z);
    }
    std::uint32_t below(std::uint32_t n) { return static_cast<std::uint32_t>(g_() % n); }

private:
    std::mt19937 g_;
};

inline Shape sphere(const glm::vec3& c, float r, std::uint32_t material = 0) {
    Shape s;
    s.type = ShapeType::Sphere;
    s.p0 = c;
    s.radius = r;
    s.material = material;
    return s;
}
inline Shape quad(const glm::vec3& q, const glm::vec3& u, const glm::vec3& v, std::uint32_t material = 0) {
    Shape s;
    s.type = ShapeType::Quad;
    s.p0 = q;
    s.p1 = u;
    s.p2 = v;
    s.material = material;
    return s;
}
inline Shape triangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, std::uint32_t material = 0) {
    Shape s;
    s.type = ShapeType::Triangle;
    s.p0 = a;
    s.p1 = b;
    s.p2 = c;
    s.material = material;
    return s;
}

/// n triangles with vertices within `size` of a centre uniform in [-extent, extent]^3.
inline std::vector<Shape> randomTriangles(std::size_t n, std::uint32_t seed, float extent = 10.0f,
                                          float size = 1.0f) {
    Rng rng(seed);
    std::vector<Shape> out;
    out.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
        glm::vec3 c = rng.inBox(glm::vec3(-extent), glm::vec3(extent));
        out.push_back(triangle(c + size * rng.inBox(glm::vec3(-1), glm::vec3(1)),
                               c + size * rng.inBox(glm::vec3(-1), glm::vec3(1)),
                               c + size * rng.inBox(glm::vec3(-1), glm::vec3(1))));
    }
    return out;
}

inline std::vector<Shape> randomSpheres(std::size_t n, std::uint32_t seed, float extent = 10.0f) {
    Rng rng(seed);
    std::vector<Shape> out;
    for (std::size_t i = 0; i < n; ++i)
        out.push_back(sphere(rng.inBox(glm::vec3(-extent), glm::vec3(extent)), rng.uniform(0.05f, 1.0f)));
    return out;
}

/// Random quads; every third one axis-aligned (a flat bounding box), like the book's walls.
inline std::vector<Shape> randomQuads(std::size_t n, std::uint32_t seed, float extent = 10.0f) {
    Rng rng(seed);
    std::vector<Shape> out;
    for (std::size_t i = 0; i < n; ++i) {
        glm::vec3 q = rng.inBox(glm::vec3(-extent), glm::vec3(extent));
        if (i % 3 == 0) {
            int axis = static_cast<int>(rng.below(3));
            glm::vec3 u(0.0f), v(0.0f);
            u[(axis + 1) % 3] = rng.uniform(0.2f, 2.0f);
            v[(axis + 2) % 3] = rng.uniform(0.2f, 2.0f);
            out.push_back(quad(q, u, v));
        } else {
            out.push_back(quad(q, rng.inBox(glm::vec3(-2), glm::vec3(2)), rng.inBox(glm::vec3(-2), glm::vec3(2))));
        }
    }
    return out;
}

/// Latitude-longitude tessellated sphere: 2 * rings * segments triangles (poles included).
inline std::vector<Shape> sphereMesh(std::uint32_t rings, std::uint32_t segments, float radius = 5.0f) {
    auto vertex = [&](std::uint32_t i, std::uint32_t j) {
        float theta = 3.14159265f * static_cast<float>(i) / static_cast<float>(rings);
        float phi = 6.2831853f * static_cast<float>(j % segments) / static_cast<float>(segments);
        return radius * glm::vec3(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
    };
    std::vector<Shape> out;
    out.reserve(2u * rings * segments);
    for (std::uint32_t i = 0; i < rings; ++i) {
        for (std::uint32_t j = 0; j < segments; ++j) {
            glm::vec3 a = vertex(i, j), b = vertex(i + 1, j), c = vertex(i + 1, j + 1), d = vertex(i, j + 1);
            out.push_back(triangle(a, b, c));
            out.push_back(triangle(a, c, d));
        }
    }
    return out;
}

inline Scene makeScene(std::vector<Shape> shapes) {
    Scene s;
    s.path = "test.json";
    s.materials.resize(1);
    s.shapes = std::move(shapes);
    return s;
}

struct Ray {
    glm::vec3 o, d;
    float tmin, tmax;
};

/// Rays of three kinds, in turn: random origin and direction; aimed at a random point of a random
/// shape (mostly hits); origin inside the scene's bounds towards a random direction.
inline std::vector<Ray> randomRays(const std::vector<Shape>& shapes, std::size_t n, std::uint32_t seed,
                                   float extent = 12.0f) {
    Rng rng(seed);
    std::vector<Ray> rays;
    for (std::size_t i = 0; i < n; ++i) {
        Ray r{rng.inBox(glm::vec3(-1.5f * extent), glm::vec3(1.5f * extent)), rng.direction(), 0.0f, gpu::VKP_FAR};
        if (i % 3 == 1 && !shapes.empty()) {
            const Shape& s = shapes[rng.below(static_cast<std::uint32_t>(shapes.size()))];
            float a = rng.uniform(), b = rng.uniform();
            glm::vec3 target;
            if (s.type == ShapeType::Sphere) target = s.p0 + s.radius * rng.direction();
            else if (s.type == ShapeType::Quad) target = s.p0 + a * s.p1 + b * s.p2;
            else {
                if (a + b > 1.0f) { a = 1.0f - a; b = 1.0f - b; }
                target = s.p0 + a * (s.p1 - s.p0) + b * (s.p2 - s.p0);
            }
            glm::vec3 dir = target - r.o;
            if (glm::length(dir) > 0.0f) r.d = glm::normalize(dir);
        } else if (i % 3 == 2) {
            r.o = rng.inBox(glm::vec3(-extent), glm::vec3(extent));
            r.tmin = 1e-4f;
            r.tmax = rng.uniform(1.0f, 30.0f);
        }
        rays.push_back(r);
    }
    return rays;
}

/// Quads in the three axis planes on integer coordinates of [0,4]^3 (a grid whose planes many
/// axis-parallel rays lie in exactly): the stress case of the slab test.
inline std::vector<Shape> axisQuadGrid() {
    std::vector<Shape> grid;  // quads in the three axis planes, on integer coordinates
    for (int i = 0; i <= 4; ++i)
        for (int j = 0; j < 4; ++j)
            for (int k = 0; k < 4; ++k) {
                const float a = float(i), b = float(j), cc = float(k);
                if ((i + j + k) % 2 == 0) grid.push_back(quad({a, b, cc}, {0, 1, 0}, {0, 0, 1}));
                if ((i + j + k) % 3 == 0) grid.push_back(quad({b, a, cc}, {0, 0, 1}, {1, 0, 0}));
                if ((i + j + k) % 2 == 1) grid.push_back(quad({b, cc, a}, {1, 0, 0}, {0, 1, 0}));
            }
    return grid;
}

/// Rays along the axes (both signs, -0 components), many exactly in axisQuadGrid's planes, with
/// and without a t interval, plus rays with a NaN origin, an infinite tmax and a NaN tmax.
inline std::vector<Ray> axisAndNonFiniteRays() {
    std::vector<Ray> rays;
    const float coords[] = {-1.0f, 0.0f, 0.5f, 1.0f, 1.25f, 2.0f, 3.0f, 4.0f, 5.0f};
    for (int axis = 0; axis < 3; ++axis)
        for (float sign : {1.0f, -1.0f})
            for (float u : coords)
                for (float v : coords)
                    for (float start : {-2.0f, 0.0f, 2.0f, 2.5f, 6.0f}) {
                        glm::vec3 o(0.0f), d(0.0f);
                        o[axis] = start;
                        o[(axis + 1) % 3] = u;
                        o[(axis + 2) % 3] = v;
                        d[axis] = sign;
                        if (sign < 0) d[(axis + 1) % 3] = -0.0f;
                        rays.push_back({o, d, 0.0f, gpu::VKP_FAR});
                        rays.push_back({o, d, 1e-3f, 3.0f});
                    }
    const float nan = std::numeric_limits<float>::quiet_NaN();
    rays.push_back({glm::vec3(nan, 0, 0), glm::vec3(0, 0, 1), 0.0f, gpu::VKP_FAR});
    rays.push_back({glm::vec3(0), glm::vec3(0, 0, 1), 0.0f, std::numeric_limits<float>::infinity()});
    rays.push_back({glm::vec3(2, 2, -3), glm::vec3(0, 0, 1), 0.0f, nan});
    return rays;
}

/// Brute force over every packed primitive: the closest t in (tmin, tmax) and the first primitive
/// that has it (hit = false: t = VKP_FAR).
struct BruteHit {
    bool hit = false;
    float t = gpu::VKP_FAR;
    std::uint32_t prim = gpu::GPU_NODE_EMPTY;
};
inline BruteHit bruteForce(const std::vector<gpu::GpuPrim>& prims, const Ray& r) {
    BruteHit h;
    float tmax = r.tmax < gpu::VKP_FAR ? r.tmax : gpu::VKP_FAR;
    for (std::uint32_t i = 0; i < prims.size(); ++i) {
        glm::vec2 ab;
        float t = gpu::intersectPrim(prims[i], r.o, r.d, r.tmin, tmax, ab);
        if (t < tmax && t < h.t) {
            h = {true, t, i};
        }
    }
    return h;
}

}  // namespace vkp::test
