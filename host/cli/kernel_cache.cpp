#include <cstdio>
#include <cstdlib>

#include "cli/commands.h"

namespace vkp {

std::shared_ptr<DiskCache> openKernelCache(const CliArgs& a) {
    const std::filesystem::path dir = a.cacheDir ? *a.cacheDir : defaultCacheDir();
    if (dir.empty()) return nullptr;
    return std::make_shared<DiskCache>(dir);
}

void reportKernelCache(const CliArgs& a, const DiskCache* cache) {
    if (!cache || cache->counts().failedStores == 0 || a.session.quiet) return;
    if (!a.cacheDir && !std::getenv("VKPATH_CACHE_DIR")) return;
    std::fprintf(stderr, "vkpath: warning: the kernel cache could not be written: %s (--cache-dir none turns it off)\n",
                 cache->lastProblem().c_str());
}

}  // namespace vkp
