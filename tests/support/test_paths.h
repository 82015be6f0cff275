// Where tests find their data (set by CMake) and where they may write scratch files.
#pragma once
#include <filesystem>
#include <string>

namespace vkp::test {
std::filesystem::path sourceDir();        ///< the repository root
std::filesystem::path scenesDir();        ///< <repo>/scenes
std::filesystem::path vkpathBinary();     ///< the built vkpath executable
/// A fresh-or-existing scratch folder for one test, created: <build tree>/test-scratch/<name>, or
/// $VKPATH_TEST_TMP/vkpath-tests/<name> when that variable is set.
std::filesystem::path scratchDir(const std::string& testName);
}  // namespace vkp::test
