// Scenes moved far from the origin or scaled, written as files the loaders read (tests of
// camera-relative space, docs/design.md "Camera-relative space"; docs/accuracy.md "Far from the
// origin"). The move is done on the file's numbers, in double, so the loaders see what a user's
// file far from the origin would contain.
#pragma once
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "test_paths.h"

namespace vkp::test {

inline nlohmann::ordered_json readJsonFile(const std::filesystem::path& file) {
    std::ifstream in(file);
    if (!in) throw std::runtime_error("cannot read " + file.string());
    return nlohmann::ordered_json::parse(in);
}

inline void writeJsonFile(const nlohmann::ordered_json& doc, const std::filesystem::path& file) {
    std::ofstream out(file);
    out << doc.dump();  // nlohmann writes doubles so that they read back exactly
    if (!out) throw std::runtime_error("cannot write " + file.string());
}

/// The JSON scene `src` with its camera and every object scaled by `scale` about the origin,
/// then translated by `t` (world units): lookfrom and lookat are mapped (focus_dist scaled), and
/// every object gets the steps {"scale": scale}, {"translate": t} after its own. Written to
/// scratchDir(name) / "<name>.json"; sphere-free scenes only need a uniform scale.
inline std::filesystem::path movedJsonScene(const std::filesystem::path& src, glm::dvec3 t, double scale,
                                            const std::string& name) {
    nlohmann::ordered_json doc = readJsonFile(src);
    auto map = [&](nlohmann::ordered_json& p) {
        for (int i = 0; i < 3; ++i) p[i] = p[i].get<double>() * scale + t[i];
    };
    map(doc["camera"]["lookfrom"]);
    map(doc["camera"]["lookat"]);
    if (doc["camera"].contains("focus_dist")) doc["camera"]["focus_dist"] = doc["camera"]["focus_dist"].get<double>() * scale;
    for (auto& o : doc["objects"]) {
        nlohmann::ordered_json steps = o.contains("transform") ? o["transform"] : nlohmann::ordered_json::array();
        if (scale != 1.0) steps.push_back({{"scale", scale}});
        steps.push_back({{"translate", {t.x, t.y, t.z}}});
        o["transform"] = steps;
    }
    const std::filesystem::path out = scratchDir(name) / (name + ".json");
    writeJsonFile(doc, out);
    return out;
}

/// The glTF file `src` (.gltf with its buffers and images beside it or embedded) with its scene's
/// root nodes under one new node translated by `t`: the whole file moved, cameras included.
/// Files the .gltf refers to are copied beside the copy. Written to scratchDir(name) / "<name>.gltf".
inline std::filesystem::path movedGltfScene(const std::filesystem::path& src, glm::dvec3 t, const std::string& name) {
    nlohmann::ordered_json doc = readJsonFile(src);
    const std::filesystem::path dir = scratchDir(name);
    for (const char* kind : {"buffers", "images"}) {
        if (!doc.contains(kind)) continue;
        for (const auto& b : doc[kind]) {
            if (!b.contains("uri")) continue;
            const std::string uri = b["uri"].get<std::string>();
            if (uri.rfind("data:", 0) == 0) continue;
            std::filesystem::create_directories((dir / uri).parent_path());
            std::filesystem::copy_file(src.parent_path() / uri, dir / uri, std::filesystem::copy_options::overwrite_existing);
        }
    }
    const std::size_t root = doc["nodes"].size();
    const std::size_t scene = doc.contains("scene") ? doc["scene"].get<std::size_t>() : 0;
    nlohmann::ordered_json node;
    node["name"] = "moved";
    node["translation"] = {t.x, t.y, t.z};
    node["children"] = doc["scenes"][scene]["nodes"];
    doc["nodes"].push_back(node);
    doc["scenes"][scene]["nodes"] = nlohmann::ordered_json::array({root});
    const std::filesystem::path out = dir / (name + ".gltf");
    writeJsonFile(doc, out);
    return out;
}

/// "1e+07 x" style label of a translation for test names and messages.
inline std::string describeMove(glm::dvec3 t, double scale) {
    std::ostringstream s;
    s << "translate (" << t.x << ", " << t.y << ", " << t.z << ") scale " << scale;
    return s.str();
}

}  // namespace vkp::test
