// "environment" of the JSON scene format: an equirectangular radiance map (scenes/README.md).
#include <cmath>

#include "core/errors.h"
#include "core/image_io.h"
#include "scene/scene_json_parts.h"

namespace vkp::scenejson {

using json::Range;

Environment readEnvironment(const json::Value& v, const std::filesystem::path& sceneFile) {
    json::Object o = v.object();
    Environment env;
    const json::Value fileValue = o.required("file");
    const std::string name = fileValue.string();
    if (name.empty()) fileValue.fail("must not be empty");
    env.strength = o.number("strength", Range::atLeast(0.0), 1.0f);
    env.rotateY = o.number("rotate_y", Range::any(), 0.0f);
    o.finish();

    const std::filesystem::path path(name);
    env.file = path.is_absolute() ? path : sceneFile.parent_path() / path;
    try {
        const ImageFormat format = imageFormatFromPath(env.file);
        if (format == ImageFormat::Png) throw InputError("PNG is display-encoded; use .hdr, .exr or .pfm");
        env.image = readImage(env.file);
    } catch (const InputError& e) {
        fileValue.fail(std::string("cannot use environment map: ") + e.what());
    }
    if (env.image.empty()) fileValue.fail("environment map has no pixels");
    for (float& x : env.image.rgb) {
        if (!std::isfinite(x) || x < 0.0f)
            fileValue.fail("environment map has a negative, NaN or infinite value (radiance must be finite and >= 0)");
        x *= env.strength;
        if (!std::isfinite(x)) fileValue.fail("radiance x strength overflows a float");
    }
    return env;
}

}  // namespace vkp::scenejson
