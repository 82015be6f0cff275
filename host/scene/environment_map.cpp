// An equirectangular radiance map read from a file: the environment of a JSON scene ("environment")
// and of `vkpath render --environment` (scene/scene.h readEnvironmentMap).
#include <cmath>

#include "core/errors.h"
#include "core/image_io.h"
#include "scene/scene.h"

namespace vkp {

Environment readEnvironmentMap(const std::filesystem::path& file, float strength, float rotateY) {
    if (!(strength >= 0.0f) || !std::isfinite(strength)) throw InputError("environment strength must be finite and >= 0");
    if (!std::isfinite(rotateY)) throw InputError("environment rotation must be finite");
    Environment env;
    env.file = file;
    env.strength = strength;
    env.rotateY = rotateY;
    try {
        const ImageFormat format = imageFormatFromPath(file);
        if (format == ImageFormat::Png) throw InputError("PNG is display-encoded; use .hdr, .exr or .pfm");
        env.image = readImage(file);
    } catch (const InputError& e) {
        throw InputError(std::string("cannot use environment map: ") + e.what());
    }
    if (env.image.empty()) throw InputError("environment map has no pixels");
    for (float& x : env.image.rgb) {
        if (!std::isfinite(x) || x < 0.0f)
            throw InputError("environment map has a negative, NaN or infinite value (radiance must be finite and >= 0)");
        x *= strength;
        if (!std::isfinite(x)) throw InputError("radiance x strength overflows a float");
    }
    return env;
}

}  // namespace vkp
