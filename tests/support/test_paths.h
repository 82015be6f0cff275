// Where tests find their data (set by CMake; a build copied to another machine, as
// tools/gpu-check.sh runs one, sets VKPATH_SOURCE_DIR and VKPATH_BINARY instead) and where they
// may write scratch files.
#pragma once
#include <filesystem>
#include <string>

namespace vkp::test {
std::filesystem::path sourceDir();        ///< the repository root ($VKPATH_SOURCE_DIR if set)
std::filesystem::path scenesDir();        ///< <repo>/scenes
std::filesystem::path vkpathBinary();     ///< the built vkpath executable ($VKPATH_BINARY if set)
/// A fresh-or-existing scratch folder for one test, created: <build tree>/test-scratch/<name>, or
/// $VKPATH_TEST_TMP/vkpath-tests/<name> when that variable is set.
std::filesystem::path scratchDir(const std::string& testName);
/// The whole content of a file (empty if it cannot be read): for byte-for-byte comparisons.
std::string fileBytes(const std::filesystem::path& path);
}  // namespace vkp::test
