// The accumulation file (render/accum_file.h) keeps every bit of a render's state; the key
// (render/render_key.h) names the first difference; merging (render/merge.h) adds sample ranges
// exactly in the order of the ranges and refuses overlaps, gaps, other renders and adaptive parts.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>

#include "core/errors.h"
#include "core/image_io.h"
#include "render/accum_file.h"
#include "render/merge.h"
#include "render/render_key.h"
#include "test_paths.h"

namespace vkp {
namespace {
namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
    const fs::path dir = test::scratchDir("render_state_files");
    fs::create_directories(dir);
    return dir / name;
}

RenderKey someKey(const std::string& seed = "1") {
    RenderKey k;
    k.entries = {{"vkpath", "0.1.0"}, {"size", "5x3"}, {"seed", seed}, {"solid-angle min", "0.1"}, {"scene", "00112233aabbccdd"}};
    return k;
}

/// A state with arbitrary float bits (denormals, negative zero, large values) in every array.
RenderState randomState(std::uint32_t w, std::uint32_t h, std::uint32_t first, std::uint32_t next, bool adaptive, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 100.0f);
    RenderState s;
    s.width = w;
    s.height = h;
    s.firstSample = first;
    s.nextSample = next;
    s.samplesTaken = 1234567890123ull;
    s.counters.rays = 0x123456789ull;
    s.counters.nonfinite = 3;
    s.counters.loopGuard = 1;
    const std::size_t n = std::size_t(w) * h * kStateFloatsPerPixel;
    for (auto* a : {&s.sum, &s.sumSq}) {
        a->resize(n);
        for (std::size_t i = 0; i < n; ++i) (*a)[i] = (i % 8 >= 4) ? u(rng) * 1e-7f : u(rng);
    }
    s.sum[5] = -0.0f;
    s.sum[6] = 1e-41f;  // a denormal
    if (adaptive) {
        s.decision.resize(n);
        for (float& x : s.decision) x = u(rng);
        s.active.resize(std::size_t(w) * h);
        for (auto& a : s.active) a = std::uint8_t(rng() & 1u);
    }
    return s;
}

