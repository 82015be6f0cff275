// The shared sampling code compiled as GLSL equals the same code compiled as C++.
// shaders/shared/{rng,onb,sampling,light_sampling,scatter}.h are checked statistically as C++ by
// tests/stats; the kernels run their GLSL build. Here every routine of the device test kernel
// shaders/tests/sampling_test.comp (ids 0..14, I/O layout at its top) runs on a few thousand inputs
// (fixed seeds, plus edge cases: u = 0 and u just below 1, points on / inside / at the centre of
// sphere lights, grazing and degenerate quads, far tiny spheres, NaN radii) and is compared with
// vkp::gpu called on the same inputs:
//   - RNG outputs bit for bit;
//   - samples (directions, points, distances, pdfs returned with a sample) against the C++ sample;
//   - evaluations (pdfX(dir), invertX(dir)) against C++ evaluated at the DEVICE's sample, so that a
//     last-ulp difference of the sample is not amplified by an ill-conditioned inverse;
//   - no NaN or Inf output in either build, for any input used here.
// Tolerances: lavapipe divides to ~0.7 ulp, does not fuse fma, and its sin/cos/atan/pow are
// approximations, so non-bit-exact results differ in the last few ulps; every field states its
// tolerance where it is compared. Where a last-ulp difference can legitimately flip a branch (a
// sample exactly on a light's edge or rim, u at a Fresnel threshold, a fuzzed mirror ray at the
// horizon), either branch is accepted there and nowhere else, and the flips are counted.
// Finally the device's own samples of the cosine hemisphere, a quad, a triangle and a sphere light
// (cone, on-surface and inside strategies) go through the chi-square tests of tests/support, so the
// device's copy is also tested statistically.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <map>
#include <memory>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "gpu_env.h"
#include "sampling_test.spv.h"
#include "shared/light_sampling.h"
#include "shared/rng.h"
#include "shared/scatter.h"
#include "stat_suite.h"
#include "vk/buffer.h"
#include "vk/compute_pipeline.h"

