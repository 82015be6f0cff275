// The vkpath subcommands. Each returns the process exit code; errors are thrown as the types of
// core/errors.h and turned into one line + exit code by main().
#pragma once
#include <chrono>
#include <memory>

#include "cli/args.h"
#include "core/disk_cache.h"

namespace vkp {
int runRender(const CliArgs& args, std::chrono::steady_clock::time_point processStart);
int runInfo(const CliArgs& args);
int runDevices(const CliArgs& args);
/// Says on stderr that signal `signo` came before the render's first sample (nothing is written);
/// returns its exit code (core/interrupt.h exitCodeForSignal).
int stoppedEarly(int signo);
/// `vkpath merge PART... -o OUT`: adds up partial files (render/merge.h) and writes the image.
int runMerge(const CliArgs& args);

/// The kernel cache a render uses (--cache-dir, else core/disk_cache.h defaultCacheDir()), or
/// nullptr for none.
std::shared_ptr<DiskCache> openKernelCache(const CliArgs& args);
/// After the render: one warning line (unless --quiet) if the cache could not store an entry and
/// its folder was chosen (--cache-dir or $VKPATH_CACHE_DIR); the default folder fails silently.
void reportKernelCache(const CliArgs& args, const DiskCache* cache);
}  // namespace vkp
