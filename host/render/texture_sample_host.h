// The one C++ build of shared/texture_sample.h's texSample() for host code and tests: texels are
// read from the buffer gHostTexels points to (a TexturePack's texels). texSample is an inline
// function whose body expands VKP_TEXEL_FETCH, so every translation unit of a program must expand
// it alike (one definition rule): include this header instead of defining the macro elsewhere.
#pragma once
#include <cstdint>
#include <vector>

namespace vkp {
/// The texel buffer texSample reads (set it before sampling; HostTexelsScope sets and restores it).
/// Not thread-safe: one thread samples at a time.
inline const std::vector<std::uint32_t>* gHostTexels = nullptr;
inline std::uint32_t hostTexelFetch(std::uint32_t i) { return gHostTexels->at(i); }

/// Points gHostTexels at `texels` for its lifetime, then restores the previous buffer.
class HostTexelsScope {
public:
    explicit HostTexelsScope(const std::vector<std::uint32_t>& texels) : previous_(gHostTexels) { gHostTexels = &texels; }
    ~HostTexelsScope() { gHostTexels = previous_; }
    HostTexelsScope(const HostTexelsScope&) = delete;
    HostTexelsScope& operator=(const HostTexelsScope&) = delete;

private:
    const std::vector<std::uint32_t>* previous_;
};
}  // namespace vkp

#ifdef VKP_TEXEL_FETCH
#error "texture_sample_host.h defines VKP_TEXEL_FETCH: do not define it elsewhere in C++"
#endif
#define VKP_TEXEL_FETCH(i) ::vkp::hostTexelFetch(i)
#include "shared/texture_sample.h"
