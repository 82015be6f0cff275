// Fuzz target: the glTF loader (host/scene/gltf_*.cpp, tinygltf, Draco, meshoptimizer, stb_image
// for embedded PNG/JPEG) on arbitrary bytes, written to a private folder as scene.glb (when they
// start with the GLB magic "glTF") or scene.gltf. Bad input may only end in InputError.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/errors.h"
#include "scene/gltf.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const std::filesystem::path dir = [] {
        const char* tmp = std::getenv("TMPDIR");
        std::filesystem::path d = std::filesystem::path(tmp ? tmp : "/tmp") / ("vkpath-fuzz-gltf-" + std::to_string(::getpid()));
        std::filesystem::create_directories(d);
        return d;
    }();
    const bool glb = size >= 4 && data[0] == 'g' && data[1] == 'l' && data[2] == 'T' && data[3] == 'F';
    const std::filesystem::path file = dir / (glb ? "scene.glb" : "scene.gltf");
    std::ofstream(file, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data), std::streamsize(size));
    try {
        const vkp::Scene s = vkp::loadSceneGltf(file);
        (void)s;
    } catch (const vkp::InputError&) {
    }
    std::filesystem::remove(file);
    return 0;
}
