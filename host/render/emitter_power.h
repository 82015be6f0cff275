// The light pick's estimate of how much a shape emits: the mean luminance of its emitted radiance,
// with a glTF emissiveTexture averaged over each triangle's own UV footprint (issue 6).
#pragma once
#include <cstdint>
#include <vector>

#include "render/texture_pack.h"
#include "scene/scene.h"

namespace vkp {

/// Rec. 709 luminance of linear RGB: 0.2126 R + 0.7152 G + 0.0722 B (ITU-R BT.709-6, item 3.2).
inline double luminance709(double r, double g, double b) { return 0.2126 * r + 0.7152 * g + 0.0722 * b; }

/// Estimates, per shape, the mean over its surface of the luminance of the radiance the kernel
/// emits from it (kernelMaterial(m).emit, times the emissive texture where the kernel applies one:
/// a triangle with UVs under a glTF emitter with an emissiveTexture).
///
/// Textured triangles: the texture is evaluated with the kernel's own lookup (shared/
/// texture_sample.h through texture_sample_host.h, on the texels, headers and KHR_texture_transform
/// packTextures() gives the kernel: same wrap modes, filtering, sRGB decoding), the UV interpolated
/// and transformed as lib/surface.glsl does, at the centroids of the k^2 equal sub-triangles of a
/// k-fold subdivision of the triangle (stratified in area), k = ceil(sqrt(footprint in texels))
/// clamped to [2, 32]: about one sample per texel covered, 4 to 1,024 per triangle. Cost
/// O(texels covered + triangles).
///
/// Never 0 where the emission can be non-zero: if the sample mean is below 1 % of the material's
/// mean over its whole image, every texel the lookup can read anywhere on the triangle (its UV
/// bounding box in texels, 2 texels of margin for the bilinear footprint and rounding, wrapped
/// as the kernel wraps) is checked, and if one emits in a channel the factor does not zero, the
/// estimate is raised to that 1 % (a box larger than 64 + 16 x the samples counts as emitting,
/// which bounds the work). So an estimate of 0 means the kernel emits exactly 0 everywhere
/// on the triangle. Only the pick probabilities (the variance) depend on these estimates, never the
/// mean of the image: next-event estimation divides by the probability it picked with, and a
/// triangle of probability 0 emits nothing that bsdf sampling would have to find in its place.
class EmissionEstimator {
public:
    explicit EmissionEstimator(const Scene& scene);
    /// Mean luminance of the emitted radiance over shape `shape` (index into scene.shapes), >= 0;
    /// 0 for a shape whose material does not emit.
    double meanLuminance(std::uint32_t shape) const;

    /// A material's emission as the kernel sees it, with its emissive slot as packed for it.
    struct MaterialTexture {
        glm::vec3 emit{0.0f};       ///< kernelMaterial(m).emit
        bool textured = false;      ///< the kernel multiplies emit by a texture (slot not empty)
        glm::uvec4 header{0};       ///< texture header (shared/texture_sample.h)
        glm::vec4 rs{1, 0, 0, 1};   ///< KHR_texture_transform rotation x scale, as packed
        glm::vec2 offset{0.0f};     ///< KHR_texture_transform offset, as packed
        std::uint32_t texCoord = 0; ///< the UV set it reads: 0 (TEXCOORD_0) or 1 (TEXCOORD_1)
        std::uint32_t emitMask = 0; ///< bytes of a packed texel in channels where emit > 0
        double imageMean = 0.0;     ///< luminance of emit x the image's mean texel (the floor's scale)
        bool anyTexel = false;      ///< some texel emits (through emitMask)
    };

private:
    double texturedMean(const Shape& s, const MaterialTexture& mt) const;
    /// Whether a texel the lookup can read on the triangle whose transformed UVs are t emits; true
    /// (conservatively) when its texel box is larger than maxTexels.
    bool anyEmittingTexel(const MaterialTexture& mt, const glm::vec2 t[3], double maxTexels) const;

    const Scene& scene_;
    TexturePack pack_;
    std::vector<MaterialTexture> materials_;
};

}  // namespace vkp
