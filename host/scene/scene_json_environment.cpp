// "environment" of the JSON scene format: an equirectangular radiance map (scenes/README.md).
#include "core/errors.h"
#include "core/image_io.h"
#include "scene/scene_json_parts.h"

namespace vkp::scenejson {

using json::Range;

Environment readEnvironment(const json::Value& v, const std::filesystem::path& sceneFile, const AllowedPaths& allowed) {
    json::Object o = v.object();
    Environment env;
    const json::Value fileValue = o.required("file");
    const std::string name = fileValue.string();
    if (name.empty()) fileValue.fail("must not be empty");
    env.strength = o.number("strength", Range::atLeast(0.0), 1.0f);
    env.rotateY = o.number("rotate_y", Range::any(), 0.0f);
    o.finish();

    std::string problem;
    (void)resolveReference(sceneFile.parent_path(), name, allowed, problem);
    if (!problem.empty()) fileValue.fail(problem);
    const std::filesystem::path path(name);
    const std::filesystem::path file = path.is_absolute() ? path : sceneFile.parent_path() / path;  // as messages name it
    try {
        const float strength = env.strength, rotateY = env.rotateY;
        env = readEnvironmentMap(file, strength, rotateY);
    } catch (const InputError& e) {
        fileValue.fail(e.what());
    }
    return env;
}

}  // namespace vkp::scenejson
