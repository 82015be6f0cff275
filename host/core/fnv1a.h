// FNV-1a, 64 bit (Fowler, Noll, Vo): a fingerprint of bytes, not a cryptographic hash. Used for
// the render key (render/render_key.h) and the keys and checksums of the kernel cache
// (core/disk_cache.h).
#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

namespace vkp {

struct Fnv1a {
    std::uint64_t h = 0xcbf29ce484222325ull;
    void add(std::span<const std::byte> bytes) {
        for (std::byte b : bytes) {
            h ^= std::uint64_t(b);
            h *= 0x100000001b3ull;
        }
    }
    /// The value's 8 bytes in the machine's order (little-endian on every supported host).
    void add(std::uint64_t v) { add(std::as_bytes(std::span<const std::uint64_t>(&v, 1))); }
    /// The string's length, then its bytes (so that "ab"+"c" and "a"+"bc" differ).
    void add(std::string_view s) {
        add(std::uint64_t(s.size()));
        add(std::as_bytes(std::span<const char>(s.data(), s.size())));
    }
};

/// The FNV-1a hash of `bytes`.
inline std::uint64_t fnv1a(std::span<const std::byte> bytes) {
    Fnv1a f;
    f.add(bytes);
    return f.h;
}

}  // namespace vkp
