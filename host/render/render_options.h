// How a render takes its samples: every option of `vkpath render` that decides the kernel's
// variant or the samples it adds (the scene and the session's stopping rule and outputs are in
// render/render_job.h). Parsed once by the command line (cli/args.cpp) or set by a test, then
// passed whole: to the packing step (render/gpu_arrays.h), the renderer and the run's stats.
#pragma once
#include <cstdint>
#include <string>

#include "shared/kinds.h"

namespace vkp {

enum class Sampler : std::uint32_t {
    Bsdf = gpu::SAMPLER_BSDF,
    Light = gpu::SAMPLER_LIGHT,
    Mixture = gpu::SAMPLER_MIXTURE,
    Mis = gpu::SAMPLER_MIS
};
const char* samplerName(Sampler s);
/// Every sampler, for tests and benchmarks that must cover them all.
inline constexpr Sampler kAllSamplers[] = {Sampler::Bsdf, Sampler::Light, Sampler::Mixture, Sampler::Mis};
/// "bsdf" | "light" | "mixture" | "mis" -> Sampler; false if unknown.
bool parseSampler(const std::string& name, Sampler& out);

/// Where a sample's random numbers come from (shaders/shared/sample_stream.h): independent hashed
/// random numbers per dimension, or Owen-scrambled Sobol' points (the default).
enum class Sequence : std::uint32_t { Random = gpu::SEQUENCE_RANDOM, Sobol = gpu::SEQUENCE_SOBOL };
const char* sequenceName(Sequence s);
/// "random" | "sobol" -> Sequence; false if unknown.
bool parseSequence(const std::string& name, Sequence& out);

/// How next-event estimation picks an emitter: in proportion to its power (default; alias table,
/// render/light_table.h) or uniformly among the emitters (`--light-pick uniform`, for comparison).
enum class LightPick : std::uint32_t { Power = 0, Uniform = 1 };
const char* lightPickName(LightPick p);
/// "power" | "uniform" -> LightPick; false if unknown.
bool parseLightPick(const std::string& name, LightPick& out);

/// How next-event estimation samples a point on a quad or triangle light: uniformly in the solid
/// angle it subtends (Urena et al. 2013 for rectangles, Arvo 1995 for triangles) or uniformly in
/// area (the book's). `Auto` (default) samples in solid angle only from points where the light
/// looks at least Features::solidAngleMinSize large (shared/rect_sampling.h apparentSize), in area
/// elsewhere; `SolidAngle` wherever the spherical warps are precise; `Area` everywhere (for
/// comparison). `mixture` always samples area, as the book does.
enum class LightSampling : std::uint32_t { SolidAngle = 0, Area = 1, Auto = 2 };
const char* lightSamplingName(LightSampling s);
/// "auto" | "solid-angle" | "area" -> LightSampling; false if unknown.
bool parseLightSampling(const std::string& name, LightSampling& out);

/// Default apparent size (sr: light area / squared distance to its centre) from which `auto`
/// light sampling switches from area to solid-angle sampling. Measured at equal time on the bench
/// scenes (docs/performance.md, "Solid angle or area").
inline constexpr float kSolidAngleMinSize = 0.1f;

struct RenderOptions {
    Sampler sampler = Sampler::Mis;
    Sequence sequence = Sequence::Sobol;                ///< `--sequence`
    LightPick lightPick = LightPick::Power;             ///< how NEE picks an emitter (`--light-pick`)
    LightSampling lightSampling = LightSampling::Auto;  ///< NEE on quads/triangles (`--light-sampling`)
    float solidAngleMinSize = kSolidAngleMinSize;       ///< Auto's switch, sr (`--solid-angle-min`)
    /// Workgroup size of the kernel (x * y invocations, each one pixel; 0x0 = chosen from the
    /// device's subgroup size, render/workgroup.h autoWorkgroup) and the order its tiles are visited
    /// in: scrambled (default; balances lavapipe's threads) or row by row (`--tile-order linear`).
    /// Neither changes the image, only the speed.
    std::uint32_t workgroupX = 0, workgroupY = 0;
    bool linearTiles = false;
    bool fullVariant = false;  ///< compile every feature in (`--variant full`)
    /// Bake the variant's specialization constants into the kernel's SPIR-V before the driver
    /// compiles it (vk/spirv_specialize.h; `--specialize host`, default) or leave them to the
    /// driver (`--specialize driver`). The same image either way; lavapipe compiles the host-
    /// specialized kernel several times faster.
    bool specializeOnHost = true;
    /// Add every sample's feature values (albedo, normal, position: shared/aov.h) to per-pixel sums
    /// (`--aov`); the image's samples are unchanged.
    bool aov = false;
    /// Samples one dispatch adds per pixel; 0 = automatic: as many (up to 32 on a CPU device, 8 on a
    /// GPU: Renderer::maxAutoSamplesPerDispatch) as keep the busiest
    /// invocation at half of lavapipe's loop budget, measured after every submission.
    std::uint32_t samplesPerDispatch = 0;
    /// Pixels one invocation takes, one after the other, in a dispatch that adds fewer samples per
    /// pixel than samplesPerDispatch (a large image, whose submissions hold one sample or few):
    /// 0 = automatic: on a CPU device as many as make up samplesPerDispatch samples, else 1;
    /// N >= 1: N in every dispatch (tests, benchmarks). The image is the same bits either way.
    std::uint32_t pixelsPerInvocation = 0;
    /// Automatic samples per dispatch also keep the slowest dispatch (device timestamps) at about
    /// this many seconds. < 0: Renderer::kTargetDispatchSeconds on a GPU, no time limit on a CPU
    /// device (lavapipe: no watchdog, and fewer, longer dispatches are faster: measured,
    /// docs/performance.md "Dispatch size"); 0: no time limit.
    double targetDispatchSeconds = -1.0;
    /// Adaptive sampling (render/adaptive.h): a pixel stops receiving samples once its estimated
    /// relative standard error is <= this (0 = off: every pixel gets every sample).
    double adaptiveThreshold = 0.0;
    /// Samples every pixel receives before the first adaptive decision.
    std::uint32_t adaptiveMinSpp = 64;
    bool adaptive() const { return adaptiveThreshold > 0.0; }
};

}  // namespace vkp
