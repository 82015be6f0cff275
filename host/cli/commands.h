// The vkpath subcommands. Each returns the process exit code; errors are thrown as the types of
// core/errors.h and turned into one line + exit code by main().
#pragma once
#include <chrono>

#include "cli/args.h"

namespace vkp {
int runRender(const CliArgs& args, std::chrono::steady_clock::time_point processStart);
int runInfo(const CliArgs& args);
int runDevices(const CliArgs& args);
/// Says on stderr that signal `signo` came before the render's first sample (nothing is written);
/// returns its exit code (core/interrupt.h exitCodeForSignal).
int stoppedEarly(int signo);
/// `vkpath merge PART... -o OUT`: adds up partial files (render/merge.h) and writes the image.
int runMerge(const CliArgs& args);
}  // namespace vkp
