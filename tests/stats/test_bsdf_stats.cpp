// Tests of the kernel's BSDF interface, shaders/shared/bsdf.h compiled as C++ (the code the
// kernel runs): the dispatch on the material type behind makeBsdf / sampleBsdf / pdfBsdf /
// evalBsdf / bsdfCosine / bsdfNumbers, in world space with a geometric normal that is not +z and
// shading normals that lean away from it. The materials' own math has its own tests
// (test_scatter_stats, test_microfacet_stats); here:
//  (a) chi-square of sampleBsdf's directions against pdfBsdf (lambertian, and the glTF BRDF with
//      and without a tilted shading normal);
//  (b) pdfBsdf integrates to 1 over the sphere;
//  (c) every sample's pdf equals pdfBsdf of its direction, and its weight equals
//      evalBsdf(b, 1, dir) / pdf (0 where the sample is refused);
//  (d) evalBsdf is 0 exactly where bsdfCosine is not positive; delta BSDFs (metal, dielectric)
//      have pdf 0, f 0, and sample exactly the books' scatter functions;
//  (e) bsdfNumbers draws the numbers of the documented dimension layout (shared/sample_stream.h).
// Significance: each chi-square test runs at statsAlpha() (stat_suite.h: Sidak-corrected so that
// the whole stats suite falsely fails with probability <= 1% for correct code; seeds are fixed).
// This file performs 5 chi-square tests: for correct code they falsely fail together with
// probability <= 1 - (1 - statsAlpha())^5 ~ 3.9e-4.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "shared/bsdf.h"
#include "stat_suite.h"

