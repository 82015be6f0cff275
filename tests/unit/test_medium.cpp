// Constant-density media on the host: the interval test of shared/medium.h (the kernel's code,
// compiled as C++) against point-by-point membership, and the JSON loader's constant_medium (the
// packed map takes the boundary to the unit ball or cube, in the camera-relative frame, also
// after the frame moves; the isotropic material; the variant).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "render/features.h"
#include "render/gpu_scene.h"
#include "scene/scene.h"
#include "shared/medium.h"

namespace vkp {
namespace {

/// The local point of x under medium m's map, and whether it lies inside (strictly, by margin).
glm::dvec3 local(const gpu::GpuMedium& m, glm::dvec3 x) {
    auto row = [&](glm::vec4 r) { return double(r.x) * x.x + double(r.y) * x.y + double(r.z) * x.z + double(r.w); };
    return {row(m.r0), row(m.r1), row(m.r2)};
}
double insideness(const gpu::GpuMedium& m, glm::dvec3 x) {  // < 1 inside, > 1 outside
    const glm::dvec3 l = local(m, x);
    if (std::bit_cast<std::uint32_t>(m.params.y) == gpu::MEDIUM_SPHERE) return glm::length(l);
    return std::max({std::abs(l.x), std::abs(l.y), std::abs(l.z)});
}

// Random spheres and boxes under random affine maps, random rays (many starting inside): every
// point of the ray is inside exactly when its t lies in the interval (away from the boundary).
TEST(Medium, IntervalIsWhereTheRayIsInside) {
    std::mt19937 gen(1234);
    std::uniform_real_distribution<float> uni(-1.0f, 1.0f);
    int checked = 0, hits = 0;
    for (int trial = 0; trial < 4000; ++trial) {
        gpu::GpuMedium m{};
        glm::vec4* rows[3] = {&m.r0, &m.r1, &m.r2};
        for (glm::vec4* r : rows) *r = glm::vec4(uni(gen), uni(gen), uni(gen), 0.5f * uni(gen));
        m.r0.x += 1.5f;  // keep the map far from singular
        m.r1.y += 1.5f;
        m.r2.z += 1.5f;
        m.params = glm::vec4(1.0f, std::bit_cast<float>(trial % 2 ? gpu::MEDIUM_BOX : gpu::MEDIUM_SPHERE), 0.0f, 0.0f);
        const glm::vec3 o(uni(gen), uni(gen), uni(gen));
        glm::vec3 d(uni(gen), uni(gen), uni(gen));
        if (trial % 7 == 0) d = glm::vec3(0.0f, 0.0f, 1.0f);  // along an axis too
        d = glm::normalize(d);
        const float tmin = 0.0f, tmax = (trial % 3 == 0) ? 1.5f : 10.0f;
        float t0 = -1.0f, t1 = -1.0f;
        const bool hit = gpu::mediumInterval(m, o, d, tmin, tmax, t0, t1);
        hits += hit;
        if (hit) {
            ASSERT_LE(tmin, t0);
            ASSERT_LT(t0, t1);
            ASSERT_LE(t1, tmax);
        }
        for (int k = 0; k <= 200; ++k) {
            const double t = tmin + (tmax - tmin) * k / 200.0;
            const double s = insideness(m, glm::dvec3(o) + t * glm::dvec3(d));
            if (std::abs(s - 1.0) < 1e-4) continue;  // on the boundary: either answer
            const bool in = s < 1.0;
            const bool inInterval = hit && t >= t0 - 1e-5 && t <= t1 + 1e-5;
            ASSERT_EQ(in, inInterval) << "trial " << trial << " t " << t << " interval " << hit << " [" << t0 << ", " << t1 << "]";
            ++checked;
        }
    }
    std::printf("  %d points checked, %d of 4000 rays meet their medium\n", checked, hits);
    EXPECT_GT(hits, 1000);
}

// A box and a sphere medium as the JSON loader reads them: the packed map takes the transformed
// box's corners to the cube's corners and the sphere's surface to the unit sphere, relative to
// the camera (here far from the file's origin); the same after moving the frame.
TEST(Medium, JsonBoundaryMapsToTheUnitRegion) {
    Scene scene = parseSceneJson(R"({
      "camera": {"lookfrom": [1000, 2000, -3000], "lookat": [0, 0, 0], "vfov": 40, "width": 8, "height": 8},
      "objects": [
        {"type": "constant_medium", "density": 0.5, "albedo": [0.2, 0.4, 0.9],
         "boundary": {"type": "box", "min": [0, 0, 0], "max": [165, 330, 165], "transform": [{"rotate_y": 15}, {"translate": [265, 0, 295]}]}},
        {"type": "constant_medium", "density": 0.0001, "albedo": {"type": "noise", "scale": 2},
         "boundary": {"type": "sphere", "center": [1, 2, 3], "radius": 70, "transform": [{"scale": [2, 1, 1]}]}}]})",
                                 "media.json");
    ASSERT_EQ(scene.media.size(), 2u);
    const Material& mat = scene.materials.at(scene.media[0].material);
    EXPECT_EQ(mat.type, MaterialType::Isotropic);
    EXPECT_EQ(mat.albedo, glm::vec3(0.2f, 0.4f, 0.9f));
    EXPECT_GE(scene.materials.at(scene.media[1].material).albedoTexture, 0);
    EXPECT_EQ(scene.media[1].density, 0.0001f);
    const double pi = 3.14159265358979323846, c = std::cos(15 * pi / 180), s = std::sin(15 * pi / 180);
    auto boxCorner = [&](int k) {  // rotate_y: x' = c x + s z, z' = -s x + c z; then translate
        const glm::dvec3 p((k & 1) ? 165 : 0, (k & 2) ? 330 : 0, (k & 4) ? 165 : 0);
        return glm::dvec3(c * p.x + s * p.z + 265, p.y, -s * p.x + c * p.z + 295);
    };
    for (int pass = 0; pass < 2; ++pass) {
        const std::vector<gpu::GpuMedium> g = packMedia(scene.media);
        for (int k = 0; k < 8; ++k) {
            const glm::dvec3 x = boxCorner(k) - scene.origin;
            const glm::dvec3 l = local(g[0], x);
            for (int i = 0; i < 3; ++i) EXPECT_NEAR(std::abs(l[i]), 1.0, 1e-5) << "corner " << k << " axis " << i;
            for (int i = 0; i < 3; ++i) {
                EXPECT_GE(x[i], scene.media[0].lo[i] - 1e-9);
                EXPECT_LE(x[i], scene.media[0].hi[i] + 1e-9);
            }
        }
        for (const glm::dvec3 dir : {glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0), glm::dvec3(0, 0.6, 0.8)}) {
            const glm::dvec3 x = glm::dvec3(2 * (1 + 70 * dir.x), 2 + 70 * dir.y, 3 + 70 * dir.z) - scene.origin;
            EXPECT_NEAR(glm::length(local(g[1], x)), 1.0, 1e-4);
        }
        EXPECT_NEAR(scene.media[1].hi.x - scene.media[1].lo.x, 280.0, 1e-9);  // the ellipsoid's x extent
        moveOrigin(scene, glm::dvec3(-500.0, 25.0, 4000.0), "test");
    }
    const Features f = sceneFeatures(scene, RenderOptions{});
    EXPECT_TRUE(f.hasMaterial(gpu::MAT_ISOTROPIC));
    EXPECT_TRUE(f.solidTextures);  // the noise albedo
    EXPECT_NE(f.name().find("isotropic"), std::string::npos) << f.name();
}

}  // namespace
}  // namespace vkp
