// The host build of shared/solid_texture.h over a packed TexturePack (host/render/texture_pack.h),
// reading its texels as lib/solid_texture.glsl reads them on the device. Include it before any
// other header that includes shared/texture_sample.h (its texSample needs VKP_TEXEL_FETCH).
#pragma once
#include "render/texture_pack.h"

namespace vkp::test {
/// The pack the host build reads (set it before calling evalSolidTexture and friends).
inline const TexturePack* gSolidPack = nullptr;
}  // namespace vkp::test

#define VKP_STEX_FETCH(i) (::vkp::test::gSolidPack->info.at(::vkp::test::gSolidPack->info[0].w + (i)))
#define VKP_TEXHEADER_FETCH(h) (::vkp::test::gSolidPack->info.at(::vkp::test::gSolidPack->info[0].x + (h)))
#define VKP_TEXEL_FETCH(i) (::vkp::test::gSolidPack->texels.at(i))
#include "shared/solid_texture.h"
