#include "reference_path.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vkp::embree_ref {

namespace {
constexpr float kPi = std::numbers::pi_v<float>;

std::uint64_t splitmix64(std::uint64_t x) {
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

/// PCG32 (O'Neill 2014, "PCG: A Family of Simple Fast Space-Efficient Statistically Good
/// Algorithms for Random Number Generation", pcg32 XSH RR).
struct Rng {
    std::uint64_t state, inc;
    Rng(std::uint64_t seed, std::uint64_t stream) : state(0), inc((stream << 1u) | 1u) {
        next();
        state += seed;
        next();
    }
    std::uint32_t nextU32() {
        std::uint64_t old = state;
        state = old * 6364136223846793005ull + inc;
        auto xorshifted = std::uint32_t(((old >> 18u) ^ old) >> 27u);
        auto rot = std::uint32_t(old >> 59u);
        return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
    }
    /// Uniform in [0, 1): 24 random bits.
    float next() { return float(nextU32() >> 8) * (1.0f / 16777216.0f); }
};

/// Orthonormal basis around unit n (Duff et al. 2017, "Building an Orthonormal Basis, Revisited").
void basis(glm::vec3 n, glm::vec3& t, glm::vec3& b) {
    float sign = std::copysign(1.0f, n.z);
    float a = -1.0f / (sign + n.z);
    float c = n.x * n.y * a;
    t = glm::vec3(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
    b = glm::vec3(c, sign + n.y * n.y * a, -n.y);
}

float powerHeuristic(float a, float b) { return a * a / (a * a + b * b); }
float maxComponent(glm::vec3 v) { return std::max(v.x, std::max(v.y, v.z)); }

/// Unit geometric normal of shape s at its point x (outward for a sphere).
glm::vec3 normalAt(const Shape& s, glm::vec3 x) {
    return s.type == ShapeType::Sphere ? (x - s.p0) / s.radius : flatNormal(s);
}

/// A point uniform in the area of quad or triangle s.
glm::vec3 pointOn(const Shape& s, float u1, float u2) {
    if (s.type == ShapeType::Quad) return s.p0 + u1 * s.p1 + u2 * s.p2;
    float r = std::sqrt(u1);  // uniform barycentrics (Shirley and Chiu; pbrt's SampleUniformTriangle)
    return (1.0f - r) * s.p0 + r * (1.0f - u2) * s.p1 + r * u2 * s.p2;
}
}  // namespace

PathTracer::PathTracer(const Scene& scene, const EmbreeScene& rt, const LightTable& lights)
    : scene_(scene), rt_(rt), lights_(lights) {
    // The book's camera (as vkpath's packCamera in host/render/gpu_scene.cpp).
    const Camera& cam = scene.camera;
    const float h = std::tan(glm::radians(cam.vfov) / 2.0f);
    const float viewportH = 2.0f * h * cam.focusDist;
    const float viewportW = viewportH * (float(cam.width) / float(cam.height));
    const glm::vec3 w = glm::normalize(cam.lookfrom - cam.lookat);
    const glm::vec3 u = glm::normalize(glm::cross(cam.vup, w));
    const glm::vec3 v = glm::cross(w, u);
    du_ = viewportW * u / float(cam.width);
    dv_ = -viewportH * v / float(cam.height);
    pixel00_ = cam.lookfrom - cam.focusDist * w - viewportW * u / 2.0f + viewportH * v / 2.0f + 0.5f * (du_ + dv_);
    origin_ = cam.lookfrom;
    const float defocusRadius = cam.focusDist * std::tan(glm::radians(cam.defocusAngle / 2.0f));
    defocusU_ = u * defocusRadius;
    defocusV_ = v * defocusRadius;
    auto [lo, hi] = sceneBounds(scene);
    double extent = 1.0;
    if (lo.x <= hi.x) extent = std::max({extent, -lo.x, -lo.y, -lo.z, hi.x, hi.y, hi.z});
    eps_ = float(1e-5 * extent);
}

glm::vec3 PathTracer::sample(std::uint32_t x, std::uint32_t y, std::uint32_t index, std::uint64_t& rays) const {
    const std::uint64_t pixel = std::uint64_t(y) * scene_.camera.width + x;
    Rng rng(splitmix64((pixel << 32) | index), splitmix64(scene_.render.seed));
    const float jx = rng.next() - 0.5f, jy = rng.next() - 0.5f;
    glm::vec3 o = origin_;
    if (scene_.camera.defocusAngle > 0.0f) {  // a point uniform on the lens disk
        float r = std::sqrt(rng.next()), phi = 2.0f * kPi * rng.next();
        o += r * std::cos(phi) * defocusU_ + r * std::sin(phi) * defocusV_;
    }
    glm::vec3 d = glm::normalize(pixel00_ + (float(x) + jx) * du_ + (float(y) + jy) * dv_ - o);
    glm::vec3 L(0.0f), beta(1.0f), prevX = o;
    float prevPdf = 0.0f;  // solid-angle pdf of the BSDF sample that made the ray; 0: the camera ray
    for (std::uint32_t depth = 1;; ++depth) {
        ++rays;
        Hit hit;
        if (!rt_.intersect(o, d, hit)) break;  // the background is black (checkSupported)
        const Shape& s = scene_.shapes[hit.shape];
        const Material& m = scene_.materials[s.material];
        const glm::vec3 xh = o + hit.t * d;
        const glm::vec3 ng = normalAt(s, xh);
        const bool front = glm::dot(d, ng) < 0.0f;
        if (m.emits() && (front || !(m.type == MaterialType::DiffuseLight && !m.twoSided))) {
            float w = 1.0f;
            const std::int32_t li = lights_.ofShape[hit.shape];
            if (prevPdf > 0.0f && li >= 0) {
                const AreaLight& l = lights_.lights[std::size_t(li)];
                const float dist = glm::distance(prevX, xh);
                const float cosL = std::abs(glm::dot(ng, d));
                if (cosL > 0.0f) w = powerHeuristic(prevPdf, l.pick * dist * dist / (cosL * l.area));
            }
            L += beta * m.emit * w;
        }
        if (m.type == MaterialType::DiffuseLight || depth >= scene_.render.maxDepth) break;
        const glm::vec3 n = front ? ng : -ng;  // Lambertian on the side the ray came from
        const glm::vec3 xo = xh + eps_ * n;
        const glm::vec3 f = m.albedo / kPi;
        // Next-event estimation: one light by power, one point uniform in its area.
        const float uPick = rng.next(), u1 = rng.next(), u2 = rng.next();
        const AreaLight& l = lights_.lights[lights_.pick(uPick)];
        if (l.shape != hit.shape) {
            const Shape& ls = scene_.shapes[l.shape];
            const glm::vec3 p = pointOn(ls, u1, u2);
            const glm::vec3 nl = flatNormal(ls);
            glm::vec3 dir = p - xh;
            const float dist = glm::length(dir);
            dir /= dist;
            const float cosX = glm::dot(n, dir);
            const float cosLs = glm::dot(nl, dir);  // < 0: x sees the light's front
            if (dist > 0.0f && cosX > 0.0f && cosLs != 0.0f && (cosLs < 0.0f || !l.oneSided)) {
                const float pl = l.pick * dist * dist / (std::abs(cosLs) * l.area);
                const float w = powerHeuristic(pl, cosX / kPi);
                const glm::vec3 contribution = beta * f * cosX * l.emit * (w / pl);
                const glm::vec3 pOff = p + eps_ * (cosLs < 0.0f ? nl : -nl);  // off the light, towards x
                glm::vec3 sd = pOff - xo;
                const float len = glm::length(sd);
                ++rays;
                if (len > 0.0f && !rt_.occluded(xo, sd / len, len)) L += contribution;
            }
        }
        // The BSDF sample: cosine-weighted about n; f cos / pdf = albedo.
        const float r = std::sqrt(rng.next()), phi = 2.0f * kPi * rng.next();
        glm::vec3 t, b;
        basis(n, t, b);
        const float cz = std::sqrt(std::max(0.0f, 1.0f - r * r));
        const glm::vec3 dir = glm::normalize(r * std::cos(phi) * t + r * std::sin(phi) * b + cz * n);
        const float pdf = glm::dot(n, dir) / kPi;
        if (!(pdf > 0.0f)) break;
        beta *= m.albedo;
        prevPdf = pdf;
        prevX = xh;
        o = xo;
        d = dir;
        if (depth >= scene_.render.rouletteDepth) {  // Russian roulette (unbiased)
            const float q = std::min(maxComponent(beta), 0.95f);
            if (rng.next() >= q) break;
            beta /= q;
        }
    }
    return L;
}

}  // namespace vkp::embree_ref
