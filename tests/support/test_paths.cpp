#include "test_paths.h"

#include <cstdlib>
#include <string>

namespace vkp::test {

std::filesystem::path sourceDir() { return VKPATH_SOURCE_DIR; }
std::filesystem::path scenesDir() { return VKPATH_SCENES_DIR; }
std::filesystem::path vkpathBinary() { return VKPATH_BINARY; }

std::filesystem::path scratchDir(const std::string& testName) {
    const char* base = std::getenv("VKPATH_TEST_TMP");
    std::filesystem::path dir = base ? std::filesystem::path(base) / "vkpath-tests" : std::filesystem::path(VKPATH_TEST_SCRATCH_DIR);
    dir /= testName;
    std::filesystem::create_directories(dir);
    return dir;
}

}  // namespace vkp::test
