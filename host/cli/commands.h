// The vkpath subcommands. Each returns the process exit code; errors are thrown as the types of
// core/errors.h and turned into one line + exit code by main().
#pragma once
#include <chrono>

#include "cli/args.h"

namespace vkp {
int runRender(const CliArgs& args, std::chrono::steady_clock::time_point processStart);
int runInfo(const CliArgs& args);
int runDevices(const CliArgs& args);
/// `vkpath merge PART... -o OUT`: adds up partial files (render/merge.h) and writes the image.
int runMerge(const CliArgs& args);
}  // namespace vkp
