#include "test_paths.h"

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>

namespace vkp::test {

namespace {
/// $name when set and not empty (a build copied to another machine, tools/gpu-check.sh), else
/// the path CMake compiled in.
std::filesystem::path fromEnv(const char* name, const char* compiledIn) {
    const char* v = std::getenv(name);
    return (v && *v) ? std::filesystem::path(v) : std::filesystem::path(compiledIn);
}
}  // namespace

std::filesystem::path sourceDir() { return fromEnv("VKPATH_SOURCE_DIR", VKPATH_SOURCE_DIR); }
std::filesystem::path scenesDir() {
    const char* v = std::getenv("VKPATH_SOURCE_DIR");
    return (v && *v) ? std::filesystem::path(v) / "scenes" : std::filesystem::path(VKPATH_SCENES_DIR);
}
std::filesystem::path vkpathBinary() { return fromEnv("VKPATH_BINARY", VKPATH_BINARY); }

std::filesystem::path scratchDir(const std::string& testName) {
    const char* base = std::getenv("VKPATH_TEST_TMP");
    std::filesystem::path dir = base ? std::filesystem::path(base) / "vkpath-tests" : std::filesystem::path(VKPATH_TEST_SCRATCH_DIR);
    dir /= testName;
    std::filesystem::create_directories(dir);
    return dir;
}

std::string fileBytes(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace vkp::test