namespace vkp::test {
namespace {

namespace gpu = vkp::gpu;
using glm::dvec3;
using glm::vec2;
using glm::vec3;
using glm::vec4;

enum Routine : std::uint32_t {
    kRng, kOnb, kCosineHemi, kUniformSphere, kUniformHemi, kUniformCone, kUniformDisk, kUniformBall,
    kQuadLight, kTriLight, kSphereLight, kLambertian, kMetal, kDielectric, kFresnel
};

struct Item {
    vec4 in[4]{vec4(0.0f), vec4(0.0f), vec4(0.0f), vec4(0.0f)};
};
struct Out {
    vec4 o[2]{vec4(0.0f), vec4(0.0f)};
};
static_assert(sizeof(Item) == 64 && sizeof(Out) == 32, "std430 vec4 arrays");

constexpr float kBelowOne = 0x1.fffffep-1f;  // 1 - 2^-24, the largest u that rngNext returns
constexpr float kEdgeU[] = {0.0f, 0x1p-24f, 0.25f, 0.5f, 0.75f, kBelowOne};
constexpr double kPi = 3.14159265358979323846;

float asFloat(std::uint32_t b) { return std::bit_cast<float>(b); }
std::uint32_t asUint(float f) { return std::bit_cast<std::uint32_t>(f); }
vec3 xyz(const vec4& v) { return vec3(v.x, v.y, v.z); }

// ---- Running the kernel -----------------------------------------------------------------------

/// Runs routine r of sampling_test.comp on the device for every item.
std::vector<Out> runOnDevice(VulkanDevice& dev, Routine r, const std::vector<Item>& items) {
    static std::unique_ptr<ComputePipeline> pipe;  // one JIT for the whole test program
    if (!pipe) {
        ComputePipelineDesc d;
        d.spirv = std::span<const std::uint32_t>(kSamplingTestSpv);
        d.bindings = {vk::DescriptorType::eStorageBuffer, vk::DescriptorType::eStorageBuffer};
        d.pushConstantBytes = 8;
        pipe = std::make_unique<ComputePipeline>(dev, d);
    }
    const auto n = static_cast<std::uint32_t>(items.size());
    GpuBuffer in(dev, sizeof(Item) * n, vk::BufferUsageFlagBits::eStorageBuffer);
    GpuBuffer out(dev, sizeof(Out) * n, vk::BufferUsageFlagBits::eStorageBuffer);
    in.upload(items.data(), sizeof(Item) * n);
    pipe->bindBuffer(0, in.buffer());
    pipe->bindBuffer(1, out.buffer());
    const std::uint32_t push[2] = {r, n};
    dev.submitAndWait([&](vk::raii::CommandBuffer& cmd) { pipe->recordDispatch(cmd, (n + 63) / 64, 1, push, sizeof push); });
    std::vector<Out> result(n);
    out.download(result.data(), sizeof(Out) * n);
    return result;
}

void expectNoValidationMessages(VulkanDevice& dev) {
    ValidationLog& log = dev.instance().validationLog();
    std::lock_guard<std::mutex> lock(log.mutex);
    EXPECT_EQ(log.count.load(), 0u) << (log.messages.empty() ? std::string() : log.messages.front());
}

/// The kernel's main() with the C++ build of the shared headers.
Out hostKernel(Routine r, const Item& it) {
    const vec4 in0 = it.in[0], in1 = it.in[1], in2 = it.in[2], in3 = it.in[3];
    Out o;
    vec4& out0 = o.o[0];
    vec4& out1 = o.o[1];
    switch (r) {
    case kRng: {
        std::uint32_t s = gpu::rngInit(asUint(in0.x), asUint(in0.y), asUint(in0.z));
        for (int k = 0; k < 4; ++k) out0[k] = gpu::rngNext(s);
        for (int k = 0; k < 4; ++k) out1[k] = gpu::rngNext(s);
        break;
    }
    case kOnb: {
        gpu::Onb f = gpu::onbFromNormal(xyz(in0));
        out0 = vec4(gpu::toWorld(f, xyz(in1)), 0.0f);
        out1 = vec4(gpu::toLocal(f, xyz(in1)), 0.0f);
        break;
    }
    case kCosineHemi: {
        vec3 w = gpu::sampleCosineHemisphere(vec2(in0));
        out0 = vec4(w, gpu::pdfCosineHemisphere(w.z));
        out1 = vec4(gpu::invertCosineHemisphere(w), 0.0f, 0.0f);
        break;
    }
    case kUniformSphere: {
        vec3 w = gpu::sampleUniformSphere(vec2(in0));
        out0 = vec4(w, gpu::pdfUniformSphere());
        out1 = vec4(gpu::invertUniformSphere(w), 0.0f, 0.0f);
        break;
    }
    case kUniformHemi: {
        vec3 w = gpu::sampleUniformHemisphere(vec2(in0));
        out0 = vec4(w, gpu::pdfUniformHemisphere(w.z));
        out1 = vec4(gpu::invertUniformHemisphere(w), 0.0f, 0.0f);
        break;
    }
    case kUniformCone: {
        vec3 w = gpu::sampleUniformCone(vec2(in0), in0.z);
        out0 = vec4(w, gpu::pdfUniformCone(w, in0.z));
        out1 = vec4(gpu::invertUniformCone(w, in0.z), 0.0f, 0.0f);
        break;
    }
    case kUniformDisk: {
        vec2 q = gpu::sampleUniformDisk(vec2(in0));
        out0 = vec4(q, 0.0f, gpu::pdfUniformDisk(q));
        out1 = vec4(gpu::invertUniformDisk(q), 0.0f, 0.0f);
        break;
    }
    case kUniformBall: {
        vec3 q = gpu::sampleUniformBall(xyz(in0));
        out0 = vec4(q, gpu::pdfUniformBall(q));
        out1 = vec4(gpu::invertUniformBall(q), 0.0f);
        break;
    }
    case kQuadLight:
    case kTriLight: {
        const vec3 a = xyz(in0), b = xyz(in1), c = xyz(in2), p = xyz(in3);
        const vec2 xi(in0.w, in1.w);
        const bool tri = r == kTriLight;
        gpu::LightSample s = tri ? gpu::sampleTriangleLight(a, b, c, p, xi) : gpu::sampleQuadLight(a, b, c, p, xi);
        out0 = vec4(s.dir, s.dist);
        out1.x = s.pdf;
        out1.y = tri ? gpu::pdfTriangleLight(a, b, c, p, s.dir) : gpu::pdfQuadLight(a, b, c, p, s.dir);
        vec2 inv = tri ? gpu::invertTriangleLight(a, b, c, p, s.dir) : gpu::invertQuadLight(a, b, c, p, s.dir);
        out1.z = inv.x;
        out1.w = inv.y;
        break;
    }
    case kSphereLight: {
        gpu::LightSample s = gpu::sampleSphereLight(xyz(in0), in0.w, xyz(in3), vec2(in1));
        out0 = vec4(s.dir, s.dist);
        out1.x = s.pdf;
        out1.y = gpu::pdfSphereLight(xyz(in0), in0.w, xyz(in3), s.dir);
        vec2 inv = gpu::invertSphereLight(xyz(in0), in0.w, xyz(in3), s.dir);
        out1.z = inv.x;
        out1.w = inv.y;
        break;
    }
    case kLambertian: {
        vec3 w = gpu::sampleLambertian(xyz(in0), vec2(in1));
        out0 = vec4(w, gpu::pdfLambertian(xyz(in0), w));
        out1 = vec4(gpu::invertLambertian(xyz(in0), w), 0.0f, 0.0f);
        break;
    }
    case kMetal: {
        bool absorbed = false;
        vec3 w = gpu::scatterMetal(xyz(in0), xyz(in1), in1.w, xyz(in2), absorbed);
        out0 = vec4(w, absorbed ? 1.0f : 0.0f);
        break;
    }
    case kDielectric:
        out0 = vec4(gpu::scatterDielectric(xyz(in0), xyz(in1), in2.x != 0.0f, in1.w, in2.y != 0.0f, in2.z), 0.0f);
        break;
    case kFresnel:
        out0 = vec4(gpu::fresnelSchlick(in0.x, in0.y), gpu::fresnelDielectricExact(in0.x, in0.y),
                    gpu::dielectricReflectProbability(in0.x, in0.y, false),
                    gpu::dielectricReflectProbability(in0.x, in0.y, true));
        break;
    }
    return o;
}

// ---- Comparing -------------------------------------------------------------------------------

/// Collects the comparisons of one routine: failures (with the item's inputs, as hex floats, for
/// reproduction), accepted branch flips, and per field the largest error relative to its tolerance.
class Compare {
public:
    explicit Compare(std::string routine) : routine_(std::move(routine)) {}
    void item(std::size_t i, const Item& it) {
        index_ = i;
        item_ = &it;
    }
    void fail(const std::string& what) {
        ++failures_;
        if (examples_.size() >= 8) return;
        char buf[512];
        const vec4* v = item_->in;
        std::snprintf(buf, sizeof buf, "item %zu: %s\n    in0 (%a %a %a %a) in1 (%a %a %a %a)\n    in2 (%a %a %a %a) in3 (%a %a %a %a)", index_,
                      what.c_str(), v[0].x, v[0].y, v[0].z, v[0].w, v[1].x, v[1].y, v[1].z, v[1].w, v[2].x, v[2].y, v[2].z, v[2].w,
                      v[3].x, v[3].y, v[3].z, v[3].w);
        examples_.emplace_back(buf);
    }
    /// |device - host| <= absTol + relTol |host|.
    void near(const char* field, double dev, double host, double absTol, double relTol = 0.0) {
        const double err = std::fabs(dev - host), tol = absTol + relTol * std::fabs(host);
        note(field, err, tol);
        if (!(err <= tol)) fail(std::string(field) + ": device " + fmt(dev) + " host " + fmt(host) + " (tolerance " + fmt(tol) + ")");
    }
    /// The same for a value on the circle [0,1) (an inverted azimuth u.y).
    void nearCircular(const char* field, double dev, double host, double tol) {
        double err = std::fabs(dev - host);
        err = std::min(err, 1.0 - err);
        note(field, err, tol);
        if (!(err <= tol && dev >= 0.0 && dev < 1.0)) fail(std::string(field) + ": device " + fmt(dev) + " host " + fmt(host));
    }
    void bitsEqual(const char* field, float dev, float host) {
        if (asUint(dev) != asUint(host)) fail(std::string(field) + ": device bits " + fmt(asUint(dev)) + " host " + fmt(asUint(host)));
    }
    /// No NaN or Inf in either build's output.
    void finite(const Out& dev, const Out& host) {
        for (int k = 0; k < 8; ++k) {
            const float d = dev.o[k / 4][k % 4], h = host.o[k / 4][k % 4];
            if (!std::isfinite(d) || !std::isfinite(h))
                fail("non-finite output " + std::to_string(k) + ": device " + fmt(d) + " host " + fmt(h));
        }
    }
    void flip() { ++flips_; }
    int failures() const { return failures_; }
    /// Prints the summary; the gtest failure message lists the first failures.
    std::string report(std::size_t items) const {
        std::printf("    [%s] %zu items, %d failures, %d accepted branch flips; worst error/tolerance:", routine_.c_str(), items,
                    failures_, flips_);
        for (const auto& [field, w] : worst_) std::printf(" %s %.2g", field.c_str(), w);
        std::printf("\n");
        std::string all;
        for (const std::string& e : examples_) all += "\n  " + e;
        return all;
    }

private:
    static std::string fmt(double v) {
        char b[64];
        std::snprintf(b, sizeof b, "%.9g", v);
        return b;
    }
    void note(const char* field, double err, double tol) {
        double& w = worst_[field];
        const double ratio = tol > 0.0 ? err / tol : (err > 0.0 ? 1e30 : 0.0);
        if (ratio > w || std::isnan(ratio)) w = std::isnan(ratio) ? 1e30 : ratio;
    }
    std::string routine_;
    std::size_t index_ = 0;
    const Item* item_ = nullptr;
    int failures_ = 0, flips_ = 0;
    std::map<std::string, double> worst_;
    std::vector<std::string> examples_;
};

using Comparator = std::function<void(Compare&, const Item&, const Out& dev, const Out& host)>;

/// Runs routine r on the device, compares every item with `cmp`, expects no failure.
void checkRoutine(VulkanDevice& dev, Routine r, const char* name, const std::vector<Item>& items, const Comparator& cmp) {
    const std::vector<Out> d = runOnDevice(dev, r, items);
    Compare c(name);
    for (std::size_t i = 0; i < items.size(); ++i) {
        const Out h = hostKernel(r, items[i]);
        c.item(i, items[i]);
        c.finite(d[i], h);
        cmp(c, items[i], d[i], h);
    }
    const std::string examples = c.report(items.size());
    EXPECT_EQ(c.failures(), 0) << name << examples;
    expectNoValidationMessages(dev);
}
