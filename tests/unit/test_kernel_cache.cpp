// The kernel cache without a device: core/disk_cache.h (entries that round-trip; every kind of
// damaged, foreign or special file a miss, never an error or a hang; writes that fail reported
// and not thrown; the folder bounded, and only the cache's own files removed; the default folder
// from the environment), vk/pipeline_cache_data.h (which driver data may be handed back) and
// vk/spirv_specialize.h's key. The device side (a second render hits, a damaged entry renders the
// same image) is test_cli_render's KernelCache* cases.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "core/disk_cache.h"
#include "vk/pipeline_cache_data.h"
#include "vk/spirv_specialize.h"
#include "test_paths.h"

namespace vkp {
namespace {
namespace fs = std::filesystem;

fs::path freshDir(const std::string& name) {
    const fs::path d = test::scratchDir("kernel_cache") / name;
    fs::remove_all(d);
    return d;
}

std::string readAll(const fs::path& p) {
    std::ifstream f(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(f), {});
}

void writeAll(const fs::path& p, const std::string& bytes) {
    std::ofstream f(p, std::ios::binary | std::ios::trunc);
    f.write(bytes.data(), std::streamsize(bytes.size()));
}

TEST(DiskCache, AnEntryRoundTripsAndCountsItsHitsAndMisses) {
    const fs::path dir = freshDir("roundtrip") / "a" / "b";  // parents are created at the first store
    DiskCache c(dir);
    EXPECT_FALSE(c.load("spirv", 42));
    std::string payload(100000, '\0');
    for (std::size_t i = 0; i < payload.size(); ++i) payload[i] = char(i * 7 + 3);
    ASSERT_TRUE(c.store("spirv", 42, payload)) << c.lastProblem();
    EXPECT_TRUE(fs::is_regular_file(c.entryPath("spirv", 42)));
    EXPECT_EQ(c.entryPath("spirv", 42).filename(), "spirv-000000000000002a.bin");
    EXPECT_EQ(c.load("spirv", 42), payload);
    EXPECT_FALSE(c.load("spirv", 43));      // another key
    EXPECT_FALSE(c.load("pipelines", 42));  // another kind
    ASSERT_TRUE(c.store("spirv", 42, "shorter"));  // replaced whole
    EXPECT_EQ(c.load("spirv", 42), "shorter");
    ASSERT_TRUE(c.store("empty", 1, ""));
    EXPECT_EQ(c.load("empty", 1), "");
    EXPECT_EQ(c.counts().hits, 3u);
    EXPECT_EQ(c.counts().misses, 3u);
    EXPECT_EQ(c.counts().stores, 3u);
    EXPECT_EQ(c.counts().failedStores, 0u);
    // A second cache on the folder (another process) sees the entries.
    DiskCache other(dir);
    EXPECT_EQ(other.load("spirv", 42), "shorter");
}

TEST(DiskCache, DamagedOrForeignEntriesAreMisses) {
    const fs::path dir = freshDir("damaged");
    DiskCache c(dir);
    const std::string payload = "0123456789abcdef0123456789abcdef";
    ASSERT_TRUE(c.store("spirv", 7, payload));
    const fs::path p = c.entryPath("spirv", 7);
    const std::string good = readAll(p);
    ASSERT_EQ(good.size(), 56u + payload.size());

    auto missesWith = [&](const std::string& bytes, const char* what) {
        writeAll(p, bytes);
        EXPECT_FALSE(c.load("spirv", 7)) << what;
    };
    for (std::size_t at : {std::size_t(0), std::size_t(9), std::size_t(20), std::size_t(33), std::size_t(41), std::size_t(50),
                           std::size_t(56), good.size() - 1}) {
        std::string bad = good;
        bad[at] = char(bad[at] ^ 0x10);  // the magic, format, kind, key, length, checksum or payload
        missesWith(bad, ("a flipped bit at byte " + std::to_string(at)).c_str());
    }
    missesWith(good.substr(0, good.size() - 1), "truncated payload");
    missesWith(good.substr(0, 30), "truncated header");
    missesWith(good + "x", "a byte too many");
    missesWith("", "empty file");
    missesWith(std::string(4096, '\xff'), "garbage");
    // An entry copied to another key's name (its header names key 7).
    writeAll(p, good);
    fs::copy_file(p, c.entryPath("spirv", 8));
    EXPECT_FALSE(c.load("spirv", 8));
    EXPECT_EQ(c.load("spirv", 7), payload);  // the intact file still loads
}

TEST(DiskCache, SpecialFilesAreMissesWithoutHanging) {
    const fs::path dir = freshDir("special");
    DiskCache c(dir);
    fs::create_directories(dir);
    // A FIFO with no writer: opening it for reading would block forever.
    ASSERT_EQ(::mkfifo(c.entryPath("spirv", 1).c_str(), 0600), 0);
    EXPECT_FALSE(c.load("spirv", 1));
    // A directory where the entry would be: a miss, and a store fails without throwing.
    fs::create_directories(c.entryPath("spirv", 2));
    EXPECT_FALSE(c.load("spirv", 2));
    EXPECT_FALSE(c.store("spirv", 2, "x"));
    EXPECT_NE(c.lastProblem().find("spirv-0000000000000002.bin"), std::string::npos) << c.lastProblem();
    // A symbolic link to /dev/zero (a device that never ends).
    fs::create_symlink("/dev/zero", c.entryPath("spirv", 3));
    EXPECT_FALSE(c.load("spirv", 3));
    // A store over a dangling link replaces the link with an entry.
    fs::create_symlink(dir / "nowhere", c.entryPath("spirv", 4));
    EXPECT_TRUE(c.store("spirv", 4, "four")) << c.lastProblem();
    EXPECT_EQ(c.load("spirv", 4), "four");
    EXPECT_FALSE(fs::exists(dir / "nowhere"));
}

TEST(DiskCache, AFolderThatCannotBeMadeFailsTheStoreNotTheCaller) {
    const fs::path base = freshDir("unwritable");
    fs::create_directories(base);
    writeAll(base / "file", "a regular file");
    DiskCache c(base / "file" / "cache");  // below a regular file: no folder can be made (also as root)
    EXPECT_FALSE(c.load("spirv", 1));
    EXPECT_FALSE(c.store("spirv", 1, "payload"));
    EXPECT_EQ(c.counts().failedStores, 1u);
    EXPECT_NE(c.lastProblem().find("cannot create the folder"), std::string::npos) << c.lastProblem();
    EXPECT_FALSE(c.store("Bad-Kind", 1, "x"));  // kinds are [a-z0-9_]
    EXPECT_FALSE(c.store("spirv", 1, std::string(DiskCache::kMaxPayloadBytes + 1, 'x')));
    EXPECT_EQ(c.counts().failedStores, 3u);
}

TEST(DiskCache, TheFolderIsBoundedAndOnlyItsOwnFilesAreRemoved) {
    const fs::path dir = freshDir("prune");
    DiskCache c(dir, 3, 1u << 20);
    fs::create_directories(dir);
    writeAll(dir / "notes.txt", "the user's");
    writeAll(dir / "spirv-xyz.bin", "not an entry name");
    // A temporary file of a killed writer, two hours old, and one being written now.
    writeAll(dir / ".spirv-00000000000000ff.bin.tmp-123-0", "stale");
    writeAll(dir / ".spirv-00000000000000fe.bin.tmp-124-0", "fresh");
    const auto now = fs::file_time_type::clock::now();
    fs::last_write_time(dir / ".spirv-00000000000000ff.bin.tmp-123-0", now - std::chrono::hours(2));
    for (std::uint64_t k = 1; k <= 3; ++k) {
        ASSERT_TRUE(c.store("spirv", k, "entry " + std::to_string(k)));
        fs::last_write_time(c.entryPath("spirv", k), now - std::chrono::minutes(10 - k));  // 1 oldest
    }
    EXPECT_TRUE(c.load("spirv", 1));  // a hit makes 1 the most recently used
    ASSERT_TRUE(c.store("spirv", 4, "entry 4"));  // four entries: the least recently used (2) goes
    EXPECT_TRUE(fs::exists(c.entryPath("spirv", 1)));
    EXPECT_FALSE(fs::exists(c.entryPath("spirv", 2)));
    EXPECT_TRUE(fs::exists(c.entryPath("spirv", 3)));
    EXPECT_TRUE(fs::exists(c.entryPath("spirv", 4)));
    EXPECT_TRUE(fs::exists(dir / "notes.txt"));
    EXPECT_TRUE(fs::exists(dir / "spirv-xyz.bin"));
    EXPECT_FALSE(fs::exists(dir / ".spirv-00000000000000ff.bin.tmp-123-0"));
    EXPECT_TRUE(fs::exists(dir / ".spirv-00000000000000fe.bin.tmp-124-0"));

    // The byte bound: entries of 600 KB in a folder of 1 MiB keep one.
    const std::string big(600000, 'b');
    ASSERT_TRUE(c.store("big", 1, big));
    ASSERT_TRUE(c.store("big", 2, big));
    std::uint64_t total = 0;
    for (const auto& e : fs::directory_iterator(dir))
        if (e.path().filename().string().rfind("big-", 0) == 0 || e.path().filename().string().rfind("spirv-0", 0) == 0)
            total += e.file_size();
    EXPECT_LE(total, 1u << 20);
    EXPECT_TRUE(fs::exists(c.entryPath("big", 2)));  // the newest stays
    EXPECT_FALSE(fs::exists(c.entryPath("big", 1)));
}

TEST(DiskCache, ThreadsSharingOneCacheCountEveryLookup) {
    const fs::path dir = freshDir("threads");
    DiskCache c(dir, 1000);
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t)
        threads.emplace_back([&c, t] {
            for (std::uint64_t i = 0; i < 50; ++i) {
                const std::uint64_t key = i % 10;  // the threads write and read the same ten entries
                c.store("spirv", key, "payload " + std::to_string(key));
                const std::optional<std::string> got = c.load("spirv", key + 100 * std::uint64_t(t % 2));
                if (got && *got != "payload " + std::to_string(key)) std::abort();  // a torn entry
            }
        });
    for (auto& th : threads) th.join();
    const DiskCache::Counts n = c.counts();
    EXPECT_EQ(n.stores + n.failedStores, 200u);
    EXPECT_EQ(n.failedStores, 0u) << c.lastProblem();
    EXPECT_EQ(n.hits + n.misses, 200u);
    EXPECT_EQ(n.hits, 100u);  // the even threads read the keys they wrote; the odd ones keys never written
    for (std::uint64_t key = 0; key < 10; ++key) EXPECT_EQ(c.load("spirv", key), "payload " + std::to_string(key));
}

/// Sets (or unsets, for nullptr) the variables for the scope of one test.
struct EnvGuard {
    std::vector<std::pair<std::string, std::optional<std::string>>> saved;
    void set(const char* name, const char* value) {
        const char* old = std::getenv(name);
        saved.emplace_back(name, old ? std::optional<std::string>(old) : std::nullopt);
        if (value) setenv(name, value, 1);
        else unsetenv(name);
    }
    ~EnvGuard() {
        for (auto it = saved.rbegin(); it != saved.rend(); ++it) {
            if (it->second) setenv(it->first.c_str(), it->second->c_str(), 1);
            else unsetenv(it->first.c_str());
        }
    }
};

TEST(DiskCache, TheDefaultFolderFollowsTheEnvironment) {
    EnvGuard env;
    env.set("VKPATH_CACHE_DIR", nullptr);
    env.set("XDG_CACHE_HOME", nullptr);
    env.set("HOME", "/home/someone");
    EXPECT_EQ(defaultCacheDir(), fs::path("/home/someone/.cache/vkpath"));
    env.set("XDG_CACHE_HOME", "relative/ignored");  // the XDG specification: relative paths are invalid
    EXPECT_EQ(defaultCacheDir(), fs::path("/home/someone/.cache/vkpath"));
    env.set("XDG_CACHE_HOME", "/var/cache/me");
    EXPECT_EQ(defaultCacheDir(), fs::path("/var/cache/me/vkpath"));
    env.set("VKPATH_CACHE_DIR", "/scratch/k");
    EXPECT_EQ(defaultCacheDir(), fs::path("/scratch/k"));
    env.set("VKPATH_CACHE_DIR", "none");
    EXPECT_TRUE(defaultCacheDir().empty());
    env.set("VKPATH_CACHE_DIR", nullptr);
    env.set("XDG_CACHE_HOME", nullptr);
    env.set("HOME", nullptr);
    EXPECT_TRUE(defaultCacheDir().empty());
}

std::string header(std::uint32_t size, std::uint32_t version, std::uint32_t vendor, std::uint32_t device, const std::uint8_t* uuid) {
    std::string h(32, '\0');
    std::memcpy(h.data(), &size, 4);
    std::memcpy(h.data() + 4, &version, 4);
    std::memcpy(h.data() + 8, &vendor, 4);
    std::memcpy(h.data() + 12, &device, 4);
    std::memcpy(h.data() + 16, uuid, 16);
    return h;
}

std::span<const std::byte> bytesOf(const std::string& s) { return std::as_bytes(std::span<const char>(s.data(), s.size())); }

TEST(PipelineCacheData, OnlyDataOfThisDeviceIsHandedToTheDriver) {
    PipelineCacheIdentity id;
    id.vendorId = 0x10de;
    id.deviceId = 0x2330;
    id.driverVersion = 7;
    for (int i = 0; i < 16; ++i) id.uuid[i] = std::uint8_t(i + 1);
    const std::string ok = header(32, 1, 0x10de, 0x2330, id.uuid) + "pipelines";
    EXPECT_TRUE(pipelineCacheDataFits(bytesOf(ok), id));
    EXPECT_TRUE(pipelineCacheDataHasPipelines(bytesOf(ok)));
    EXPECT_TRUE(pipelineCacheDataFits(bytesOf(header(32, 1, 0x10de, 0x2330, id.uuid)), id));
    EXPECT_FALSE(pipelineCacheDataHasPipelines(bytesOf(header(32, 1, 0x10de, 0x2330, id.uuid))));  // lavapipe's bare header
    EXPECT_FALSE(pipelineCacheDataFits(bytesOf(header(32, 2, 0x10de, 0x2330, id.uuid)), id));       // another header version
    EXPECT_FALSE(pipelineCacheDataFits(bytesOf(header(32, 1, 0x1002, 0x2330, id.uuid)), id));       // another vendor
    EXPECT_FALSE(pipelineCacheDataFits(bytesOf(header(32, 1, 0x10de, 0x2331, id.uuid)), id));       // another device
    std::uint8_t otherUuid[16];
    std::memcpy(otherUuid, id.uuid, 16);
    otherUuid[15] ^= 1;
    EXPECT_FALSE(pipelineCacheDataFits(bytesOf(header(32, 1, 0x10de, 0x2330, otherUuid)), id));  // another driver build
    EXPECT_FALSE(pipelineCacheDataFits(bytesOf(header(16, 1, 0x10de, 0x2330, id.uuid)), id));    // headerSize too small
    EXPECT_FALSE(pipelineCacheDataFits(bytesOf(header(64, 1, 0x10de, 0x2330, id.uuid)), id));    // headerSize past the end
    EXPECT_FALSE(pipelineCacheDataFits(bytesOf(ok.substr(0, 31)), id));
    EXPECT_FALSE(pipelineCacheDataFits({}, id));

    // One entry per device and driver version.
    PipelineCacheIdentity other = id;
    const std::uint64_t key = pipelineCacheKey(id);
    EXPECT_EQ(pipelineCacheKey(other), key);
    other.driverVersion = 8;
    EXPECT_NE(pipelineCacheKey(other), key);
    other = id;
    other.uuid[0] ^= 1;
    EXPECT_NE(pipelineCacheKey(other), key);
    other = id;
    other.deviceId ^= 1;
    EXPECT_NE(pipelineCacheKey(other), key);
}

TEST(SpecializationKey, ChangesWithTheModuleAndEveryValue) {
    const std::vector<std::uint32_t> module = {0x07230203u, 0x00010300u, 0u, 10u, 0u, 1u, 2u, 3u};
    const std::vector<std::uint32_t> values = {1u, 0u, 5u};
    const std::uint64_t k = specializationKey(module, values);
    EXPECT_EQ(specializationKey(module, values), k);
    for (std::size_t i = 0; i < values.size(); ++i) {
        std::vector<std::uint32_t> v = values;
        v[i] ^= 1u;
        EXPECT_NE(specializationKey(module, v), k) << i;
    }
    std::vector<std::uint32_t> m = module;
    m.back() ^= 1u;
    EXPECT_NE(specializationKey(m, values), k);
    // Words moved from the module to the values are another input.
    EXPECT_NE(specializationKey(std::span(module).first(7), std::vector<std::uint32_t>{3u, 1u, 0u, 5u}), k);
    EXPECT_NE(specializationKey(module, std::span(values).first(2)), k);
}

}  // namespace
}  // namespace vkp