namespace {

using namespace vkp::test;
namespace gpu = vkp::gpu;
using glm::dvec3;
using glm::vec3;
using glm::vec4;

constexpr int kSamples = 200000;

/// A kernel material record (shared/gpu_types.h) of type `type` with albedo / base colour `c`,
/// param (fuzz or ior), and for MAT_PBR metallic, roughness and specularFactor.
gpu::GpuMaterial material(std::uint32_t type, vec3 c, float param = 0.0f, float metallic = 0.0f, float roughness = 1.0f,
                          float specular = 1.0f, std::uint32_t flags = 0) {
    gpu::GpuMaterial m{};
    m.m0 = vec4(c, std::bit_cast<float>(type | flags));
    m.m1 = vec4(0.0f, 0.0f, 0.0f, param);
    m.m2 = vec4(1.0f, 1.0f, 1.0f, specular);
    m.m3 = vec4(metallic, roughness, 0.0f, 1.5f);
    return m;
}

vec3 unit(vec3 v) { return glm::normalize(v); }

double sumOf(const std::vector<double>& v) {
    double s = 0.0;
    for (double x : v) s += x;
    return s;
}

struct Case {
    const char* name;
    gpu::GpuMaterial m;
    vec3 nShade;  ///< shading normal (the geometric one is kN)
    vec3 dIn;     ///< arriving direction
};

const vec3 kN = unit(vec3(0.3f, 0.2f, 0.93f));  // geometric normal, facing the arriving rays

std::vector<Case> cases() {
    const vec3 tilted = unit(kN + vec3(0.35f, -0.1f, 0.0f));
    return {
        {"lambertian", material(gpu::MAT_LAMBERTIAN, vec3(0.8f, 0.5f, 0.2f)), kN, unit(vec3(0.2f, 0.1f, -1.0f))},
        {"pbr rough dielectric", material(gpu::MAT_PBR, vec3(0.7f, 0.6f, 0.5f), 0.0f, 0.0f, 0.8f), kN,
         unit(vec3(-0.6f, 0.1f, -0.7f))},
        {"pbr glossy metal", material(gpu::MAT_PBR, vec3(0.9f, 0.8f, 0.6f), 0.0f, 1.0f, 0.3f), kN,
         unit(vec3(0.5f, 0.3f, -0.8f))},
        {"pbr, tilted shading normal", material(gpu::MAT_PBR, vec3(0.5f), 0.0f, 0.2f, 0.5f), tilted,
         unit(vec3(-0.2f, 0.4f, -0.9f))},
        {"pbr, grazing view", material(gpu::MAT_PBR, vec3(0.6f, 0.7f, 0.8f), 0.0f, 0.0f, 0.4f, 0.5f), kN,
         unit(-kN * 0.05f + unit(glm::cross(kN, vec3(1.0f, 0.0f, 0.0f))))},
        // A medium's phase function (shared/medium.h): no surface, the whole sphere.
        {"isotropic phase (medium)", material(gpu::MAT_ISOTROPIC, vec3(0.9f, 0.6f, 0.3f)), kN, unit(vec3(0.1f, -0.4f, -0.9f))},
    };
}

// (a), (b), (c), (d) for the non-delta BSDFs.
TEST(BsdfStats, SamplesFollowPdfAndWeightsAreFCosOverPdf) {
    std::uint32_t seed = 9101;
    for (const Case& c : cases()) {
        SCOPED_TRACE(c.name);
        const gpu::Bsdf b = gpu::makeBsdf(c.m, kN, c.nShade, c.dIn, true);
        ASSERT_FALSE(gpu::bsdfIsDelta(b));
        UniformSource rng(seed++);
        std::vector<dvec3> dirs;
        double worstPdf = 0.0, worstWeight = 0.0;
        int refused = 0;
        for (int i = 0; i < kSamples; ++i) {
            vec3 dir;
            float pdf = -1.0f;
            vec3 weight;
            const bool ok = gpu::sampleBsdf(b, rng.next3(), dir, pdf, weight);
            ASSERT_TRUE(std::isfinite(dir.x) && std::isfinite(dir.y) && std::isfinite(dir.z) && std::isfinite(pdf));
            dirs.push_back(dvec3(dir));
            const vec3 f = gpu::evalBsdf(b, vec3(1.0f), dir);
            const float cosine = gpu::bsdfCosine(b, dir);
            // (d) f cos is 0 exactly where the cosine says so.
            ASSERT_EQ(cosine > 0.0f, f.x + f.y + f.z > 0.0f) << "cosine " << cosine;
            if (!ok) {
                ++refused;
                ASSERT_EQ(f.x + f.y + f.z, 0.0f) << "a refused sample must carry nothing";
                continue;
            }
            ASSERT_GT(pdf, 0.0f);
            const float alone = gpu::pdfBsdf(b, dir);
            worstPdf = std::max(worstPdf, std::fabs(double(pdf) - alone) / alone);
            // The weight uses the sampled local direction, evalBsdf the world one taken back into
            // the frame: their cosines differ by a few 1e-8 absolute, which matters at grazing
            // angles only (tolerance: 1e-3 relative + 1e-6 / cos).
            const double tol = 1e-3 + 1e-6 / double(cosine);
            for (int k = 0; k < 3; ++k)
                worstWeight = std::max(worstWeight, std::fabs(double(weight[k]) - double(f[k]) / pdf) / (double(f[k]) / pdf) / tol);
        }
        // (c) The sample's pdf is computed from the sampled half vector (microfacet.h), the one
        // alone from the direction: ~1e-4 apart for glossy lobes (test_microfacet_stats).
        EXPECT_LT(worstPdf, 1e-3);
        EXPECT_LT(worstWeight, 1.0);  // in units of the tolerance above
        const SphereBinning bins = SphereBinning::around(dvec3(kN), -1.0, 30, 60);
        const PdfDir pdf = [&](const dvec3& d) { return double(gpu::pdfBsdf(b, vec3(d))); };
        const std::vector<double> cells = integrateDirectionCells(bins, pdf, 1e-5, 10, 1);
        std::printf("    %s: pdf integral %.6f, %d of %d samples refused, worst pdf %.2e, worst weight %.2f of its tolerance\n", c.name,
                    sumOf(cells), refused, kSamples, worstPdf, worstWeight);
        EXPECT_NEAR(sumOf(cells), 1.0, 2e-3);                            // (b)
        EXPECT_TRUE(passesChi2(chi2TestDirections(dirs, bins, cells)));  // (a)
    }
}

// (d) Delta BSDFs: no density, no f for any direction, and their samples are the books' scatters.
TEST(BsdfStats, DeltaBsdfsSampleTheBooksScattersAndHaveNoDensity) {
    const vec3 dIn = unit(vec3(0.3f, -0.2f, -1.0f));
    const gpu::Bsdf metal = gpu::makeBsdf(material(gpu::MAT_METAL, vec3(0.9f, 0.7f, 0.5f), 0.3f), kN, kN, dIn, true);
    const gpu::Bsdf glass =
        gpu::makeBsdf(material(gpu::MAT_DIELECTRIC, vec3(1.0f), 1.5f, 0, 1, 1, gpu::MATF_FRESNEL_EXACT), kN, kN, dIn, false);
    ASSERT_TRUE(gpu::bsdfIsDelta(metal));
    ASSERT_TRUE(gpu::bsdfIsDelta(glass));
    EXPECT_FALSE(gpu::bsdfIsGlossy(metal));
    UniformSource rng(9201);
    for (int i = 0; i < 10000; ++i) {
        const vec3 u = rng.next3();
        vec3 dir, weight;
        float pdf = -1.0f;
        bool absorbed = false;
        const vec3 expected = gpu::scatterMetal(dIn, kN, 0.3f, u, absorbed);
        ASSERT_EQ(gpu::sampleBsdf(metal, u, dir, pdf, weight), !absorbed);
        ASSERT_EQ(dir, expected);
        ASSERT_EQ(pdf, 0.0f);
        ASSERT_EQ(weight, vec3(0.9f, 0.7f, 0.5f));
        ASSERT_TRUE(gpu::sampleBsdf(glass, u, dir, pdf, weight));
        ASSERT_EQ(dir, gpu::scatterDielectric(dIn, kN, false, 1.5f, true, u.x));
        ASSERT_EQ(weight, vec3(1.0f));
        const vec3 any = unit(vec3(u.x - 0.5f, u.y - 0.5f, u.z));
        for (const gpu::Bsdf& b : {metal, glass}) {
            ASSERT_EQ(gpu::pdfBsdf(b, any), 0.0f);
            ASSERT_EQ(gpu::evalBsdf(b, vec3(1.0f), any), vec3(0.0f));
            ASSERT_EQ(gpu::bsdfCosine(b, any), 0.0f);
        }
    }
}

// (d) A glTF BRDF whose shading normal leans over the geometric horizon gives f = 0 below the
// geometric surface even where the shading hemisphere is above it: no light leaks.
TEST(BsdfStats, ShadingNormalNeverLeaksBelowTheGeometricSurface) {
    const vec3 leaning = unit(kN + 3.0f * unit(glm::cross(kN, vec3(0.0f, 1.0f, 0.0f))));
    const gpu::Bsdf b = gpu::makeBsdf(material(gpu::MAT_PBR, vec3(0.8f), 0.0f, 0.0f, 0.7f), kN, leaning,
                                      unit(vec3(0.1f, 0.1f, -1.0f)), true);
    UniformSource rng(9301);
    int belowWithShadingAbove = 0;
    for (int i = 0; i < 20000; ++i) {
        const vec3 u = rng.next3();
        const vec3 dir = unit(vec3(2.0f * u.x - 1.0f, 2.0f * u.y - 1.0f, 2.0f * u.z - 1.0f));
        if (glm::dot(dir, kN) > 0.0f) continue;
        belowWithShadingAbove += glm::dot(dir, leaning) > 0.0f;
        ASSERT_EQ(gpu::evalBsdf(b, vec3(1.0f), dir), vec3(0.0f));
        ASSERT_LE(gpu::bsdfCosine(b, dir), 0.0f);
    }
    EXPECT_GT(belowWithShadingAbove, 1000) << "the case must have directions below the surface but above the shading one";
}

// (e) The numbers each BSDF draws: lambertian one pair, pbr a single and a pair, metal three
// singles, dielectric one single, isotropic one pair, at the places shared/sample_stream.h documents.
TEST(BsdfStats, NumbersFollowTheSampleStreamLayout) {
    const vec3 dIn = unit(vec3(0.0f, 0.0f, -1.0f));
    struct Expect {
        std::uint32_t type;
        std::uint32_t singles, pairs;
    };
    for (const Expect e : {Expect{gpu::MAT_LAMBERTIAN, 0, 1}, Expect{gpu::MAT_PBR, 1, 1}, Expect{gpu::MAT_METAL, 3, 0},
                           Expect{gpu::MAT_DIELECTRIC, 1, 0}, Expect{gpu::MAT_ISOTROPIC, 0, 1}}) {
        SCOPED_TRACE(gpu::kMaterialTypeNames[e.type]);
        const gpu::Bsdf b = gpu::makeBsdf(material(e.type, vec3(0.5f), 1.5f), kN, kN, dIn, true);
        gpu::SampleStream s = gpu::sampleStreamInit(77, 5, 3, false);
        gpu::sampleStartVertex(s, 2);
        gpu::SampleStream ref = s;
        const vec3 u = gpu::bsdfNumbers(b, s);
        EXPECT_EQ(s.singles, e.singles);
        EXPECT_EQ(s.pairs, e.pairs);
        // The same numbers drawn by hand in the same order.
        vec3 expected(0.0f);
        if (e.singles == 3) {
            expected.x = gpu::sampleNext(ref);
            expected.y = gpu::sampleNext(ref);
            expected.z = gpu::sampleNext(ref);
        }
        if (e.singles == 1 && e.pairs == 0) expected.x = gpu::sampleNext(ref);
        if (e.pairs == 1) {
            if (e.singles == 1) expected.x = gpu::sampleNext(ref);
            const glm::vec2 p = gpu::sampleNext2(ref);
            expected.y = p.x;
            expected.z = p.y;
        }
        EXPECT_EQ(u, expected);
    }
}

}  // namespace
