// Micro-benchmark of the device data layout (issue 3): the BVH traversal kernel
// (shaders/tests/bvh_trace.comp + lib/traverse.glsl) run in one process on the same BVH and the
// same rays, with nodes and primitives fetched from texel buffers (the kernels' layout) and from
// storage buffers (the same source compiled with -DVKP_FETCH_SSBO), through buffer device addresses
// (-DVKP_FETCH_BDA: plain pointer loads, no descriptor; binary and 4-wide nodes; skipped on a device
// without bufferDeviceAddress), and the 4-wide node layout
// (-DVKP_BVH_WIDE, shared/wide_bvh.h; same primitives, texel buffers), and three variants of it:
// children in slot order instead of nearest first (-DVKP_WIDE_UNORDERED), inner children culled
// again against the hit found in the node's leaves (-DVKP_WIDE_RECULL), and nodes quantized to
// 64 bytes (-DVKP_BVH_WIDE_QUANTIZED, shaders/tests/wide_quantized.h); and 8-wide nodes
// (-DVKP_BVH_WIDE8, shaders/tests/traverse_wide8.glsl, host/bvh/wide_pack.h packWide8). A third
// case builds the 1M-triangle scene with other BvhBuildOptions (leaf size, traversal cost) and
// times the 4-wide kernel on each; two more (RayOrder*) trace the same rays in other orders
// (sorted by direction and origin, in windows or globally) to measure what ray reordering could
// buy on an 8-lane SIMD device. Runs are interleaved
// (A B A B ...) and reported as rays/s ratios against the texel variant: a report, never a timed
// assertion. What it asserts: every variant returns the same hits (t bit-exact, primitive, any-hit
// answer; and pass counts for the variants of the binary layout) as the texel variant, and the texel variant matches the CPU twin on a subset of the rays,
// so a broken variant cannot be timed silently.
//
// Scenes: cornell-classic, and cornell-classic with a 1M-triangle sphere mesh in its middle.
// Rays: incoherent, like path-tracing bounces: origins uniform in the scene's box, directions
// uniform on the sphere; each ray is traced closest-hit and any-hit (2 rays per ray slot).
// Environment: VKP_BENCH_RAYS (ray slots, default 131072), VKP_BENCH_ROUNDS (default 5).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sys/resource.h>

#include "bvh/flatten.h"
#include "bvh/sbvh.h"
#include "traverse_binary_cpu.h"
#include "bvh/wide_pack.h"
#include "bvh_test_scenes.h"
#include "bvh_trace.spv.h"
#include "bvh_trace_bda.spv.h"
#include "bvh_trace_ssbo.spv.h"
#include "bvh_trace_wide.spv.h"
#include "bvh_trace_wide_bda.spv.h"
#include "bvh_trace_wide_quantized.spv.h"
#include "bvh_trace_wide_recull.spv.h"
#include "bvh_trace_wide_postpone.spv.h"
#include "bvh_trace_wide_ssbo.spv.h"
#include "bvh_trace_wide_unordered.spv.h"
#include "bvh_trace_wide8.spv.h"
#include "gpu_env.h"
#include "test_paths.h"
#include "vk/buffer.h"
#include "vk/compute_pipeline.h"
#include "wide_quantized_pack.h"

namespace vkp::test {
namespace {

std::size_t envCount(const char* name, std::size_t fallback) {
    const char* v = std::getenv(name);
    return v ? std::size_t(std::strtoull(v, nullptr, 10)) : fallback;
}

/// Process CPU time (user + system, every thread: lavapipe's workers run in this process).
double cpuSeconds() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

struct Variant {
    const char* name;
    std::span<const std::uint32_t> spirv;
    vk::DescriptorType dataType;  ///< descriptor type of bindings 1 and 2
    bool wide = false;            ///< nodes not in the binary layout (GpuWideNode): hits compared by t, not pass counts
    bool bda = false;             ///< nodes and primitives read through buffer device addresses (push constants)
    bool quantized = false;       ///< 4-wide nodes quantized to 4 texels (shaders/tests/wide_quantized.h)
    bool wide8 = false;           ///< 8-wide nodes (host/bvh/wide_pack.h packWide8, shaders/tests/traverse_wide8.glsl)
};

/// Buffers of one scene, bound to one pipeline per variant.
struct LayoutBench {
    VulkanDevice& dev;
    std::size_t rayCount;
    std::vector<gpu::GpuWideNode> wide8Data;  ///< packWide8's nodes, where a variant reads them
    GpuBuffer rays, nodes, wideNodes, quantizedNodes, wide8Nodes, prims, out;
    vk::raii::BufferView nodeView{nullptr}, wideView{nullptr}, quantizedView{nullptr}, wide8View{nullptr}, primView{nullptr};
    std::vector<std::unique_ptr<ComputePipeline>> pipes;

