#include "render/emitter_power.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "render/texture_sample_host.h"

namespace vkp {

namespace {
constexpr double kFloorFraction = 0.01;  // floor of a dark triangle that may emit, x the image mean
constexpr int kMinSubdivision = 2, kMaxSubdivision = 32;

double lum(const glm::vec3& e, const glm::vec4& c) { return luminance709(double(e.x * c.x), double(e.y * c.y), double(e.z * c.z)); }
}  // namespace

EmissionEstimator::EmissionEstimator(const Scene& scene) : scene_(scene) {
    bool anyTextured = false;
    for (const Material& m : scene.materials) anyTextured = anyTextured || (m.emits() && m.pbr.emissiveTexture.valid());
    if (anyTextured) pack_ = packTextures(scene);
    HostTexelsScope texels(pack_.texels);
    materials_.resize(scene.materials.size());
    for (std::size_t i = 0; i < scene.materials.size(); ++i) {
        MaterialTexture& mt = materials_[i];
        mt.emit = kernelMaterial(scene.materials[i]).emit;
        if (!anyTextured) continue;
        const glm::uvec4* rec = &pack_.info.at(1 + kMatTexTexels * i + 2 * kTexSlotEmissive);
        if (rec[1].z == kNoTexture) continue;
        mt.textured = true;
        mt.header = pack_.info.at(pack_.info[0].x + rec[1].z);
        mt.rs = glm::vec4(std::bit_cast<float>(rec[0].x), std::bit_cast<float>(rec[0].y), std::bit_cast<float>(rec[0].z),
                          std::bit_cast<float>(rec[0].w));
        mt.offset = glm::vec2(std::bit_cast<float>(rec[1].x), std::bit_cast<float>(rec[1].y));
        mt.texCoord = rec[1].w;
        for (int c = 0; c < 3; ++c)
            if (mt.emit[c] > 0.0f) mt.emitMask |= 0xffu << (8 * c);
        const std::size_t n = std::size_t(mt.header.y) * mt.header.z;
        const bool srgb = (mt.header.w & gpu::TEXF_SRGB) != 0u;
        double sum = 0.0;
        for (std::size_t k = 0; k < n; ++k) {
            const std::uint32_t t = pack_.texels.at(mt.header.x + k);
            mt.anyTexel = mt.anyTexel || (t & mt.emitMask) != 0u;
            sum += lum(mt.emit, gpu::texDecode(t, srgb));
        }
        mt.imageMean = n > 0 ? sum / double(n) : 0.0;
    }
}

double EmissionEstimator::meanLuminance(std::uint32_t shape) const {
    const Shape& s = scene_.shapes.at(shape);
    const MaterialTexture& mt = materials_.at(s.material);
    if (!(mt.emit.x > 0.0f || mt.emit.y > 0.0f || mt.emit.z > 0.0f)) return 0.0;
    // Where lib/surface.glsl applies the texture: triangles whose attribute record has UVs
    // (packVertexAttributes: the flag and a non-empty UV array); elsewhere emit alone.
    // (The loader refuses a texture on TEXCOORD_1 for a primitive without it.)
    const bool one = mt.texCoord == 1;
    const bool hasUv = s.type == ShapeType::Triangle && s.attributes != Shape::kNoAttributes &&
                       (scene_.triangleVertices.at(s.attributes).flags &
                        (one ? TriangleVertices::kHasUv1 : TriangleVertices::kHasUv)) != 0u &&
                       !(one ? scene_.vertices.uv1 : scene_.vertices.uv).empty();
    if (!mt.textured || !hasUv) return luminance709(mt.emit.x, mt.emit.y, mt.emit.z);
    HostTexelsScope texels(pack_.texels);
    return texturedMean(s, mt);
}

double EmissionEstimator::texturedMean(const Shape& s, const MaterialTexture& mt) const {
    const TriangleVertices& tv = scene_.triangleVertices.at(s.attributes);
    const std::vector<glm::vec2>& set = mt.texCoord == 1 ? scene_.vertices.uv1 : scene_.vertices.uv;
    const glm::vec2 uv[3] = {set.at(tv.v[0]), set.at(tv.v[1]), set.at(tv.v[2])};
    glm::vec2 t[3];
    for (int k = 0; k < 3; ++k) t[k] = gpu::texTransform(uv[k], mt.rs, mt.offset);
    const double w = mt.header.y, h = mt.header.z;
    const double footprint = 0.5 * std::abs(double(t[1].x - t[0].x) * double(t[2].y - t[0].y) -
                                            double(t[2].x - t[0].x) * double(t[1].y - t[0].y)) * w * h;  // texels
    const int k = std::isfinite(footprint)
                      ? std::clamp(int(std::ceil(std::sqrt(std::min(footprint, 1e6)))), kMinSubdivision, kMaxSubdivision)
                      : kMaxSubdivision;
    // Centroids of the k^2 sub-triangles: (i + 1/3, j + 1/3) / k for i + j < k (upright), (i + 2/3,
    // j + 2/3) / k for i + j < k - 1 (inverted); barycentrics (a, b) of corners 1 and 2.
    double sum = 0.0;
    const float inv = 1.0f / float(k);
    for (int i = 0; i < k; ++i)
        for (int j = 0; i + j < k; ++j)
            for (int up = 0; up < 2; ++up) {
                if (up == 1 && i + j >= k - 1) break;
                const float o = up == 0 ? 1.0f / 3.0f : 2.0f / 3.0f;
                const float a = (float(i) + o) * inv, b = (float(j) + o) * inv;
                // As lib/surface.glsl: interpolate the file's UVs, then transform.
                const glm::vec2 p = (1.0f - a - b) * uv[0] + a * uv[1] + b * uv[2];
                sum += lum(mt.emit, gpu::texSample(mt.header, gpu::texTransform(p, mt.rs, mt.offset)));
            }
    const double mean = sum / double(k * k);
    const double floor = kFloorFraction * mt.imageMean;
    if (mean >= floor) return mean;
    return anyEmittingTexel(mt, t, 64.0 + 16.0 * double(k * k)) ? floor : mean;
}

bool EmissionEstimator::anyEmittingTexel(const MaterialTexture& mt, const glm::vec2 t[3], double maxTexels) const {
    if (!mt.anyTexel) return false;
    const int n[2] = {int(mt.header.y), int(mt.header.z)};
    const std::uint32_t mode[2] = {mt.header.w & 3u, (mt.header.w >> 2u) & 3u};
    int lo[2], hi[2];
    for (int axis = 0; axis < 2; ++axis) {
        double a = std::min({t[0][axis], t[1][axis], t[2][axis]}) * n[axis];
        double b = std::max({t[0][axis], t[1][axis], t[2][axis]}) * n[axis];
        if (!std::isfinite(a) || !std::isfinite(b)) return true;  // conservative
        // Texels the lookup reads at texel coordinate x (bilinear: floor(x - 0.5) and one more;
        // nearest: floor(x)) lie in [floor(x) - 1, floor(x) + 1]; one more each side for rounding.
        a = std::floor(a) - 2.0;
        b = std::floor(b) + 2.0;
        if (mode[axis] == gpu::TEXF_WRAP_CLAMP) {
            a = std::clamp(a, 0.0, double(n[axis] - 1));
            b = std::clamp(b, 0.0, double(n[axis] - 1));
        } else {  // periodic: shift into the first period, and a whole period covers every texel
            const double period = (mode[axis] == gpu::TEXF_WRAP_MIRROR ? 2.0 : 1.0) * n[axis];
            if (b - a + 1.0 >= period) {
                a = 0.0;
                b = period - 1.0;
            } else {
                const double shift = period * std::floor(a / period);
                a -= shift;
                b -= shift;
            }
        }
        lo[axis] = int(a);
        hi[axis] = int(b);
    }
    // Bounded work (a sliver's box can be far larger than its footprint): past maxTexels the
    // image's own flag (true here) answers, conservatively.
    const double box = (double(hi[0] - lo[0]) + 1.0) * (double(hi[1] - lo[1]) + 1.0);
    if (box > maxTexels) return true;
    for (int y = lo[1]; y <= hi[1]; ++y) {
        const int ty = gpu::texWrap(y, n[1], mode[1]);
        for (int x = lo[0]; x <= hi[0]; ++x) {
            const int tx = gpu::texWrap(x, n[0], mode[0]);
            if ((pack_.texels.at(mt.header.x + std::size_t(ty) * n[0] + tx) & mt.emitMask) != 0u) return true;
        }
    }
    return false;
}

}  // namespace vkp