bool sameBits(const std::vector<float>& a, const std::vector<float>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

TEST(AccumFile, RoundTripKeepsEveryBit) {
    for (bool adaptive : {false, true}) {
        const RenderState s = randomState(5, 3, 0, 77, adaptive, 1);
        const fs::path p = scratch(adaptive ? "adaptive.exr" : "plain.exr");
        writeAccumFile(p, someKey(), s);
        const AccumFile f = readAccumFile(p);
        EXPECT_EQ(f.state.width, 5u);
        EXPECT_EQ(f.state.height, 3u);
        EXPECT_EQ(f.state.firstSample, 0u);
        EXPECT_EQ(f.state.nextSample, 77u);
        EXPECT_EQ(f.state.samplesTaken, s.samplesTaken);
        EXPECT_EQ(f.state.counters.rays, s.counters.rays);
        EXPECT_EQ(f.state.counters.nonfinite, 3u);
        EXPECT_EQ(f.state.counters.loopGuard, 1u);
        EXPECT_TRUE(sameBits(f.state.sum, s.sum));
        {
            std::vector<float> want = s.sumSq;
            for (std::size_t i = 3; i < want.size(); i += 4) want[i] = 0.0f;  // w and its term: not stored, 0 on the device
            EXPECT_TRUE(sameBits(f.state.sumSq, want));
        }
        EXPECT_EQ(f.state.adaptive(), adaptive);
        if (adaptive) {
            EXPECT_EQ(f.state.active, s.active);
            for (std::size_t i = 0; i < s.decision.size(); ++i)
                if (i % 8 != 7) EXPECT_EQ(std::bit_cast<std::uint32_t>(f.state.decision[i]), std::bit_cast<std::uint32_t>(s.decision[i])) << i;
        }
        EXPECT_TRUE(keyMismatch(f.key, someKey()).empty()) << keyMismatch(f.key, someKey());
    }
}

// The file is an ordinary EXR: its sums' high parts and count divide into the mean image, which
// is what oiiotool or Blender would show of channels sum.* / count.
TEST(AccumFile, IsAnExrOtherToolsCanRead) {
    RenderState s = randomState(4, 2, 0, 8, false, 2);
    const fs::path p = scratch("readable.exr");
    writeAccumFile(p, someKey(), s);
    EXPECT_THROW(readImage(p), InputError);  // no R, G, B channels: it is not an image to view
    std::ifstream in(p, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (const char* name : {"sum.R", "sum_lo.G", "sumsq.B", "count", "vkpath.samples", "vkpath.key.seed", "vkpath.key.solid-angle_min"})
        EXPECT_NE(bytes.find(name), std::string::npos) << name;
}

TEST(AccumFile, RefusesFilesThatAreNotAccumulations) {
    Image img(2, 2);
    img.rgb.assign(12, 1.0f);
    const fs::path p = scratch("plain-image.exr");
    writeImage(img, p);
    try {
        readAccumFile(p);
        FAIL() << "accepted a plain image";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("not a vkpath accumulation file"), std::string::npos) << e.what();
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    }
    EXPECT_THROW(readAccumFile(scratch("missing.exr")), InputError);
    EXPECT_THROW(readAccumFile("/dev/zero"), InputError);  // not a regular file: refused, not read forever
}

TEST(RenderKey, NamesTheFirstDifference) {
    EXPECT_EQ(keyMismatch(someKey("1"), someKey("2")), "seed is 1 in it, 2 here");
    RenderKey other = someKey();
    other.entries.back().second = "ffffffffffffffff";
    EXPECT_NE(keyMismatch(other, someKey()).find("scene's content differs"), std::string::npos);
    RenderKey shorter = someKey();
    shorter.entries.erase(shorter.entries.begin() + 1);
    EXPECT_EQ(keyMismatch(shorter, someKey()), "size is missing in it");
}

AccumFile part(std::uint32_t first, std::uint32_t next, unsigned seed) { return {someKey(), randomState(5, 3, first, next, false, seed)}; }

TEST(Merge, AddsTheRangesInTheirOrderWhateverTheInputOrder) {
    const std::vector<AccumFile> parts = {part(0, 10, 1), part(10, 25, 2), part(25, 26, 3), part(26, 64, 4)};
    const std::vector<std::string> names = {"a", "b", "c", "d"};
    const AccumFile m = mergeParts(parts, names);
    EXPECT_EQ(m.state.firstSample, 0u);
    EXPECT_EQ(m.state.nextSample, 64u);
    EXPECT_EQ(m.state.samplesTaken, 4 * parts[0].state.samplesTaken);
    EXPECT_EQ(m.state.counters.rays, 4 * parts[0].state.counters.rays);
    // Each pixel's (hi, lo) holds the double sum of the parts' (hi + lo) to within float rounding of lo.
    const PixelSums ps = m.state.pixelSums();
    for (std::size_t i = 0; i < ps.sum.size(); ++i) {
        double want = 0.0;
        for (const AccumFile& p : parts) want += double(p.state.sum[(i / 4) * 8 + i % 4]) + double(p.state.sum[(i / 4) * 8 + 4 + i % 4]);
        EXPECT_NEAR(ps.sum[i], want, std::abs(want) * 1e-14) << i;
    }
    std::vector<std::size_t> perm = {0, 1, 2, 3};
    while (std::next_permutation(perm.begin(), perm.end())) {
        std::vector<AccumFile> shuffled;
        std::vector<std::string> n;
        for (std::size_t k : perm) {
            shuffled.push_back(parts[k]);
            n.push_back(names[k]);
        }
        const AccumFile o = mergeParts(shuffled, n);
        ASSERT_TRUE(sameBits(o.state.sum, m.state.sum));
        ASSERT_TRUE(sameBits(o.state.sumSq, m.state.sumSq));
    }
}

std::string mergeError(const std::vector<AccumFile>& parts) {
    std::vector<std::string> names;
    for (std::size_t i = 0; i < parts.size(); ++i) names.push_back("p" + std::to_string(i) + ".exr");
    try {
        mergeParts(parts, names);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

TEST(Merge, RefusesOverlapsGapsOtherRendersAndAdaptiveParts) {
    EXPECT_EQ(mergeError({part(0, 10, 1), part(5, 20, 2)}), "p1.exr: samples [5:20) overlap p0.exr's [0:10)");
    EXPECT_EQ(mergeError({part(12, 20, 1), part(0, 10, 2)}),
              "p0.exr: samples [12:20) leave a gap after p1.exr's [0:10): samples [10:12) are in no part");
    EXPECT_EQ(mergeError({part(0, 10, 1), part(0, 10, 2)}), "p1.exr: samples [0:10) overlap p0.exr's [0:10)");
    AccumFile otherSeed = part(10, 20, 2);
    otherSeed.key = someKey("9");
    EXPECT_EQ(mergeError({part(0, 10, 1), otherSeed}), "p1.exr: a different render than p0.exr: seed is 9 in it, 1 here");
    AccumFile adaptive{someKey(), randomState(5, 3, 0, 10, true, 3)};
    EXPECT_NE(mergeError({adaptive, part(10, 20, 2)}).find("adaptive sampling"), std::string::npos);
    EXPECT_EQ(mergeError({part(3, 9, 1)}), "");  // one part: its own range
}

}  // namespace
}  // namespace vkp
