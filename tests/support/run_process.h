// Running the vkpath binary from tests: exit code, stdout and stderr.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

namespace vkp::test {

struct ProcessResult {
    int exitCode = -1;
    std::string out, err;
};

/// Runs `program args...` in `cwd` through /bin/sh with `envPrefix` (e.g. "VK_ICD_FILENAMES=/x")
/// before it; every argument is single-quoted.
ProcessResult runProcess(const std::filesystem::path& program, const std::vector<std::string>& args,
                         const std::filesystem::path& cwd, const std::string& envPrefix = "");

/// Number of lines in s (a final line without '\n' counts).
int lineCount(const std::string& s);

}  // namespace vkp::test
