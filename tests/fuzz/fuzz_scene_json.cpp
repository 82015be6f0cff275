// Fuzz target: the JSON scene loader (host/scene/scene_json*.cpp) on arbitrary text. Bad input may
// only end in InputError (one line); anything else (a crash, another exception, a sanitizer report,
// a hang, unbounded memory) is a defect. Files the scene names are read relative to a folder that
// does not exist, so they fail as missing files.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/errors.h"
#include "scene/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    try {
        const vkp::Scene s = vkp::parseSceneJson(std::string_view(reinterpret_cast<const char*>(data), size),
                                                 "/nonexistent-vkpath-fuzz/scene.json");
        (void)s;
    } catch (const vkp::InputError&) {
    }
    return 0;
}
