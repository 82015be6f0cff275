#include "core/huge_pages.h"

#include <cstdlib>

#include <unistd.h>

namespace vkp {

namespace {
constexpr const char* kTunable = "glibc.malloc.hugetlb";

/// The value of `name` in a colon-separated list of name=value pairs (the last one wins), or nullopt.
std::optional<std::string> tunableValue(const std::string& list, const std::string& name) {
    std::optional<std::string> value;
    std::size_t start = 0;
    while (start <= list.size()) {
        std::size_t end = list.find(':', start);
        if (end == std::string::npos) end = list.size();
        const std::string item = list.substr(start, end - start);
        if (item.size() > name.size() && item.compare(0, name.size(), name) == 0 && item[name.size()] == '=')
            value = item.substr(name.size() + 1);
        start = end + 1;
    }
    return value;
}
}  // namespace

std::optional<std::string> tunablesWithHugePages(const char* current) {
    const std::string list = current ? current : "";
    if (tunableValue(list, kTunable)) return std::nullopt;
    return (list.empty() ? std::string() : list + ":") + kTunable + "=1";
}

bool hugePagesRequested() {
    const char* current = std::getenv("GLIBC_TUNABLES");
    const std::optional<std::string> v = tunableValue(current ? current : "", kTunable);
    return v && *v == "1";
}

void reexecWithHugePages(char** argv) {
    // Once only, even where the environment does not survive the exec as set (glibc drops
    // tunables from the environment of set-user-ID programs).
    constexpr const char* kGuard = "VKPATH_REEXECUTED";
    if (std::getenv(kGuard)) {
        unsetenv(kGuard);
        return;
    }
    const char* current = std::getenv("GLIBC_TUNABLES");
    const std::optional<std::string> tunables = tunablesWithHugePages(current);
    if (!tunables || !argv || !argv[0]) return;
    const std::optional<std::string> before = current ? std::optional<std::string>(current) : std::nullopt;
    if (setenv("GLIBC_TUNABLES", tunables->c_str(), 1) == 0 && setenv(kGuard, "1", 1) == 0) execv("/proc/self/exe", argv);
    // Not re-executed (no /proc, say): go on with normal pages and the environment as it was.
    unsetenv(kGuard);
    if (before) setenv("GLIBC_TUNABLES", before->c_str(), 1);
    else unsetenv("GLIBC_TUNABLES");
}

}  // namespace vkp
