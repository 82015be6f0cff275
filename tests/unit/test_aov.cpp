// Feature images on the host (render/aov.h, shaders/shared/aov.h, core/image_io.h layers), label
// unit: the list `--aov` takes; the means, depth and world positions made from the kernel's sums;
// the layers and their channel names; the rules of what a vertex contributes (the kernel's own
// code, built as C++); EXR files with layers (every bit back, channels sorted as OpenEXR keeps
// them) and the files of formats without layers; the feature sums in accumulation files and merges.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>

#include "core/errors.h"
#include "core/image_io.h"
#include "render/accum_file.h"
#include "render/aov.h"
#include "render/merge.h"
#include "render/render_state.h"
#include "shared/aov.h"
#include "test_paths.h"

namespace vkp {
namespace {
namespace fs = std::filesystem;

TEST(AovList, ParsesNamesAllAndRefusesUnknownOnes) {
    std::vector<Aov> v;
    EXPECT_EQ(parseAovList("normal,albedo,normal", v), "");
    EXPECT_EQ(v, (std::vector<Aov>{Aov::Albedo, Aov::Normal}));
    EXPECT_EQ(parseAovList("all", v), "");
    EXPECT_EQ(v.size(), std::size(kAllAovs));
    EXPECT_EQ(parseAovList("spp,variance", v), "");
    EXPECT_FALSE(aovNeedsKernel(v[0]) || aovNeedsKernel(v[1]));
    const std::string e = parseAovList("albedo,colour", v);
    EXPECT_NE(e.find("unknown AOV 'colour'"), std::string::npos) << e;
    EXPECT_NE(e.find("albedo, normal, depth, position, emission, variance, spp"), std::string::npos) << e;
    EXPECT_NE(parseAovList("", v), "");
    EXPECT_NE(parseAovList("albedo,", v), "");
}

/// One pixel in shared/aov.h's layout: means and counts.
void putPixel(std::vector<float>& sums, std::size_t i, glm::vec3 albedo, float samples, glm::vec3 normal, float hits, glm::vec3 pos) {
    float* s = sums.data() + i * kAovFloatsPerPixel;
    for (int c = 0; c < 3; ++c) {
        s[c] = albedo[c];
        s[4 + c] = normal[c];
        s[8 + c] = pos[c];
    }
    s[3] = samples;
    s[7] = hits;
}

TEST(AovImages, MeansDepthAndWorldPositionsFromTheSums) {
    std::vector<float> sums(3 * kAovFloatsPerPixel, 0.0f);
    // Pixel 0: 4 samples, 2 of which hit, at camera-relative (1, 2, -10) on average.
    putPixel(sums, 0, {0.5f, 0.25f, 0.1f}, 4.0f, {0.0f, 0.0f, 1.0f}, 2.0f, {1.0f, 2.0f, -10.0f});
    // Pixel 1: 2 samples, none hit.  Pixel 2: no sample at all.
    putPixel(sums, 1, {1.0f, 1.0f, 1.0f}, 2.0f, {0.0f, 0.0f, 0.0f}, 0.0f, {0.0f, 0.0f, 0.0f});
    AovFrame frame;
    frame.worldOrigin = glm::dvec3(100.0, 200.0, 300.0);
    frame.eye = glm::vec3(0.0f, 0.0f, 1.0f);
    frame.viewAxis = glm::normalize(glm::vec3(0.0f, 0.6f, -0.8f));
    const FeatureImages f = featureImages(sums, 3, 1, frame);
    EXPECT_FLOAT_EQ(f.albedo.rgb[0], 0.5f);
    EXPECT_FLOAT_EQ(f.albedo.rgb[2], 0.1f);
    EXPECT_FLOAT_EQ(f.normal.rgb[2], 1.0f);
    EXPECT_FLOAT_EQ(f.hitFraction[0], 0.5f);
    EXPECT_EQ(f.samples[0], 4.0f);
    EXPECT_EQ(f.samples[1], 2.0f);
    EXPECT_EQ(f.samples[2], 0.0f);
    EXPECT_FLOAT_EQ(f.position.rgb[0], 101.0f);
    EXPECT_FLOAT_EQ(f.position.rgb[1], 202.0f);
    EXPECT_FLOAT_EQ(f.position.rgb[2], 290.0f);
    EXPECT_NEAR(f.depth[0], 0.6 * 2.0 + 0.8 * 11.0, 1e-5);  // (1, 2, -11) from the eye along the axis
    EXPECT_FLOAT_EQ(f.albedo.rgb[3], 1.0f);
    EXPECT_TRUE(std::isinf(f.depth[1]));
    EXPECT_EQ(f.position.rgb[3], 0.0f);
    EXPECT_EQ(f.hitFraction[1], 0.0f);
    EXPECT_EQ(f.albedo.rgb[6], 0.0f);
    EXPECT_TRUE(std::isinf(f.depth[2]));
    EXPECT_THROW(featureImages(sums, 2, 1, frame), std::invalid_argument);
}

TEST(AovImages, IndirectVarianceIsTheVarianceOfTheMeanFromTheMoments) {
    std::vector<float> sums(3 * kAovFloatsPerPixel, 0.0f);
    // Pixel 0: 4 samples of indirect luminance 1, 3, 1, 3: mean 2, mean square 5, sample variance
    // (5 - 4) x 4/3, of the mean / 4.  Pixel 1: 1 sample (no variance).  Pixel 2: none.
    putPixel(sums, 0, {0.5f, 0.5f, 0.5f}, 4.0f, {0.0f, 0.0f, 1.0f}, 4.0f, {0.0f, 0.0f, -1.0f});
    sums[11] = 2.0f;
    sums[15] = 5.0f;
    putPixel(sums, 1, {0.5f, 0.5f, 0.5f}, 1.0f, {0.0f, 0.0f, 1.0f}, 1.0f, {0.0f, 0.0f, -1.0f});
    sums[kAovFloatsPerPixel + 11] = 7.0f;
    sums[kAovFloatsPerPixel + 15] = 49.0f;
    const FeatureImages f = featureImages(sums, 3, 1, AovFrame{});
    ASSERT_EQ(f.indirectVariance.size(), 3u);
    EXPECT_FLOAT_EQ(f.indirectVariance[0], 1.0f / 3.0f);
    EXPECT_EQ(f.indirectVariance[1], 0.0f);
    EXPECT_EQ(f.indirectVariance[2], 0.0f);
    sums[15] = 3.9f;  // rounding made the mean square smaller than the squared mean: 0, not negative
    EXPECT_EQ(featureImages(sums, 3, 1, AovFrame{}).indirectVariance[0], 0.0f);
}

TEST(AovImages, LayersNameTheirChannelsAndTakeVarianceAndSppFromTheSums) {
    std::vector<float> sums(2 * kAovFloatsPerPixel, 0.0f);
    putPixel(sums, 0, {0.5f, 0.5f, 0.5f}, 2.0f, {0.0f, 1.0f, 0.0f}, 2.0f, {0.0f, 0.0f, -2.0f});
    sums[12] = 0.75f;  // emission.R
    putPixel(sums, 1, {0.5f, 0.5f, 0.5f}, 1.0f, {1.0f, 0.0f, 0.0f}, 1.0f, {0.0f, 0.0f, -3.0f});
    const FeatureImages f = featureImages(sums, 2, 1, AovFrame{});
    PixelSums s;
    s.width = 2;
    s.height = 1;
    s.sum = {2.0, 4.0, 6.0, 2.0, 1.0, 1.0, 1.0, 1.0};  // pixel 0: samples 1,1,1 and 1,3,5; pixel 1: one sample
    s.sumSq = {2.0, 10.0, 26.0, 0.0, 1.0, 1.0, 1.0, 0.0};
    const std::vector<ImageLayer> layers = aovLayers(std::vector<Aov>(std::begin(kAllAovs), std::end(kAllAovs)), &f, s);
    ASSERT_EQ(layers.size(), 7u);
    EXPECT_EQ(layers[0].name, "albedo");
    EXPECT_EQ(layers[1].channels, (std::vector<std::string>{"X", "Y", "Z"}));
    EXPECT_EQ(layers[2].name, "depth");
    EXPECT_EQ(layers[2].channels, (std::vector<std::string>{"Z"}));
    EXPECT_FLOAT_EQ(layers[2].values.rgb[0], 2.0f);  // (0, 0, -2) from the eye at 0 along -z
    EXPECT_FLOAT_EQ(layers[2].values.rgb[3], 3.0f);
    EXPECT_EQ(layers[3].name, "position");
    EXPECT_EQ(layers[4].name, "emission");
    EXPECT_FLOAT_EQ(layers[4].values.rgb[0], 0.75f);
    EXPECT_EQ(layers[5].name, "variance");
    EXPECT_FLOAT_EQ(layers[5].values.rgb[0], 0.0f);  // equal samples
    EXPECT_FLOAT_EQ(layers[5].values.rgb[1], 1.0f);  // samples 1 and 3: variance 2, of the mean 1
    EXPECT_FLOAT_EQ(layers[5].values.rgb[2], 4.0f);
    EXPECT_FLOAT_EQ(layers[5].values.rgb[3], 0.0f);  // one sample: no estimate, 0
    EXPECT_EQ(layers[6].name, "spp");
    EXPECT_EQ(layers[6].channels, (std::vector<std::string>{"V"}));
    EXPECT_FLOAT_EQ(layers[6].values.rgb[0], 2.0f);
    EXPECT_FLOAT_EQ(layers[6].values.rgb[3], 1.0f);
    // Variance and spp need no kernel images; albedo does.
    EXPECT_EQ(aovLayers({Aov::Variance, Aov::Spp}, nullptr, s).size(), 2u);
    EXPECT_THROW(aovLayers({Aov::Albedo}, nullptr, s), std::invalid_argument);
}

// ---- The kernel's rules, built as C++ ------------------------------------------------------------

gpu::Bsdf bsdfOf(std::uint32_t type, glm::vec3 albedo, float param) {
    gpu::GpuMaterial m{};
    m.m0 = glm::vec4(albedo, std::bit_cast<float>(type));
    m.m1 = glm::vec4(0.0f, 0.0f, 0.0f, param);
    m.m3 = glm::vec4(0.5f, 0.4f, 0.0f, 0.0f);  // MAT_PBR: metallic, roughness
    const glm::vec3 n(0.0f, 0.0f, 1.0f);
    return gpu::makeBsdf(m, n, n, n, glm::vec3(0.0f, 0.0f, -1.0f), true);
}

TEST(AovRules, TheEmissionStopsAtGlassAndAtTheVertexButNotAtMirrors) {
    EXPECT_TRUE(gpu::aovEmissionStops(bsdfOf(gpu::MAT_DIELECTRIC, glm::vec3(1.0f), 1.5f)));  // reflects or refracts by chance
    EXPECT_FALSE(gpu::aovEmissionStops(bsdfOf(gpu::MAT_METAL, glm::vec3(0.9f), 0.0f)));     // a mirror: deterministic
    EXPECT_TRUE(gpu::aovEmissionStops(bsdfOf(gpu::MAT_METAL, glm::vec3(0.9f), 0.01f)));
    EXPECT_TRUE(gpu::aovEmissionStops(bsdfOf(gpu::MAT_LAMBERTIAN, glm::vec3(0.3f), 0.0f)));
    EXPECT_TRUE(gpu::aovEmissionStops(bsdfOf(gpu::MAT_PBR, glm::vec3(0.3f), 0.0f)));
}

TEST(AovRules, MirrorsAndGlassAreSeenThroughEverythingElseIsTheVertex) {
    EXPECT_TRUE(gpu::aovSeesThrough(bsdfOf(gpu::MAT_DIELECTRIC, glm::vec3(1.0f), 1.5f)));
    EXPECT_TRUE(gpu::aovSeesThrough(bsdfOf(gpu::MAT_METAL, glm::vec3(0.9f), 0.0f)));
    EXPECT_FALSE(gpu::aovSeesThrough(bsdfOf(gpu::MAT_METAL, glm::vec3(0.9f), 0.01f)));
    EXPECT_FALSE(gpu::aovSeesThrough(bsdfOf(gpu::MAT_LAMBERTIAN, glm::vec3(0.3f), 0.0f)));
    EXPECT_FALSE(gpu::aovSeesThrough(bsdfOf(gpu::MAT_PBR, glm::vec3(0.3f), 0.0f)));
    EXPECT_EQ(gpu::aovAlbedo(bsdfOf(gpu::MAT_LAMBERTIAN, glm::vec3(0.1f, 0.2f, 0.3f), 0.0f)), glm::vec3(0.1f, 0.2f, 0.3f));
    EXPECT_EQ(gpu::aovAlbedo(bsdfOf(gpu::MAT_METAL, glm::vec3(0.4f, 0.5f, 0.6f), 0.2f)), glm::vec3(0.4f, 0.5f, 0.6f));
    EXPECT_EQ(gpu::aovAlbedo(bsdfOf(gpu::MAT_PBR, glm::vec3(0.7f, 0.2f, 0.1f), 0.0f)), glm::vec3(0.7f, 0.2f, 0.1f));
    // The normal faces the arriving ray; a medium has none.
    gpu::GpuMaterial m{};
    m.m0 = glm::vec4(0.5f, 0.5f, 0.5f, std::bit_cast<float>(gpu::MAT_LAMBERTIAN));
    const glm::vec3 up(0.0f, 1.0f, 0.0f);
    const gpu::Bsdf fromBelow = gpu::makeBsdf(m, -up, up, up, glm::vec3(0.0f, 1.0f, 0.0f), false);
    EXPECT_EQ(gpu::aovNormal(fromBelow), -up);
    m.m0.w = std::bit_cast<float>(gpu::MAT_ISOTROPIC);
    EXPECT_EQ(gpu::aovNormal(gpu::makeBsdf(m, glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(0.0f), up, true)), glm::vec3(0.0f));
}

// ---- Files ---------------------------------------------------------------------------------------

Image ramp(std::uint32_t w, std::uint32_t h, float scale) {
    Image img(w, h);
    for (std::size_t i = 0; i < img.rgb.size(); ++i) img.rgb[i] = scale * float(i) + 0.25f;
    return img;
}

TEST(AovFiles, ExrKeepsEveryLayerAndTheImageBitForBit) {
    const fs::path dir = test::scratchDir("aov_files");
    const Image img = ramp(5, 3, 0.5f);
    WriteOptions wo;
    wo.layers.push_back({"albedo", {"R", "G", "B"}, ramp(5, 3, 0.01f)});
    wo.layers.push_back({"normal", {"X", "Y", "Z"}, ramp(5, 3, -0.02f)});
    ImageLayer depth{"depth", {"Z"}, Image(5, 3)};
    for (std::size_t i = 0; i < 15; ++i) depth.values.rgb[3 * i] = i == 7 ? std::numeric_limits<float>::infinity() : float(i);
    wo.layers.push_back(depth);
    writeImages(img, {dir / "x.exr", dir / "x.png", dir / "x.pfm"}, wo);
    EXPECT_EQ(readImage(dir / "x.exr").rgb, img.rgb);  // the image's own channels unchanged
    EXPECT_EQ(readImageLayer(dir / "x.exr", "albedo").rgb, wo.layers[0].values.rgb);
    EXPECT_EQ(readImageLayer(dir / "x.exr", "normal").rgb, wo.layers[1].values.rgb);
    const Image d = readImageLayer(dir / "x.exr", "depth");
    for (std::size_t i = 0; i < 15; ++i)
        for (int c = 0; c < 3; ++c) EXPECT_EQ(d.rgb[3 * i + c], depth.values.rgb[3 * i]) << i;
    EXPECT_THROW(readImageLayer(dir / "x.exr", "position"), InputError);
    EXPECT_THROW(readImageLayer(dir / "x.pfm", "albedo"), InputError);
    // Formats without layers: a file per layer, PFM beside a PNG.
    EXPECT_EQ(layerFilePath(dir / "x.png", "albedo"), dir / "x.albedo.pfm");
    EXPECT_EQ(layerFilePath(dir / "x.pfm", "depth"), dir / "x.depth.pfm");
    EXPECT_EQ(layerFilePath(dir / "a.b.hdr", "normal"), dir / "a.b.normal.hdr");
    EXPECT_EQ(readImage(dir / "x.albedo.pfm").rgb, wo.layers[0].values.rgb);
    EXPECT_EQ(readImage(dir / "x.normal.pfm").rgb, wo.layers[1].values.rgb);
    EXPECT_EQ(readImage(dir / "x.depth.pfm").rgb, d.rgb);
    EXPECT_FALSE(fs::exists(dir / "x.albedo.exr"));
    EXPECT_FALSE(fs::exists(dir / "x.albedo.png"));
}

TEST(AovFiles, AccumulationFilesAndMergesKeepTheFeatureSums) {
    RenderState a;
    a.width = 3;
    a.height = 2;
    a.firstSample = 0;
    a.nextSample = 4;
    a.sum.assign(6 * kStateFloatsPerPixel, 1.0f);
    a.sumSq.assign(6 * kStateFloatsPerPixel, 2.0f);
    a.aov.resize(6 * kAovFloatsPerPixel);
    for (std::size_t i = 0; i < a.aov.size(); ++i) a.aov[i] = 0.125f * float(i) + 1.0f / 3.0f;  // 11, 15: the indirect moments
    RenderKey key;
    key.entries = {{"aov", "on"}};
    const fs::path file = test::scratchDir("aov_files") / "part.exr";
    writeAccumFile(file, key, a);
    const AccumFile back = readAccumFile(file);
    EXPECT_EQ(back.state.aov, a.aov);
    // Merged: the means weighted by their counts (3 samples and 1 hit in a, 1 sample and 1 hit in b).
    RenderState b = a;
    b.firstSample = 4;
    b.nextSample = 8;
    for (std::size_t p = 0; p < a.aov.size(); p += kAovFloatsPerPixel) {
        a.aov[p + 3] = 3.0f;
        a.aov[p + 7] = 1.0f;
        b.aov[p + 3] = 1.0f;
        b.aov[p + 7] = 1.0f;
        for (int c = 0; c < 16; ++c)
            if (c != 3 && c != 7) b.aov[p + std::size_t(c)] = a.aov[p + std::size_t(c)] + 4.0f;
    }
    const RenderState m = addStates({&a, &b}, 0, 8);
    ASSERT_EQ(m.aov.size(), a.aov.size());
    for (std::size_t p = 0; p < m.aov.size(); p += kAovFloatsPerPixel) {
        for (int c = 0; c < 3; ++c) {
            EXPECT_FLOAT_EQ(m.aov[p + c], a.aov[p + c] + 1.0f);            // (3 a + (a + 4)) / 4
            EXPECT_FLOAT_EQ(m.aov[p + 4 + c], a.aov[p + 4 + c] + 1.0f);
            EXPECT_FLOAT_EQ(m.aov[p + 8 + c], a.aov[p + 8 + c] + 2.0f);    // over the hits: (a + (a + 4)) / 2
            EXPECT_FLOAT_EQ(m.aov[p + 12 + c], a.aov[p + 12 + c] + 1.0f);
        }
        EXPECT_FLOAT_EQ(m.aov[p + 11], a.aov[p + 11] + 1.0f);  // the indirect moments: over the samples
        EXPECT_FLOAT_EQ(m.aov[p + 15], a.aov[p + 15] + 1.0f);
        EXPECT_EQ(m.aov[p + 3], 4.0f);
        EXPECT_EQ(m.aov[p + 7], 2.0f);
    }
    RenderState plain = b;
    plain.aov.clear();
    EXPECT_THROW(addStates({&a, &plain}, 0, 8), InputError);
    // Files of an older vkpath, whose feature sums lack the indirect moments or the frame: the
    // header's names altered in place (same length) make such a file from this one.
    auto older = [&](const std::string& from, const std::string& to) {
        std::ifstream in(file, std::ios::binary);
        std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        const std::size_t at = bytes.find(from + '\0');
        EXPECT_NE(at, std::string::npos) << from;
        if (at != std::string::npos) bytes.replace(at, to.size(), to);
        const fs::path old = test::scratchDir("aov_files") / "older.exr";
        std::ofstream(old, std::ios::binary) << bytes;
        try {
            readAccumFile(old);
            ADD_FAILURE() << "read a file without " << from;
        } catch (const InputError& e) {
            const std::string m = e.what();
            EXPECT_NE(m.find("older.exr: its feature sums (--aov) are from an older vkpath: no "), std::string::npos) << m;
            EXPECT_NE(m.find(from), std::string::npos) << m;
            EXPECT_EQ(m.find('\n'), std::string::npos) << m;
        }
    };
    older("aov_indirect.mean", "aov_indirect.MEAN");
    older("aov_indirect.sq", "aov_indirect.SQ");
    older("vkpath.aovFrame", "vkpath.aovFRAME");
    plain.sum.clear();  // a file without them reads back without them
    RenderState c = a;
    c.aov.clear();
    writeAccumFile(file, key, c);
    EXPECT_TRUE(readAccumFile(file).state.aov.empty());
}

}  // namespace
}  // namespace vkp
