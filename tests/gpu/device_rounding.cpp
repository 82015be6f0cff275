#include "device_rounding.h"

#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <mutex>
#include <random>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "rounding_probe.spv.h"
#include "vk/buffer.h"
#include "vk/compute_pipeline.h"

namespace vkp::test {

namespace {

bool sameBits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

RoundingProbe runProbe(VulkanDevice& dev) {
    const std::vector<glm::vec4> in = roundingProbeInputs();
    const auto n = static_cast<std::uint32_t>(in.size());
    ComputePipelineDesc d;
    d.spirv = std::span<const std::uint32_t>(kRoundingProbeSpv);
    d.bindings = {vk::DescriptorType::eStorageBuffer, vk::DescriptorType::eStorageBuffer};
    d.pushConstantBytes = 4;
    ComputePipeline pipe(dev, d);
    GpuBuffer inBuf(dev, sizeof(glm::vec4) * n, vk::BufferUsageFlagBits::eStorageBuffer);
    GpuBuffer outBuf(dev, sizeof(glm::vec4) * n, vk::BufferUsageFlagBits::eStorageBuffer);
    inBuf.upload(in.data(), sizeof(glm::vec4) * n);
    pipe.bindBuffer(0, inBuf.buffer());
    pipe.bindBuffer(1, outBuf.buffer());
    dev.submitAndWait([&](vk::raii::CommandBuffer& cmd) { pipe.recordDispatch(cmd, (n + 63) / 64, 1, &n, sizeof n); });
    std::vector<glm::vec4> out(n);
    outBuf.download(out.data(), sizeof(glm::vec4) * n);
    dev.instance().throwIfValidationMessages("in the rounding probe");
    RoundingProbe p;
    p.items = n;
    for (std::uint32_t i = 0; i < n; ++i) {
        const glm::vec4 v = in[i];
        // volatile: the host's own compiler must not fuse the product and the sum either.
        volatile float product = v.x * v.y;
        p.quotient += !sameBits(out[i].x, v.x / v.y);
        p.reciprocal += !sameBits(out[i].y, 1.0f / v.y);
        p.root += !sameBits(out[i].z, std::sqrt(std::fabs(v.x)));
        p.mulAdd += !sameBits(out[i].w, product + v.z);
    }
    return p;
}

}  // namespace

std::vector<glm::vec4> roundingProbeInputs() {
    std::mt19937 rng(20261206u);
    std::uniform_real_distribution<float> mantissa(1.0f, 2.0f);
    std::uniform_int_distribution<int> exponent(-20, 20);
    auto value = [&] { return ((rng() & 1u) ? -1.0f : 1.0f) * std::ldexp(mantissa(rng), exponent(rng)); };
    std::vector<glm::vec4> in(4096);
    for (glm::vec4& v : in) v = glm::vec4(value(), value(), value(), 0.0f);
    return in;
}

std::string RoundingProbe::describe() const {
    if (exact()) return "rounds as the host (" + std::to_string(items) + " probes)";
    return "rounds otherwise than the host: of " + std::to_string(items) + " probes, a / b differs in " +
           std::to_string(quotient) + ", 1 / b in " + std::to_string(reciprocal) + ", sqrt in " + std::to_string(root) +
           ", a * b + c in " + std::to_string(mulAdd);
}

const RoundingProbe& probeRounding(VulkanDevice& dev) {
    static std::mutex mutex;
    static std::map<const VulkanDevice*, std::unique_ptr<RoundingProbe>> probes;
    std::lock_guard<std::mutex> lock(mutex);
    std::unique_ptr<RoundingProbe>& p = probes[&dev];
    if (!p) p = std::make_unique<RoundingProbe>(runProbe(dev));
    return *p;
}

}  // namespace vkp::test
