// farm_image_diff A B [--min-value V] [--max-relative T]: the largest relative difference
// |a - b| / max(|a|, |b|) between two images of the same size (.exr, .pfm, .hdr), over the values
// (each channel of each pixel) where max(|a|, |b|) >= V (default 1e-4; smaller ones are all noise
// of the float rounding). Prints that number, where it is and how many values were compared.
// Exit 0 when both images are read, have the same size, the same non-finite values, at least
// half their values at or above V, and (with --max-relative) the largest difference is <= T;
// 1 otherwise, with one line saying why. The farm test compares a merged render with a
// single-process one by it (tests/farm/test_farm.sh).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "core/image_io.h"

namespace {

int usage() {
    std::fprintf(stderr, "usage: farm_image_diff A B [--min-value V] [--max-relative T]\n");
    return 1;
}

bool parseNumber(const char* text, double& out) {
    char* end = nullptr;
    out = std::strtod(text, &end);
    return end != text && *end == '\0' && std::isfinite(out) && out >= 0;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 3) return usage();
    double minValue = 1e-4, maxRelative = -1;
    for (int i = 3; i < argc; i += 2) {
        const std::string option = argv[i];
        if (i + 1 >= argc) return usage();
        double* target = option == "--min-value" ? &minValue : option == "--max-relative" ? &maxRelative : nullptr;
        if (!target || !parseNumber(argv[i + 1], *target)) return usage();
    }
    try {
        const vkp::Image a = vkp::readImage(argv[1]);
        const vkp::Image b = vkp::readImage(argv[2]);
        if (a.width != b.width || a.height != b.height) {
            std::printf("FAIL: sizes differ: %ux%u and %ux%u\n", a.width, a.height, b.width, b.height);
            return 1;
        }
        double worst = 0, worstA = 0, worstB = 0;
        size_t worstIndex = 0, compared = 0;
        for (size_t i = 0; i < a.rgb.size(); ++i) {
            const double x = a.rgb[i], y = b.rgb[i];
            if (!std::isfinite(x) || !std::isfinite(y)) {
                if (std::isnan(x) && std::isnan(y)) continue;
                if (x == y) continue;  // the same infinity
                std::printf("FAIL: value %zu (pixel %zu, channel %zu) is %g in one image and %g in the other\n", i,
                            i / 3, i % 3, x, y);
                return 1;
            }
            const double scale = std::max(std::fabs(x), std::fabs(y));
            if (scale < minValue) continue;
            ++compared;
            const double relative = std::fabs(x - y) / scale;
            if (relative > worst) worst = relative, worstA = x, worstB = y, worstIndex = i;
        }
        const size_t pixel = worstIndex / 3;
        std::printf("largest relative difference %.3g (pixel %zu,%zu channel %zu: %.9g vs %.9g) over %zu of %zu "
                    "values >= %g\n",
                    worst, pixel % a.width, pixel / a.width, worstIndex % 3, worstA, worstB, compared, a.rgb.size(),
                    minValue);
        if (2 * compared < a.rgb.size()) {
            std::printf("FAIL: fewer than half the values are >= %g: a dark or empty image compares nothing\n", minValue);
            return 1;
        }
        if (maxRelative >= 0 && worst > maxRelative) {
            std::printf("FAIL: %.3g exceeds the tolerance %g\n", worst, maxRelative);
            return 1;
        }
        return 0;
    } catch (const std::exception& e) {
        std::printf("FAIL: %s\n", e.what());
        return 1;
    }
}
