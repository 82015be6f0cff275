// A cache of derived data on disk: one file per entry, "<kind>-<key as 16 hex digits>.bin" in one
// folder. vkpath keeps its kernel cache in it (vk/kernel_cache.h): the specialized SPIR-V of each
// shader variant and the driver's VkPipelineCache data.
//
// The cache is advisory. A missing, unreadable, truncated, corrupted or foreign entry is a miss, a
// write that fails is skipped, and neither is ever an error: a render neither fails nor changes
// because of the cache. Each file carries its kind, key, length and an FNV-1a checksum of its
// payload, all checked on load. Entries are written atomically (core/atomic_file.h), so processes
// sharing the folder (a render farm's nodes on one home directory) see whole entries or none.
// The folder is bounded: after a store, the oldest entries (by modification time; a hit refreshes
// it) beyond maxEntries or maxBytes are removed, and so are temporary files older than an hour
// that a killed writer left. Only files named as this cache names them are ever removed. One
// DiskCache may serve several threads.
#pragma once
#include <cstdint>
#include <filesystem>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>

namespace vkp {

class DiskCache {
public:
    static constexpr std::size_t kDefaultMaxEntries = 64;
    static constexpr std::uint64_t kDefaultMaxBytes = 256ull << 20;
    /// Largest payload stored or loaded, in bytes (a VkPipelineCache of a big pipeline is a few MB).
    static constexpr std::uint64_t kMaxPayloadBytes = 64ull << 20;

    /// A cache in `dir` (created, with its parents, at the first store). `dir` must not be empty.
    explicit DiskCache(std::filesystem::path dir, std::size_t maxEntries = kDefaultMaxEntries,
                       std::uint64_t maxBytes = kDefaultMaxBytes);

    /// The payload stored for (kind, key), or nothing on a miss (absent, not a regular file,
    /// unreadable, or failing any check). `kind`: a short name of [a-z0-9_] (at most 16 characters).
    std::optional<std::string> load(std::string_view kind, std::uint64_t key);
    /// Stores `payload` for (kind, key), replacing an entry there, then bounds the folder. Returns
    /// false (and keeps the reason in lastProblem()) if it could not be written; never throws.
    bool store(std::string_view kind, std::uint64_t key, std::string_view payload);

    const std::filesystem::path& dir() const { return dir_; }
    /// The file that holds (kind, key).
    std::filesystem::path entryPath(std::string_view kind, std::uint64_t key) const;

    struct Counts {
        std::uint64_t hits = 0, misses = 0, stores = 0, failedStores = 0;
    };
    Counts counts() const;
    /// Why the last store failed ("" if none did): "<path>: <reason>".
    std::string lastProblem() const;

private:
    void prune();
    void count(std::uint64_t Counts::*which, const std::string& problem = {});

    mutable std::mutex mutex_;  // counts_ and lastProblem_: devices on several threads may share a cache
    std::filesystem::path dir_;
    std::size_t maxEntries_;
    std::uint64_t maxBytes_;
    Counts counts_;
    std::string lastProblem_;
};

/// The cache folder vkpath uses when none is given: $VKPATH_CACHE_DIR if set (the value "none":
/// no cache), else $XDG_CACHE_HOME/vkpath, else $HOME/.cache/vkpath (XDG Base Directory
/// Specification); empty (no cache) if none of them is set or the one found is not absolute.
std::filesystem::path defaultCacheDir();

}  // namespace vkp