    LayoutBench(VulkanDevice& d, const FlatBvh& bvh, const std::vector<gpu::GpuWideNode>& wide, const std::vector<Ray>& rs,
                const std::vector<Variant>& variants)
        : dev(d), rayCount(rs.size()),
          wide8Data(anyWide8(variants) ? packWide8(collapseToWideOf<8>(bvh)) : std::vector<gpu::GpuWideNode>{}),
          rays(d, rs.size() * 32, vk::BufferUsageFlagBits::eStorageBuffer),
          nodes(d, bvh.nodes.size() * sizeof(gpu::GpuNode), usage(d)),
          wideNodes(d, wide.size() * sizeof(gpu::GpuWideNode), usage(d)),
          quantizedNodes(d, anyQuantized(variants) ? wide.size() * gpu::QUANTIZED_NODE_TEXELS * sizeof(glm::uvec4) : 16, usage(d)),
          wide8Nodes(d, std::max<std::size_t>(16, wide8Data.size() * sizeof(gpu::GpuWideNode)), usage(d)),
          prims(d, bvh.prims.size() * sizeof(gpu::GpuPrim), usage(d)),
          out(d, rs.size() * sizeof(glm::uvec4), vk::BufferUsageFlagBits::eStorageBuffer) {
        std::vector<glm::vec4> data;
        for (const Ray& r : rs) {
            data.emplace_back(r.o, r.tmin);
            data.emplace_back(r.d, r.tmax);
        }
        rays.upload(data.data(), data.size() * sizeof(glm::vec4));
        nodes.upload(bvh.nodes.data(), bvh.nodes.size() * sizeof(gpu::GpuNode));
        prims.upload(bvh.prims.data(), bvh.prims.size() * sizeof(gpu::GpuPrim));
        wideNodes.upload(wide.data(), wide.size() * sizeof(gpu::GpuWideNode));
        if (anyQuantized(variants)) {
            const std::vector<glm::uvec4> quantized = packWideQuantized(wide);
            quantizedNodes.upload(quantized.data(), quantized.size() * sizeof(glm::uvec4));
        }
        if (!wide8Data.empty()) wide8Nodes.upload(wide8Data.data(), wide8Data.size() * sizeof(gpu::GpuWideNode));
        wide8View = wide8Nodes.texelView();
        quantizedView = quantizedNodes.texelView();
        nodeView = nodes.texelView();
        wideView = wideNodes.texelView();
        primView = prims.texelView();
        for (const Variant& v : variants) {
            ComputePipelineDesc desc;
            desc.spirv = v.spirv;
            desc.bindings = {vk::DescriptorType::eStorageBuffer, v.dataType, v.dataType, vk::DescriptorType::eStorageBuffer};
            desc.pushConstantBytes = v.bda ? sizeof(BdaPush) : 0;
            auto p = std::make_unique<ComputePipeline>(dev, desc);
            p->bindBuffer(0, rays.buffer());
            if (v.dataType == vk::DescriptorType::eUniformTexelBuffer) {
                p->bindTexelView(1, v.wide8 ? *wide8View : v.quantized ? *quantizedView : v.wide ? *wideView : *nodeView);
                p->bindTexelView(2, *primView);
            } else {
                p->bindBuffer(1, v.wide ? wideNodes.buffer() : nodes.buffer());
                p->bindBuffer(2, prims.buffer());
            }
            p->bindBuffer(3, out.buffer());
            pipes.push_back(std::move(p));
            bda.push_back(v.bda);
            push.push_back(BdaPush{v.bda ? (v.wide ? wideNodes.deviceAddress() : nodes.deviceAddress()) : 0,
                                   v.bda ? prims.deviceAddress() : 0});
        }
    }
    static bool anyQuantized(const std::vector<Variant>& variants) {
        return std::any_of(variants.begin(), variants.end(), [](const Variant& v) { return v.quantized; });
    }
    static bool anyWide8(const std::vector<Variant>& variants) {
        return std::any_of(variants.begin(), variants.end(), [](const Variant& v) { return v.wide8; });
    }
    /// The push constants of a BDA variant: node and primitive addresses (uvec2 each in the shader).
    struct BdaPush {
        std::uint64_t nodes, prims;
    };
    std::vector<bool> bda;
    std::vector<BdaPush> push;
    static vk::BufferUsageFlags usage(VulkanDevice& d) {
        vk::BufferUsageFlags u = vk::BufferUsageFlagBits::eUniformTexelBuffer | vk::BufferUsageFlagBits::eStorageBuffer;
        if (d.info().bufferDeviceAddress) u |= vk::BufferUsageFlagBits::eShaderDeviceAddress;
        return u;
    }
    /// Runs variant v once; returns {wall seconds, CPU seconds} and the results in `res`.
    std::pair<double, double> run(std::size_t v, std::vector<glm::uvec4>& res) {
        const auto groups = std::uint32_t((rayCount + 63) / 64);
        const auto t0 = std::chrono::steady_clock::now();
        const double c0 = cpuSeconds();
        dev.submitAndWait([&](vk::raii::CommandBuffer& cmd) {
            pipes[v]->recordDispatch(cmd, groups, 1, bda[v] ? &push[v] : nullptr, bda[v] ? sizeof(BdaPush) : 0);
        });
        const double c1 = cpuSeconds();
        const auto t1 = std::chrono::steady_clock::now();
        res.resize(rayCount);
        out.download(res.data(), res.size() * sizeof(glm::uvec4));
        return {std::chrono::duration<double>(t1 - t0).count(), c1 - c0};
    }
};

/// The box around every shape of the scene (scene/scene.h sceneBounds), in float.
std::pair<glm::vec3, glm::vec3> floatBounds(const Scene& scene) {
    const auto [lo, hi] = sceneBounds(scene);
    return {glm::vec3(lo), glm::vec3(hi)};
}

std::vector<Ray> incoherentRays(const Scene& scene, std::size_t n, std::uint32_t seed) {
    const auto [lo, hi] = floatBounds(scene);
    const glm::vec3 pad = 0.01f * (hi - lo);
    Rng rng(seed);
    std::vector<Ray> rays;
    rays.reserve(n);
    for (std::size_t i = 0; i < n; ++i)
        rays.push_back({rng.inBox(lo + pad, hi - pad), rng.direction(), 1e-4f * glm::length(hi - lo), gpu::VKP_FAR});
    return rays;
}

/// True when primitive `prim` is hit by ray r at exactly the distance whose bits are tBits.
bool primGivesT(const FlatBvh& bvh, const Ray& r, std::uint32_t prim, std::uint32_t tBits) {
    if (prim >= bvh.prims.size()) return false;
    glm::vec2 ab;
    const float t = gpu::intersectPrim(bvh.prims[prim], r.o, r.d, r.tmin, std::min(r.tmax, gpu::VKP_FAR), ab);
    std::uint32_t bits;
    std::memcpy(&bits, &t, sizeof bits);
    return bits == tBits;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

void benchScene(VulkanDevice& dev, const char* label, const Scene& scene) {
    std::vector<Variant> variants = {
        {"texel", std::span<const std::uint32_t>(kBvhTraceSpv, std::size(kBvhTraceSpv)), vk::DescriptorType::eUniformTexelBuffer},
        {"ssbo", std::span<const std::uint32_t>(kBvhTraceSsboSpv, std::size(kBvhTraceSsboSpv)), vk::DescriptorType::eStorageBuffer},
        {"wide4 texel", std::span<const std::uint32_t>(kBvhTraceWideSpv, std::size(kBvhTraceWideSpv)),
         vk::DescriptorType::eUniformTexelBuffer, true},
        {"wide4 unordered", std::span<const std::uint32_t>(kBvhTraceWideUnorderedSpv, std::size(kBvhTraceWideUnorderedSpv)),
         vk::DescriptorType::eUniformTexelBuffer, true},
        {"wide4 recull", std::span<const std::uint32_t>(kBvhTraceWideRecullSpv, std::size(kBvhTraceWideRecullSpv)),
         vk::DescriptorType::eUniformTexelBuffer, true},
        {"wide4 ssbo", std::span<const std::uint32_t>(kBvhTraceWideSsboSpv, std::size(kBvhTraceWideSsboSpv)),
         vk::DescriptorType::eStorageBuffer, true},
        {"wide4 postponed leaves", std::span<const std::uint32_t>(kBvhTraceWidePostponeSpv, std::size(kBvhTraceWidePostponeSpv)),
         vk::DescriptorType::eUniformTexelBuffer, true},
        {"wide4 quantized", std::span<const std::uint32_t>(kBvhTraceWideQuantizedSpv, std::size(kBvhTraceWideQuantizedSpv)),
         vk::DescriptorType::eUniformTexelBuffer, true, false, true},
        {"wide8 texel", std::span<const std::uint32_t>(kBvhTraceWide8Spv, std::size(kBvhTraceWide8Spv)),
         vk::DescriptorType::eUniformTexelBuffer, true, false, false, true},
    };
    if (dev.info().bufferDeviceAddress) {
        variants.push_back({"bda", std::span<const std::uint32_t>(kBvhTraceBdaSpv, std::size(kBvhTraceBdaSpv)),
                            vk::DescriptorType::eUniformTexelBuffer, false, true});
        variants.push_back({"wide4 bda", std::span<const std::uint32_t>(kBvhTraceWideBdaSpv, std::size(kBvhTraceWideBdaSpv)),
                            vk::DescriptorType::eUniformTexelBuffer, true, true});
    } else {
        std::printf("%s: the device has no bufferDeviceAddress: the bda variants are not run\n", dev.info().name.c_str());
    }
    const FlatBvh bvh = buildFlatBvh(scene);
    const std::vector<gpu::GpuWideNode> wide = buildWideNodes(bvh);
    const std::vector<Ray> rays = incoherentRays(scene, envCount("VKP_BENCH_RAYS", 131072), 17);
    LayoutBench bench(dev, bvh, wide, rays, variants);

    // Correctness first: the reference variant against the CPU twin on a subset, then every
    // variant against the reference on every ray.
    std::vector<glm::uvec4> ref, res;
    bench.run(0, ref);
    int cpuMismatches = 0, hits = 0;
    for (std::size_t i = 0; i < std::min<std::size_t>(rays.size(), 4000); ++i) {
        const Ray& r = rays[i];
        const TraceResult c = traceClosestCpu(bvh, r.o, r.d, r.tmin, r.tmax);
        const TraceResult a = traceAnyCpu(bvh, r.o, r.d, r.tmin, r.tmax);
        hits += c.hit;
        float t;
        std::memcpy(&t, &ref[i].x, sizeof t);
        if (std::memcmp(&t, &c.t, sizeof t) != 0 || ref[i].y != c.prim || bool(ref[i].w & 1u) != a.hit) ++cpuMismatches;
    }
    EXPECT_EQ(cpuMismatches, 0) << label << ": texel variant against the CPU twin";
    EXPECT_GT(hits, 1000) << label << ": the rays must hit something";
    for (std::size_t v = 1; v < variants.size(); ++v) {
        bench.run(v, res);
        int mismatches = 0;
        for (std::size_t i = 0; i < rays.size(); ++i) {
            // Same node layout: everything equal (t, primitive, any-hit, pass counts). Other layout:
            // t and any-hit equal; the primitive may differ only in a tie (coplanar quads, e.g. a box
            // standing on the floor), so it must give the same t.
            const bool same = variants[v].wide ? res[i].x == ref[i].x && (res[i].w & 1u) == (ref[i].w & 1u) &&
                                                     (res[i].y == ref[i].y || primGivesT(bvh, rays[i], res[i].y, res[i].x))
                                               : res[i] == ref[i];
            mismatches += !same;
            if (!same && mismatches <= 3)
                std::printf("  ray %zu: ref t %08x prim %u any %u | %s t %08x prim %u any %u\n", i, ref[i].x, ref[i].y,
                            ref[i].w & 1u, variants[v].name, res[i].x, res[i].y, res[i].w & 1u);
        }
        EXPECT_EQ(mismatches, 0) << label << ": variant " << variants[v].name << " differs from texel";
    }
    dev.instance().throwIfValidationMessages("in the BVH layout bench");

    // Interleaved timing rounds.
    const std::size_t rounds = std::max<std::size_t>(1, envCount("VKP_BENCH_ROUNDS", 5));
    std::vector<std::vector<double>> wall(variants.size()), cpu(variants.size()), ratio(variants.size());
    for (std::size_t r = 0; r < rounds; ++r) {
        for (std::size_t v = 0; v < variants.size(); ++v) {
            const auto [w, c] = bench.run(v, res);
            wall[v].push_back(w);
            cpu[v].push_back(c);
        }
        for (std::size_t v = 0; v < variants.size(); ++v) ratio[v].push_back(cpu[0].back() / cpu[v].back());
    }
    const double raysPerRun = 2.0 * double(rays.size());
    std::printf("\n%s: %zu prims, %zu binary nodes, %zu wide nodes, %zu ray slots (closest + any), %zu interleaved rounds\n", label,
                bvh.prims.size(), bvh.nodes.size(), wide.size(), rays.size(), rounds);
    std::printf("| variant | Mrays/s (wall, median) | Mrays/CPU-s (median) | CPU-time speed vs texel: median [min, max] |\n");
    std::printf("|---|---|---|---|\n");
    for (std::size_t v = 0; v < variants.size(); ++v) {
        const auto [lo, hi] = std::minmax_element(ratio[v].begin(), ratio[v].end());
        std::printf("| %s | %.3f | %.3f | %.3f [%.3f, %.3f] |\n", variants[v].name, raysPerRun / median(wall[v]) * 1e-6,
                    raysPerRun / median(cpu[v]) * 1e-6, median(ratio[v]), *lo, *hi);
    }
    std::fflush(stdout);
}

/// Interleaved timing rounds of the first variant of each bench (rounds: VKP_BENCH_ROUNDS): per
/// bench, its CPU seconds per round and its CPU-time speed against bench 0 in the same round.
struct Rounds {
    std::vector<std::vector<double>> cpu, ratio;
};
Rounds timeInterleaved(std::vector<std::unique_ptr<LayoutBench>>& benches) {
    const std::size_t rounds = std::max<std::size_t>(1, envCount("VKP_BENCH_ROUNDS", 5));
    Rounds out{std::vector<std::vector<double>>(benches.size()), std::vector<std::vector<double>>(benches.size())};
    std::vector<glm::uvec4> res;
    for (std::size_t r = 0; r < rounds; ++r) {
        for (std::size_t b = 0; b < benches.size(); ++b) out.cpu[b].push_back(benches[b]->run(0, res).second);
        for (std::size_t b = 0; b < benches.size(); ++b) out.ratio[b].push_back(out.cpu[0].back() / out.cpu[b].back());
    }
    return out;
}

/// Build parameters as a lever (issue 18): the same scene built with several BvhBuildOptions, and
/// with spatial splits (host/bvh/sbvh.h) at two duplication budgets, each traced by the kernels'
/// 4-wide traversal on the same rays, rounds interleaved. Every build must give the same
/// closest-hit distance (bits) and any-hit answer as the default build.
void benchBuildOptions(VulkanDevice& dev, const char* label, const Scene& scene) {
    struct Option {
        const char* name;
        BvhBuildOptions o;
        float sbvhDuplication = -1.0f;  ///< >= 0: buildSbvh with this budget (SbvhOptions::maxDuplication)
    };
    std::vector<Option> options(7);
    options[0].name = "default (leaf <= 4, Ct 1, Ci 1)";
    options[1].name = "leaf <= 8";
    options[1].o.maxLeafSize = 8;
    options[2].name = "leaf <= 2";
    options[2].o.maxLeafSize = 2;
    options[3].name = "leaf <= 8, Ct 2";
    options[3].o.maxLeafSize = 8;
    options[3].o.traversalCost = 2.0f;
    options[4].name = "leaf <= 4, Ct 0.5";
    options[4].o.traversalCost = 0.5f;
    options[5].name = "SBVH, duplication <= 0.3";
    options[5].sbvhDuplication = 0.3f;
    options[6].name = "SBVH, duplication <= 1";
    options[6].sbvhDuplication = 1.0f;
    const Variant wide4 = {"wide4 texel", std::span<const std::uint32_t>(kBvhTraceWideSpv, std::size(kBvhTraceWideSpv)),
                           vk::DescriptorType::eUniformTexelBuffer, true};
    const std::vector<Ray> rays = incoherentRays(scene, envCount("VKP_BENCH_RAYS", 131072), 17);
    std::vector<FlatBvh> bvhs;
    std::vector<std::unique_ptr<LayoutBench>> benches;
    for (const Option& opt : options) {
        if (opt.sbvhDuplication >= 0.0f) {
            SbvhOptions so;
            so.base = opt.o;
            so.maxDuplication = opt.sbvhDuplication;
            FlatBvh flat = flattenBvh(buildSbvh(scene.shapes, so), scene);
            flat.wideNodes = buildWideNodes(flat);
            bvhs.push_back(std::move(flat));
        } else {
            bvhs.push_back(buildFlatBvh(scene, opt.o));
        }
        benches.push_back(std::make_unique<LayoutBench>(dev, bvhs.back(), bvhs.back().wideNodes, rays, std::vector<Variant>{wide4}));
    }
    // Same hits as the default build; passes per ray from each build's first run.
    std::vector<glm::uvec4> ref, res;
    std::vector<double> passes(options.size(), 0.0);
    for (std::size_t b = 0; b < benches.size(); ++b) {
        benches[b]->run(0, res);
        for (const glm::uvec4& x : res) passes[b] += double(x.z) + double(x.w >> 1u);
        if (b == 0) {
            ref = res;
            continue;
        }
        int mismatches = 0;
        for (std::size_t i = 0; i < rays.size(); ++i) mismatches += res[i].x != ref[i].x || (res[i].w & 1u) != (ref[i].w & 1u);
        EXPECT_EQ(mismatches, 0) << label << ": build " << options[b].name << " finds other hits than the default build";
    }
    dev.instance().throwIfValidationMessages("in the BVH build-options bench");
    const Rounds t = timeInterleaved(benches);
    const std::size_t rounds = t.cpu[0].size();
    const std::vector<std::vector<double>>&cpu = t.cpu, &ratio = t.ratio;
    const double raysPerRun = 2.0 * double(rays.size());
    std::printf("\n%s: build options, 4-wide texel traversal, %zu ray slots (closest + any), %zu interleaved rounds\n", label,
                rays.size(), rounds);
    std::printf("| build | primitive references | wide nodes | SAH cost | passes per ray | Mrays/CPU-s (median) | CPU-time speed vs default: median [min, max] |\n");
    std::printf("|---|---|---|---|---|---|---|\n");
    for (std::size_t b = 0; b < options.size(); ++b) {
        const auto [lo, hi] = std::minmax_element(ratio[b].begin(), ratio[b].end());
        std::printf("| %s | %zu | %zu | %.2f | %.1f | %.3f | %.3f [%.3f, %.3f] |\n", options[b].name, bvhs[b].prims.size(),
                    bvhs[b].wideNodes.size(), bvhs[b].stats.sahCost, passes[b] / raysPerRun, raysPerRun / median(cpu[b]) * 1e-6,
                    median(ratio[b]), *lo, *hi);
    }
    std::fflush(stdout);
}

/// A ray's sort key: 5 bits of each direction component and of each origin coordinate (in the
/// scene's box), interleaved bit by bit from the top, direction first: rays of similar direction
/// from nearby origins, which visit the same nodes, get near keys (ray hashing as in Garanzha and
/// Loop 2010, "Fast Ray Sorting and Breadth-First Packet Traversal for GPU Ray Tracing", sec. 3).
/// Measured against the octant then a 30-bit Morton code of the origin: lane use 0.826 against
/// 0.786 sorted globally on cornell-classic, 0.592 against 0.618 on the 1M mesh, speed 1.34x
/// against 1.27x and 1.37x against 1.28x.
std::uint32_t rayKey(const Ray& r, const glm::vec3& lo, const glm::vec3& hi) {
    const glm::vec3 o = glm::clamp((r.o - lo) / glm::max(hi - lo, glm::vec3(1e-30f)), 0.0f, 1.0f) * 31.99f;
    const glm::vec3 d = glm::clamp(r.d * 0.5f + 0.5f, 0.0f, 1.0f) * 31.99f;
    const std::uint32_t c[6] = {std::uint32_t(d.x), std::uint32_t(d.y), std::uint32_t(d.z),
                                std::uint32_t(o.x), std::uint32_t(o.y), std::uint32_t(o.z)};
    std::uint32_t key = 0;
    for (int bit = 4; bit >= 0; --bit)
        for (std::uint32_t a : c) key = (key << 1) | ((a >> bit) & 1u);
    return key;
}

/// Ray reordering as a lever (issue 18): on lavapipe the 8 lanes of a SIMD batch run each loop as
/// long as their busiest lane, so rays that visit the same nodes waste less. The same rays are
/// traced by the 4-wide kernel in their generated (incoherent) order, sorted by rayKey within
/// windows of 64 (what one workgroup could do in shared memory) and of 4096, and sorted globally
/// (what a wavefront renderer's sort pass could do); reported per order: speed against the
/// generated order (CPU time, interleaved rounds) and lane use, the mean of the kernel's own pass
/// counts over 8 x the busiest lane's, per batch of 8 consecutive rays and per loop (closest, any).
/// Every order must give each ray the same hit. The sort's own cost is not included: this is the
/// ceiling of what reordering can buy the traversal.
void benchRayOrder(VulkanDevice& dev, const char* label, const Scene& scene) {
    const Variant wide4 = {"wide4 texel", std::span<const std::uint32_t>(kBvhTraceWideSpv, std::size(kBvhTraceWideSpv)),
                           vk::DescriptorType::eUniformTexelBuffer, true};
    const FlatBvh bvh = buildFlatBvh(scene);
    const std::vector<Ray> rays = incoherentRays(scene, envCount("VKP_BENCH_RAYS", 131072), 17);
    const auto [lo, hi] = floatBounds(scene);
    struct Order {
        const char* name;
        std::size_t window;  ///< sort within windows of this many rays (0: no sort)
        std::vector<std::uint32_t> perm;  ///< slot -> ray
    };
    std::vector<Order> orders = {{"generated (incoherent)", 0, {}}, {"sorted in windows of 64", 64, {}},
                                 {"sorted in windows of 4096", 4096, {}}, {"sorted globally", rays.size(), {}}};
    std::vector<std::uint32_t> keys(rays.size());
    for (std::size_t i = 0; i < rays.size(); ++i) keys[i] = rayKey(rays[i], lo, hi);
    std::vector<std::unique_ptr<LayoutBench>> benches;
    for (Order& o : orders) {
        o.perm.resize(rays.size());
        for (std::size_t i = 0; i < rays.size(); ++i) o.perm[i] = std::uint32_t(i);
        for (std::size_t b = 0; o.window > 0 && b < rays.size(); b += o.window) {
            const auto first = o.perm.begin() + std::ptrdiff_t(b);
            const auto last = o.perm.begin() + std::ptrdiff_t(std::min(rays.size(), b + o.window));
            std::stable_sort(first, last, [&](std::uint32_t x, std::uint32_t y) { return keys[x] < keys[y]; });
        }
        std::vector<Ray> ordered(rays.size());
        for (std::size_t i = 0; i < rays.size(); ++i) ordered[i] = rays[o.perm[i]];
        benches.push_back(std::make_unique<LayoutBench>(dev, bvh, bvh.wideNodes, ordered, std::vector<Variant>{wide4}));
    }
    // Same hits whatever the order; lane use from the first run's pass counts.
    std::vector<glm::uvec4> ref(rays.size()), res;
    std::vector<double> laneUse(orders.size());
    for (std::size_t k = 0; k < orders.size(); ++k) {
        benches[k]->run(0, res);
        double sum = 0.0, busiest = 0.0;
        for (std::size_t b = 0; b < res.size(); b += 8) {
            std::uint32_t maxClosest = 0, maxAny = 0;
            const std::size_t n = std::min<std::size_t>(8, res.size() - b);
            for (std::size_t i = b; i < b + n; ++i) {
                sum += double(res[i].z) + double(res[i].w >> 1u);
                maxClosest = std::max(maxClosest, res[i].z);
                maxAny = std::max(maxAny, res[i].w >> 1u);
            }
            busiest += double(n) * (double(maxClosest) + double(maxAny));
        }
        laneUse[k] = sum / busiest;
        int mismatches = 0;
        for (std::size_t i = 0; i < rays.size(); ++i) {
            const glm::uvec4 hit = res[i];
            glm::uvec4& r = ref[orders[k].perm[i]];
            if (k == 0) r = hit;
            mismatches += k > 0 && (hit.x != r.x || hit.y != r.y || (hit.w & 1u) != (r.w & 1u));
        }
        EXPECT_EQ(mismatches, 0) << label << ": order " << orders[k].name << " finds other hits";
    }
    dev.instance().throwIfValidationMessages("in the ray-order bench");
    const Rounds t = timeInterleaved(benches);
    const std::size_t rounds = t.cpu[0].size();
    const std::vector<std::vector<double>>&cpu = t.cpu, &ratio = t.ratio;
    const double raysPerRun = 2.0 * double(rays.size());
    std::printf("\n%s: ray order, 4-wide texel traversal, %zu ray slots (closest + any), %zu interleaved rounds\n", label,
                rays.size(), rounds);
    std::printf("| order | lane use (mean / busiest of 8) | Mrays/CPU-s (median) | CPU-time speed vs generated: median [min, max] |\n");
    std::printf("|---|---|---|---|\n");
    for (std::size_t k = 0; k < orders.size(); ++k) {
        const auto [mn, mx] = std::minmax_element(ratio[k].begin(), ratio[k].end());
        std::printf("| %s | %.3f | %.3f | %.3f [%.3f, %.3f] |\n", orders[k].name, laneUse[k], raysPerRun / median(cpu[k]) * 1e-6,
                    median(ratio[k]), *mn, *mx);
    }
    std::fflush(stdout);
}

Scene cornellClassic() { return loadSceneJson(scenesDir() / "cornell-classic.json"); }

TEST(BenchBvhLayout, CornellClassic) {
    VKP_REQUIRE_DEVICE(dev);
    benchScene(dev, "cornell-classic", cornellClassic());
}

/// cornell-classic with a sphere mesh of 1,002,528 triangles in its middle.
Scene cornellWithMillionTriangleMesh() {
    Scene scene = cornellClassic();
    const auto [lo, hi] = floatBounds(scene);
    const glm::vec3 center = 0.5f * (lo + hi);
    const float radius = 0.2f * glm::length(hi - lo);
    for (Shape s : sphereMesh(708, 708, radius)) {
        s.p0 += center;
        s.p1 += center;
        s.p2 += center;
        scene.shapes.push_back(s);
    }
    return scene;
}

TEST(BenchBvhLayout, CornellWithMillionTriangleMesh) {
    VKP_REQUIRE_DEVICE(dev);
    const Scene scene = cornellWithMillionTriangleMesh();
    ASSERT_GE(scene.shapes.size(), 1000000u);
    benchScene(dev, "cornell-classic + 1M-triangle mesh", scene);
}

TEST(BenchBvhLayout, RayOrderCornellClassic) {
    VKP_REQUIRE_DEVICE(dev);
    benchRayOrder(dev, "cornell-classic", cornellClassic());
}

TEST(BenchBvhLayout, RayOrderMillionTriangleMesh) {
    VKP_REQUIRE_DEVICE(dev);
    benchRayOrder(dev, "cornell-classic + 1M-triangle mesh", cornellWithMillionTriangleMesh());
}

TEST(BenchBvhLayout, BuildOptionsCornellClassic) {
    VKP_REQUIRE_DEVICE(dev);
    benchBuildOptions(dev, "cornell-classic", cornellClassic());
}

TEST(BenchBvhLayout, BuildOptionsMillionTriangleMesh) {
    VKP_REQUIRE_DEVICE(dev);
    benchBuildOptions(dev, "cornell-classic + 1M-triangle mesh", cornellWithMillionTriangleMesh());
}

}  // namespace
}  // namespace vkp::test
