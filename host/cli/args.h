// Command-line parsing for `vkpath`. Pure: no files are touched, no device is opened.
#pragma once
#include <cstdint>
#include <filesystem>
#include <optional>
#include <utility>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/image_io.h"
#include "render/denoiser.h"
#include "render/render_options.h"
#include "render/session.h"

namespace vkp {

enum class Command { Help, Version, Render, Info, Devices, Merge };

struct CliArgs {
    Command command = Command::Help;
    std::filesystem::path scene;
    /// Overrides of the scene's values (applied to the loaded scene, cli/commands.cpp).
    std::optional<std::uint32_t> spp, width, height, maxDepth, seed;
    std::optional<std::uint32_t> rouletteDepth;  ///< --rr-depth
    RenderOptions render;    ///< how the samples are taken: --sampler ... --adaptive-min-spp
    SessionOptions session;  ///< when to stop and what to write: -o, --time, --exposure, --dump-*, --quiet
    std::string device;      ///< --device N | NAME-SUBSTRING
    bool validate = false;
    std::filesystem::path reference;         ///< --reference: image to measure the error against
    std::filesystem::path errorLog;          ///< --error-log: CSV of the error (needs --reference)
    std::filesystem::path statsJson;         ///< --stats-json: the run's numbers
    std::optional<std::uint32_t> gltfScene;  ///< --gltf-scene N: scene of a .gltf/.glb (default: the file's)
    std::optional<std::uint32_t> camera;     ///< --camera N: camera of a .gltf/.glb (default: its first perspective one)
    bool instancing = true;                  ///< --instancing auto (true) | flatten (false): glTF shared meshes
    bool spatialSplits = false;              ///< --spatial-splits: BVHs with spatial splits (host/bvh/sbvh.h)
    /// --allow-path DIR (repeatable): folders a scene's file references may reach besides the
    /// referring file's own (scene/file_references.h).
    std::vector<std::filesystem::path> allowPaths;
    /// Light for a scene that brings none (or replaces the scene's): --background R,G,B (linear
    /// radiance of escaping rays; replaces the scene's environment), --environment FILE (an
    /// equirectangular .hdr/.exr/.pfm map), --environment-strength S and --environment-rotate DEG
    /// (for that map, or the scene's own when --environment is not given).
    std::optional<glm::vec3> background;
    std::filesystem::path environment;
    std::optional<float> environmentStrength, environmentRotate;
    /// `--resume FILE`: continue the checkpoint FILE (render/accum_file.h) of the same render.
    std::filesystem::path resume;
    /// `--sample-range A:B`: render samples [A, B) of every pixel (B replaces --spp).
    std::optional<std::pair<std::uint32_t, std::uint32_t>> sampleRange;
    /// `vkpath merge PART...`: the partial files to add up (outputs: session.outputs, .partial).
    std::vector<std::filesystem::path> parts;
    /// `--denoise`: write a denoised image beside the raw one (render/denoiser.h).
    bool denoise = false;
    /// `--denoise-filter nlm|atrous`: the denoiser's filter (DenoiseOptions::filter).
    std::optional<DenoiseFilter> denoiseFilter;
    /// `--cache-dir DIR`: the kernel cache's folder (core/disk_cache.h); an empty path: `--cache-dir
    /// none`, no cache; unset: defaultCacheDir() ($VKPATH_CACHE_DIR, $XDG_CACHE_HOME, $HOME).
    std::optional<std::filesystem::path> cacheDir;
};

/// Parses argv. Throws InputError("usage: ...") with one line on any bad flag or value.
CliArgs parseArgs(const std::vector<std::string>& args);

/// The text of `vkpath --help`.
const char* usageText();

}  // namespace vkp
