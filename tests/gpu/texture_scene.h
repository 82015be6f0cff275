// Helpers of the device tests on scenes/gltf/textures.gltf and alpha.gltf (tools/gen_gltf_scenes.py):
// quads of size 2 in the plane z = 0, quad i at x in [2.5 i, 2.5 i + 2], y in [0, 2], UV (-0.75,
// -0.75) at the top left and (1.75, 1.75) at the bottom right, seen straight on by a camera whose
// focal plane is z = 0; the C++ build of shared/texture_sample.h reading the packed texels.
#pragma once
#include <bit>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "render/gpu_scene.h"
#include "render/texture_pack.h"
#include "render_helpers.h"
#include "test_gpu_analytic_common.h"

#include "render/texture_sample_host.h"

namespace vkp::test {
/// The texel buffer the C++ texSample reads (set before sampling): the host build's (one
/// definition of texSample per program, render/texture_sample_host.h).
inline const std::vector<std::uint32_t>*& gTexels = ::vkp::gHostTexels;
}  // namespace vkp::test

namespace vkp::test {

/// Where the ray through image point (px, py) (pixel units, as the kernel's jitter) meets z = 0.
inline glm::dvec2 planePoint(const gpu::GpuFrame& f, double px, double py) {
    return glm::dvec2(rayPlanePoint(f, px, py, 0.0));
}

/// Quad index at a plane point (-1: none) and the UV there (as the file sets them).
inline int quadAt(glm::dvec2 p, glm::vec2& uv, int quads) {
    const int i = int(std::floor(p.x / 2.5));
    const double x0 = 2.5 * i;
    if (i < 0 || i >= quads || p.x < x0 || p.x > x0 + 2.0 || p.y < 0.0 || p.y > 2.0) return -1;
    uv = glm::vec2(float(-0.75 + 1.25 * (p.x - x0)), float(-0.75 + 1.25 * (2.0 - p.y)));
    return i;
}

/// One texture slot of material mi as packed for the kernel: header, transform.
struct Slot {
    bool valid = false;
    glm::uvec4 header{0};
    glm::vec4 rs{1, 0, 0, 1};
    glm::vec2 offset{0};
    glm::vec2 uvOf(glm::vec2 uv) const { return gpu::texTransform(uv, rs, offset); }
    /// Texel (x, y) under the wrap modes (nearest), for the footprint test.
    glm::ivec2 texel(glm::vec2 uv) const {
        const glm::vec2 t = uvOf(uv);
        const std::uint32_t ws = header.w & 3u, wt = (header.w >> 2u) & 3u;
        return glm::ivec2(gpu::texWrap(int(std::floor(gpu::texReduce(t.x, ws) * float(header.y))), int(header.y), ws),
                          gpu::texWrap(int(std::floor(gpu::texReduce(t.y, wt) * float(header.z))), int(header.z), wt));
    }
};

inline Slot slotOf(const TexturePack& pack, std::uint32_t mi, std::uint32_t slot) {
    const glm::uvec4* rec = &pack.info[1 + kMatTexTexels * mi + 2 * slot];
    Slot s;
    s.valid = rec[1].z != kNoTexture;
    if (!s.valid) return s;
    s.header = pack.info[pack.info[0].x + rec[1].z];
    s.rs = glm::vec4(std::bit_cast<float>(rec[0].x), std::bit_cast<float>(rec[0].y), std::bit_cast<float>(rec[0].z),
                     std::bit_cast<float>(rec[0].w));
    s.offset = glm::vec2(std::bit_cast<float>(rec[1].x), std::bit_cast<float>(rec[1].y));
    return s;
}

inline std::uint32_t materialNamed(const Scene& scene, const std::string& name) {
    for (std::uint32_t i = 0; i < scene.materials.size(); ++i)
        if (scene.materials[i].name == name) return i;
    ADD_FAILURE() << "no material " << name;
    return 0;
}

using CellOf = std::function<glm::ivec2(glm::vec2)>;  // UV -> the cell it lies in

/// Pixels whose whole footprint (corners pushed out by 0.02 pixel) lies on quad q and inside one
/// cell of every given cell function (cells are convex in the image plane, so the corners decide).
inline std::vector<Pixel> insideCells(const gpu::GpuFrame& f, std::uint32_t width, std::uint32_t height, int quads, int q,
                                      const std::vector<CellOf>& slots) {
    std::vector<Pixel> out;
    for (std::uint32_t y = 0; y < height; ++y)
        for (std::uint32_t x = 0; x < width; ++x) {
            bool ok = true;
            glm::ivec2 first[4];
            int k = 0;
            for (double sx : {-0.52, 0.52})
                for (double sy : {-0.52, 0.52}) {
                    glm::vec2 uv;
                    ok = ok && quadAt(planePoint(f, x + sx, y + sy), uv, quads) == q;
                    for (std::size_t s = 0; ok && s < slots.size(); ++s) {
                        const glm::ivec2 t = slots[s](uv);
                        if (k == 0) first[s] = t;
                        ok = t == first[s];
                    }
                    ++k;
                }
            if (ok) out.push_back({x, y});
        }
    return out;
}

/// ... inside one texel of every slot under nearest filtering (wrapped texels: where wrapping
/// joins two cells, the texel is the same on both, so the value is constant over the union).
inline std::vector<Pixel> insideTexels(const gpu::GpuFrame& f, std::uint32_t width, std::uint32_t height, int quads, int q,
                                       const std::vector<Slot>& slots) {
    std::vector<CellOf> cells;
    for (const Slot& s : slots) cells.push_back([s](glm::vec2 uv) { return s.texel(uv); });
    return insideCells(f, width, height, quads, q, cells);
}

inline glm::vec2 centreUv(const gpu::GpuFrame& f, Pixel p, int quads) {
    glm::vec2 uv(0.0f);
    quadAt(planePoint(f, p.x, p.y), uv, quads);
    return uv;
}

}  // namespace vkp::test
