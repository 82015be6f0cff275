// Feature images (AOVs, `vkpath render --aov albedo,normal,depth,position,variance,spp`): the
// per-pixel means made from the kernel's AOV sums (shared/aov.h defines what a sample adds) and
// from the accumulation sums, and the named layers they are written as (EXR channels
// "albedo.R", "normal.X", ...; docs/design.md "Feature images" has the exact definitions).
#pragma once
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/image.h"
#include "render/renderer.h"

namespace vkp {

enum class Aov : std::uint32_t { Albedo, Normal, Depth, Position, Emission, Variance, Spp };
/// Every AOV, in the order of their layers.
inline constexpr Aov kAllAovs[] = {Aov::Albedo, Aov::Normal, Aov::Depth, Aov::Position, Aov::Emission, Aov::Variance, Aov::Spp};
/// "albedo", "normal", "depth", "position", "emission", "variance", "spp": the layer's name.
const char* aovName(Aov a);
/// True for the AOVs the kernel gathers (albedo, normal, depth, position, emission); variance and spp come
/// from the accumulation sums.
bool aovNeedsKernel(Aov a);
/// Parses a comma-separated list of AOV names ("albedo,normal"; "all" for every one) into `out`
/// (each once, in kAllAovs order). Returns "" or what is wrong ("unknown AOV 'x' (known: ...)").
std::string parseAovList(const std::string& list, std::vector<Aov>& out);

/// Where the kernel's coordinates are: its camera-relative frame in the scene file's coordinates
/// (Scene::origin), the camera's eye and unit view axis in the kernel's frame.
struct AovFrame {
    glm::dvec3 worldOrigin{0.0};
    glm::vec3 eye{0.0f};
    glm::vec3 viewAxis{0.0f, 0.0f, -1.0f};
};

/// The kernel-gathered feature images, per pixel.
struct FeatureImages {
    Image albedo;    ///< mean albedo over all samples (linear RGB)
    Image normal;    ///< mean unit shading normal over all samples (XYZ in R,G,B; 0 where none)
    Image position;  ///< mean first-hit position over the samples that hit (world units); 0 where none hit
    std::vector<float> depth;  ///< that position's distance along the view axis (world units); +inf where none hit
    std::vector<float> hitFraction;  ///< fraction of the pixel's samples whose camera ray hit something
    std::vector<float> samples;      ///< the samples in the pixel's feature means (0: none)
    Image emission;  ///< mean radiance seen before the first non-specular vertex (shared/aov.h)
    /// Variance of the MEAN of the luminance of radiance - emission (shared/aov.h "indirect"):
    /// the sample variance (n/(n-1) corrected) over all n samples, divided by n; 0 where n < 2.
    /// What the denoiser filters is that part, so its edge-stopping reads this variance.
    std::vector<float> indirectVariance;
};

/// The feature images from the AOV sums (Renderer::readAovSums, RenderState::aov; kAovFloatsPerPixel
/// floats per pixel: running means and counts, shared/aov.h). Pixels without a sample are 0 (depth +inf). Throws std::invalid_argument when
/// `sums` does not hold width x height pixels.
FeatureImages featureImages(std::span<const float> sums, std::uint32_t width, std::uint32_t height, const AovFrame& frame);

/// The layers of `which` for an image's outputs: from `features` (albedo, normal, depth, position;
/// may be null when none of those is asked for) and `sums` (variance: of each pixel's mean, per
/// channel; spp: the samples in each pixel's mean). Channel names: albedo R,G,B; normal X,Y,Z;
/// depth Z; position X,Y,Z; emission R,G,B; variance R,G,B; spp V.
std::vector<ImageLayer> aovLayers(const std::vector<Aov>& which, const FeatureImages* features, const PixelSums& sums);

}  // namespace vkp
