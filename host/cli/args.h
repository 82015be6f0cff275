// Command-line parsing for `vkpath`. Pure: no files are touched, no device is opened.
#pragma once
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/image_io.h"
#include "render/features.h"

namespace vkp {

enum class Command { Help, Version, Render, Info, Devices };

struct CliArgs {
    Command command = Command::Help;
    std::filesystem::path scene;
    std::vector<std::filesystem::path> outputs;  // -o, repeatable
    std::optional<std::uint32_t> spp, width, height, maxDepth, seed;
    std::optional<std::uint32_t> rouletteDepth;  // --rr-depth
    double timeLimit = 0.0;                      // --time SECONDS (0: none)
    Sampler sampler = Sampler::Mis;
    Sequence sequence = Sequence::Sobol;         // --sequence random|sobol
    LightPick lightPick = LightPick::Power;      // --light-pick power|uniform
    LightSampling lightSampling = LightSampling::Auto;  // --light-sampling auto|solid-angle|area
    float solidAngleMinSize = kSolidAngleMinSize;       // --solid-angle-min SR (auto's switch)
    std::uint32_t workgroupX = 8, workgroupY = 8;  // --workgroup WxH
    bool linearTiles = false;                      // --tile-order linear
    bool fullVariant = false;                    // --variant full
    std::string device;                          // --device N | NAME-SUBSTRING
    bool validate = false;
    double exposure = 0.0;
    std::uint32_t dumpEvery = 0;
    std::filesystem::path dumpDir = "frames";
    std::vector<ImageFormat> dumpFormats{ImageFormat::Png};
    bool quiet = false;
    std::uint32_t samplesPerDispatch = 0;        // 0: automatic
    double adaptiveThreshold = 0.0;              // --adaptive T (0: off)
    std::uint32_t adaptiveMinSpp = 64;           // --adaptive-min-spp N
    std::filesystem::path reference;             ///< --reference: image to measure the error against
    std::filesystem::path errorLog;              ///< --error-log: CSV of the error (needs --reference)
    std::filesystem::path statsJson;             ///< --stats-json: the run's numbers
    std::optional<std::uint32_t> gltfScene;      ///< --gltf-scene N: scene of a .gltf/.glb (default: the file's)
    std::optional<std::uint32_t> camera;         ///< --camera N: camera of a .gltf/.glb (default: its first perspective one)
    bool instancing = true;                      ///< --instancing auto (true) | flatten (false): glTF shared meshes
};

/// Parses argv. Throws InputError("usage: ...") with one line on any bad flag or value.
CliArgs parseArgs(const std::vector<std::string>& args);

/// The text of `vkpath --help`.
const char* usageText();

}  // namespace vkp
