// Checks of rendered images that the comparisons of two renders make before comparing: two renders
// of a scene that renders nothing (all black, or one colour everywhere, e.g. only a uniform
// background) agree with each other and with anything alike, so such an image must fail the test.
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <string>

#include "core/image.h"

namespace vkp::test {

/// Success when `img` has a non-zero value; the failure names the render (`render`). For the
/// comparisons with a render that is rightly one colour (say so at the call): it still must not be
/// black.
inline ::testing::AssertionResult notAllBlack(const Image& img, const std::string& render) {
    if (img.empty()) return ::testing::AssertionFailure() << "render '" << render << "' has no pixels";
    if (std::all_of(img.rgb.begin(), img.rgb.end(), [](float v) { return v == 0.0f; }))
        return ::testing::AssertionFailure() << "render '" << render << "' is all black (" << img.width << " x "
                                             << img.height << " pixels): a scene that renders nothing cannot agree";
    return ::testing::AssertionSuccess() << "render '" << render << "' is not all black";
}

/// Success when `img` has a non-zero value and at least two pixels of different colours; the
/// failure names the render (`render`) and says what is wrong with it. For the comparisons of two
/// renders: EXPECT_TRUE(litAndNotConstant(image, "name")) on both before comparing them.
inline ::testing::AssertionResult litAndNotConstant(const Image& img, const std::string& render) {
    if (::testing::AssertionResult lit = notAllBlack(img, render); !lit) return lit;
    const float r = img.rgb[0], g = img.rgb[1], b = img.rgb[2];
    bool constant = true;
    for (std::size_t i = 0; constant && i < img.pixelCount(); ++i)
        constant = img.rgb[3 * i] == r && img.rgb[3 * i + 1] == g && img.rgb[3 * i + 2] == b;
    if (constant)
        return ::testing::AssertionFailure() << "render '" << render << "' is one colour (" << r << ", " << g << ", " << b
                                             << ") over all its " << img.width << " x " << img.height
                                             << " pixels: a scene that shows nothing but that cannot agree";
    return ::testing::AssertionSuccess() << "render '" << render << "' is lit and not constant";
}

}  // namespace vkp::test
