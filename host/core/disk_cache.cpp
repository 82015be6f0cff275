#include "core/disk_cache.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ostream>
#include <vector>

#include "core/atomic_file.h"
#include "core/fnv1a.h"
#include "core/input_file.h"

namespace vkp {
namespace fs = std::filesystem;

namespace {

/// An entry's file: this header, then the payload.
struct EntryHeader {
    char magic[8];          ///< "vkpcache"
    std::uint32_t format;   ///< kFormat
    std::uint32_t headerBytes;  ///< sizeof(EntryHeader)
    char kind[16];          ///< the kind, zero-padded
    std::uint64_t key;
    std::uint64_t payloadBytes;
    std::uint64_t payloadHash;  ///< FNV-1a of the payload
};
static_assert(sizeof(EntryHeader) == 56, "EntryHeader is written as bytes");
constexpr char kMagic[8] = {'v', 'k', 'p', 'c', 'a', 'c', 'h', 'e'};
constexpr std::uint32_t kFormat = 1;

bool validKind(std::string_view kind) {
    if (kind.empty() || kind.size() > sizeof(EntryHeader::kind)) return false;
    return std::all_of(kind.begin(), kind.end(), [](char c) { return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_'; });
}

/// Whether `name` is an entry file of this cache: "<kind>-<16 hex digits>.bin".
bool isEntryName(const std::string& name) {
    const std::size_t dash = name.rfind('-');
    if (dash == std::string::npos || name.size() != dash + 1 + 16 + 4 || name.compare(dash + 17, 4, ".bin") != 0) return false;
    if (!validKind(std::string_view(name).substr(0, dash))) return false;
    return std::all_of(name.begin() + long(dash) + 1, name.begin() + long(dash) + 17,
                       [](char c) { return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'); });
}

/// Whether `name` is a temporary file of an entry being written (core/atomic_file.h's naming).
bool isEntryTempName(const std::string& name) {
    if (name.size() < 2 || name[0] != '.') return false;
    const std::size_t tmp = name.find(".tmp-");
    return tmp != std::string::npos && isEntryName(name.substr(1, tmp - 1));
}

}  // namespace

DiskCache::DiskCache(fs::path dir, std::size_t maxEntries, std::uint64_t maxBytes)
    : dir_(std::move(dir)), maxEntries_(maxEntries), maxBytes_(maxBytes) {}

fs::path DiskCache::entryPath(std::string_view kind, std::uint64_t key) const {
    char hex[20];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(key));
    return dir_ / (std::string(kind) + "-" + hex + ".bin");
}

std::optional<std::string> DiskCache::load(std::string_view kind, std::uint64_t key) {
    auto miss = [&]() -> std::optional<std::string> {
        count(&Counts::misses);
        return std::nullopt;
    };
    if (!validKind(kind)) return miss();
    const fs::path path = entryPath(kind, key);
    std::string bytes;
    try {
        bytes = readInputFile(path, sizeof(EntryHeader) + kMaxPayloadBytes);  // absent, FIFO, device, huge: throws
    } catch (const std::exception&) {
        return miss();
    }
    if (bytes.size() < sizeof(EntryHeader)) return miss();
    EntryHeader h{};
    std::memcpy(&h, bytes.data(), sizeof h);
    char wantKind[sizeof h.kind] = {};
    std::memcpy(wantKind, kind.data(), kind.size());
    if (std::memcmp(h.magic, kMagic, sizeof kMagic) != 0 || h.format != kFormat || h.headerBytes != sizeof h ||
        std::memcmp(h.kind, wantKind, sizeof wantKind) != 0 || h.key != key || h.payloadBytes != bytes.size() - sizeof h)
        return miss();
    std::string payload = bytes.substr(sizeof h);
    if (fnv1a(std::as_bytes(std::span<const char>(payload.data(), payload.size()))) != h.payloadHash) return miss();
    std::error_code ec;
    fs::last_write_time(path, fs::file_time_type::clock::now(), ec);  // recently used: pruned last (errors ignored)
    count(&Counts::hits);
    return payload;
}

bool DiskCache::store(std::string_view kind, std::uint64_t key, std::string_view payload) {
    auto failed = [&](const std::string& why) {
        count(&Counts::failedStores, why);
        return false;
    };
    if (!validKind(kind)) return failed(std::string(kind) + ": not a cache entry kind");
    if (payload.size() > kMaxPayloadBytes) return failed(entryPath(kind, key).string() + ": larger than the cache takes");
    std::error_code ec;
    fs::create_directories(dir_, ec);
    if (ec) return failed(dir_.string() + ": cannot create the folder: " + ec.message());
    EntryHeader h{};
    std::memcpy(h.magic, kMagic, sizeof kMagic);
    h.format = kFormat;
    h.headerBytes = sizeof h;
    std::memcpy(h.kind, kind.data(), kind.size());
    h.key = key;
    h.payloadBytes = payload.size();
    h.payloadHash = fnv1a(std::as_bytes(std::span<const char>(payload.data(), payload.size())));
    try {
        writeFileAtomic(entryPath(kind, key), [&](std::ostream& os) {
            os.write(reinterpret_cast<const char*>(&h), sizeof h);
            os.write(payload.data(), std::streamsize(payload.size()));
        });
    } catch (const std::exception& e) {
        return failed(e.what());
    }
    count(&Counts::stores);
    prune();
    return true;
}

void DiskCache::count(std::uint64_t Counts::*which, const std::string& problem) {
    const std::lock_guard<std::mutex> lock(mutex_);
    ++(counts_.*which);
    if (!problem.empty()) lastProblem_ = problem;
}

DiskCache::Counts DiskCache::counts() const {
    const std::lock_guard<std::mutex> lock(mutex_);
    return counts_;
}

std::string DiskCache::lastProblem() const {
    const std::lock_guard<std::mutex> lock(mutex_);
    return lastProblem_;
}

void DiskCache::prune() {
    struct Entry {
        fs::path path;
        fs::file_time_type time;
        std::uint64_t bytes;
    };
    std::vector<Entry> entries;
    std::error_code ec;
    const auto now = fs::file_time_type::clock::now();
    for (fs::directory_iterator it(dir_, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        const bool entry = isEntryName(name);
        if (!entry && !isEntryTempName(name)) continue;
        std::error_code e2;
        if (!it->is_regular_file(e2)) continue;
        const fs::file_time_type t = it->last_write_time(e2);
        if (e2) continue;
        if (!entry) {  // a temporary file: removed once an hour old (its writer was killed)
            if (now - t > std::chrono::hours(1)) fs::remove(it->path(), e2);
            continue;
        }
        const std::uint64_t bytes = it->file_size(e2);
        if (!e2) entries.push_back({it->path(), t, bytes});
    }
    std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) { return a.time > b.time; });  // newest first
    std::uint64_t total = 0;
    for (std::size_t i = 0; i < entries.size(); ++i) {
        total += entries[i].bytes;
        if (i >= maxEntries_ || total > maxBytes_) fs::remove(entries[i].path, ec);
    }
}

fs::path defaultCacheDir() {
    auto env = [](const char* name) -> std::optional<std::string> {
        const char* v = std::getenv(name);
        return v ? std::optional<std::string>(v) : std::nullopt;
    };
    if (const auto v = env("VKPATH_CACHE_DIR")) return (v->empty() || *v == "none") ? fs::path() : fs::path(*v);
    // XDG Base Directory Specification: relative paths are invalid and ignored.
    if (const auto xdg = env("XDG_CACHE_HOME"); xdg && fs::path(*xdg).is_absolute()) return fs::path(*xdg) / "vkpath";
    if (const auto home = env("HOME"); home && fs::path(*home).is_absolute()) return fs::path(*home) / ".cache" / "vkpath";
    return {};
}

}  // namespace vkp
