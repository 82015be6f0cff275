// The harness of sampling_kernel.h: device run, C++ twin of the kernel, comparisons.
#include "sampling_kernel.h"

#include <cmath>
#include <cstdio>
#include <memory>
#include <mutex>
#include <span>

#include <gtest/gtest.h>

#include "render/ggx_albedo_table.h"
#include "sampling_test.spv.h"
#include "shared/light_sampling.h"
#include "shared/microfacet.h"
#include "shared/rect_sampling.h"
#include "shared/triangle_sampling.h"
#include "shared/rng.h"
#include "shared/sample_stream.h"
#include "shared/scatter.h"
#include "stat_suite.h"
#include "vk/buffer.h"
#include "vk/compute_pipeline.h"

namespace vkp::test::sampling {

namespace gpu = vkp::gpu;

std::vector<Out> runSamplingKernel(VulkanDevice& dev, Routine r, const std::vector<Item>& items) {
    static std::unique_ptr<ComputePipeline> pipe;  // one JIT per process (each test case has its own)
    static std::unique_ptr<GpuBuffer> albedo;      // microfacet.h's GGX albedo table, as the host has it
    if (!pipe) {
        ComputePipelineDesc d;
        d.spirv = std::span<const std::uint32_t>(kSamplingTestSpv);
        d.bindings = {vk::DescriptorType::eStorageBuffer, vk::DescriptorType::eStorageBuffer, vk::DescriptorType::eStorageBuffer};
        d.pushConstantBytes = 8;
        pipe = std::make_unique<ComputePipeline>(dev, d);
        const std::vector<glm::vec4>& table = ggxAlbedoTable();
        albedo = std::make_unique<GpuBuffer>(dev, table.size() * sizeof(glm::vec4), vk::BufferUsageFlagBits::eStorageBuffer);
        albedo->upload(table.data(), table.size() * sizeof(glm::vec4));
        pipe->bindBuffer(2, albedo->buffer());
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

Out hostSamplingKernel(Routine r, const Item& it) {
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
    case kSphTriLight: {
        const vec3 a = xyz(in0), b = xyz(in1), e = xyz(in2), p = xyz(in3);
        gpu::LightSample s = gpu::sampleTriangleLightSolidAngle(a, b, e, p, vec2(in0.w, in1.w), in2.w);
        out0 = vec4(s.dir, s.dist);
        out1.x = s.pdf;
        out1.y = gpu::pdfTriangleLightSolidAngle(a, b, e, p, s.dir, in2.w);
        out1.z = gpu::triangleLightUsesSolidAngle(a, b, e, p, in2.w) ? 1.0f : 0.0f;
        break;
    }
    case kRectLight: {
        const vec3 a = xyz(in0), b = xyz(in1), e = xyz(in2), p = xyz(in3);
        gpu::LightSample s = gpu::sampleRectLight(a, b, e, p, vec2(in0.w, in1.w), in2.w);
        out0 = vec4(s.dir, s.dist);
        out1.x = s.pdf;
        out1.y = gpu::pdfRectLight(a, b, e, p, s.dir, in2.w);
        out1.z = gpu::rectLightUsesSolidAngle(a, b, e, p, in2.w) ? 1.0f : 0.0f;
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
    case kGgxVndf: {
        const vec3 v = xyz(in0), l = gpu::sampleGgxVndf(v, in0.w, vec2(in1)), h = gpu::sampleGgxVisibleNormal(v, in0.w, vec2(in1));
        out0 = vec4(l, gpu::pdfGgxVndf(v, l, in0.w));
        out1 = vec4(h, gpu::pdfGgxVndfHalf(v, h, in0.w));
        break;
    }
    case kLightPick:  // needs the whole item list (the table): compared in its own test
        break;
    case kGltfSample:
    case kGltfEval: {
        const gpu::GltfBrdf b = gpu::makeGltfBrdf(xyz(in0), in0.w, in2.x, in1.w, xyz(in1));
        const vec3 v = xyz(in3), u3(in2.y, in2.z, in2.w);
        if (r == kGltfSample) {
            float pdf = 0.0f;
            const vec3 l = gpu::sampleGltfBrdf(b, v, u3, pdf);
            out0 = vec4(l, pdf);
            out1 = vec4(gpu::pdfGltfBrdf(b, v, l), gpu::gltfSpecularProbability(b, v), b.alpha, 0.0f);
        } else {
            const vec3 l = u3, hv = v + l;
            const float len2 = glm::dot(hv, hv);
            out0 = vec4(gpu::evalGltfBrdf(b, v, l), gpu::pdfGltfBrdf(b, v, l));
            out1 = vec4(gpu::ggxVisibility(v, l, b.alpha), gpu::ggxG1(v, b.alpha),
                        len2 > 0.0f ? gpu::ggxD(hv / std::sqrt(len2), b.alpha) : 0.0f, 0.0f);
        }
        break;
    }
    case kSobol: {
        const std::uint32_t pixel = asUint(in0.x), index = asUint(in0.y), seed = asUint(in0.z), group = asUint(in0.w);
        const std::uint32_t ps = gpu::sobolPixelSeed(pixel, seed);
        for (std::uint32_t k = 0; k < 4; ++k) out0[int(k)] = gpu::sobolSample(ps, index, group, k);
        const vec2 p2 = gpu::sobolSample2(ps, index, group + 1u);
        gpu::SampleStream st = gpu::sampleStreamInit(pixel, index, seed, (group & 1u) != 0u);
        gpu::sampleStartVertex(st, group % 10u);
        out1 = vec4(p2.x, p2.y, gpu::sampleNext(st), gpu::sobolToFloat(ps));
        break;
    }
    }
    return o;
}

// ---- Comparing -------------------------------------------------------------------------------

namespace {
std::string fmt(double v) {
    char b[64];
    std::snprintf(b, sizeof b, "%.9g", v);
    return b;
}
}  // namespace

void Compare::fail(const std::string& what) {
    ++failures_;
    if (examples_.size() >= 8) return;
    char buf[512];
    const vec4* v = item_->in;
    std::snprintf(buf, sizeof buf, "item %zu: %s\n    in0 (%a %a %a %a) in1 (%a %a %a %a)\n    in2 (%a %a %a %a) in3 (%a %a %a %a)",
                  index_, what.c_str(), v[0].x, v[0].y, v[0].z, v[0].w, v[1].x, v[1].y, v[1].z, v[1].w, v[2].x, v[2].y, v[2].z,
                  v[2].w, v[3].x, v[3].y, v[3].z, v[3].w);
    examples_.emplace_back(buf);
}

void Compare::near(const char* field, double dev, double host, double absTol, double relTol) {
    const double err = std::fabs(dev - host), tol = absTol + relTol * std::fabs(host);
    note(field, err, tol);
    if (!(err <= tol)) fail(std::string(field) + ": device " + fmt(dev) + " host " + fmt(host) + " (tolerance " + fmt(tol) + ")");
}

void Compare::nearCircular(const char* field, double dev, double host, double tol) {
    double err = std::fabs(dev - host);
    err = std::min(err, 1.0 - err);
    note(field, err, tol);
    if (!(err <= tol && dev >= 0.0 && dev < 1.0)) fail(std::string(field) + ": device " + fmt(dev) + " host " + fmt(host));
}

void Compare::bitsEqual(const char* field, float dev, float host) {
    if (asUint(dev) != asUint(host)) fail(std::string(field) + ": device bits " + fmt(asUint(dev)) + " host " + fmt(asUint(host)));
}

void Compare::finite(const Out& dev, const Out& host) {
    for (int k = 0; k < 8; ++k) {
        const float d = dev.o[k / 4][k % 4], h = host.o[k / 4][k % 4];
        if (!std::isfinite(d) || !std::isfinite(h)) fail("non-finite output " + std::to_string(k) + ": device " + fmt(d) + " host " + fmt(h));
    }
}

std::string Compare::report(std::size_t items) const {
    std::printf("    [%s] %zu items, %d failures, %d accepted branch flips; worst error/tolerance:", routine_.c_str(), items, failures_,
                flips_);
    for (const auto& [field, w] : worst_) std::printf(" %s %.2g", field.c_str(), w);
    std::printf("\n");
    std::string all;
    for (const std::string& e : examples_) all += "\n  " + e;
    return all;
}

void Compare::note(const char* field, double err, double tol) {
    double& w = worst_[field];
    const double ratio = tol > 0.0 ? err / tol : (err > 0.0 ? 1e30 : 0.0);
    if (ratio > w || std::isnan(ratio)) w = std::isnan(ratio) ? 1e30 : ratio;
}

void checkRoutine(VulkanDevice& dev, Routine r, const char* name, const std::vector<Item>& items, const Comparator& cmp) {
    const std::vector<Out> d = runSamplingKernel(dev, r, items);
    Compare c(name);
    for (std::size_t i = 0; i < items.size(); ++i) {
        const Out h = hostSamplingKernel(r, items[i]);
        c.item(i, items[i]);
        c.finite(d[i], h);
        cmp(c, items[i], d[i], h);
    }
    const std::string examples = c.report(items.size());
    EXPECT_EQ(c.failures(), 0) << name << examples;
    expectNoValidationMessages(dev);
}

std::vector<vec2> uPairs(std::uint32_t seed, int n) {
    std::vector<vec2> u;
    for (float a : kEdgeU)
        for (float b : kEdgeU) u.emplace_back(a, b);
    UniformSource rng(seed);
    for (int i = 0; i < n; ++i) u.push_back(rng.next2());
    return u;
}

std::vector<vec3> unitNormals(std::uint32_t seed, int n) {
    const float h = std::sqrt(0.5f);
    std::vector<vec3> v = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0},
                           glm::normalize(vec3(0.0f, 1e-7f, -1.0f)), glm::normalize(vec3(1e-7f, 0.0f, 1.0f)),
                           glm::normalize(vec3(3e-4f, -2e-4f, -1.0f)), {h, h, -0.0f}, {0.6f, 0.0f, 0.8f}, {0.0f, -0.8f, -0.6f}};
    UniformSource rng(seed);
    for (int i = 0; i < n; ++i) v.push_back(gpu::sampleUniformSphere(rng.next2()));
    return v;
}

}  // namespace vkp::test::sampling
