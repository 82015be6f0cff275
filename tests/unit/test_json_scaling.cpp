// JSON loading is linear in the file's size (json_parse.cpp). Not a timing assertion: each case is
// a document large enough that the quadratic loader vkpath had before would need far longer than
// this executable's CTest timeout (60 s per case), while the linear one needs a few seconds.
// Measured on the 2-core development machine, Release (docs/performance.md "Loading a JSON scene"):
//   200000 materials + 200000 spheres  before: 177 s for the materials alone (issue 15)  now: ~3 s
//   1000000 empty objects in an array   before: 3.4 s at 50000, quadratic: ~23 min      now: 0.4 s
//   an object of 1000000 keys           before: 6.1 s at 50000, quadratic: ~40 min      now: 3.6 s
// so a quadratic regression fails by timeout and the linear loader passes with a margin of 3
// (the smallest, the materials) to 40 on either side. The duplicate-key and pointer checks on the
// same large documents keep the messages exact.
#include <gtest/gtest.h>

#include <string>

#include "core/errors.h"
#include "scene/json_reader.h"
#include "scene/scene.h"

namespace {

using namespace vkp;

/// n materials "m0".."m<n-1>" and one sphere per material (a distinct material each).
std::string manyMaterialsAndSpheres(std::size_t n) {
    std::string s = R"({"camera": {"lookfrom": [0,0,10], "lookat": [0,0,0], "vfov": 40, "width": 8, "height": 8}, "materials": {)";
    for (std::size_t i = 0; i < n; ++i) {
        s += (i ? ",\"m" : "\"m") + std::to_string(i) + R"(": {"type": "lambertian", "albedo": [0.5, 0.5, 0.5]})";
    }
    s += R"(}, "objects": [)";
    for (std::size_t i = 0; i < n; ++i) {
        s += (i ? "," : "") + std::string(R"({"type": "sphere", "center": [)") + std::to_string(i % 1000) + ", " +
             std::to_string(i / 1000) + R"(, 0], "radius": 0.4, "material": "m)" + std::to_string(i) + "\"}";
    }
    return s + "]}";
}

TEST(JsonScaling, TwoHundredThousandMaterialsAndSpheres) {
    const std::size_t n = 200000;
    const Scene s = parseSceneJson(manyMaterialsAndSpheres(n), "large.json");
    ASSERT_EQ(s.materials.size(), n);
    ASSERT_EQ(s.shapes.size(), n);
    EXPECT_EQ(s.materials[n - 1].name, "m" + std::to_string(n - 1));
    EXPECT_EQ(s.shapes[n - 1].material, n - 1);  // the last sphere names the last material
}

TEST(JsonScaling, AMillionObjectsInAnArray) {
    const std::size_t n = 1000000;
    std::string text = "[";
    for (std::size_t i = 0; i < n; ++i) text += i ? ",{}" : "{}";
    text += "]";
    const json::Json doc = json::parseDocument(text, "array.json");
    ASSERT_TRUE(doc.is_array());
    EXPECT_EQ(doc.size(), n);
    // The pointer of a problem at the end is still exact.
    text.back() = ',';
    text += R"({"a": 1, "a": 2}])";
    try {
        (void)json::parseDocument(text, "array.json");
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_STREQ(e.what(), ("array.json: /" + std::to_string(n) + "/a: duplicate key").c_str());
    }
}

TEST(JsonScaling, AnObjectOfAMillionKeys) {
    const std::size_t n = 1000000;
    std::string text = "{";
    for (std::size_t i = 0; i < n; ++i) text += (i ? ",\"k" : "\"k") + std::to_string(i) + "\": " + std::to_string(i);
    const json::Json doc = json::parseDocument(text + "}", "keys.json");
    ASSERT_EQ(doc.size(), n);
    EXPECT_EQ(doc.at("k" + std::to_string(n - 1)).get<std::size_t>(), n - 1);
    EXPECT_EQ(doc.begin().key(), "k0");  // file order kept
    // A duplicate far from its first occurrence (found through the hash set).
    try {
        (void)json::parseDocument(text + ", \"k17\": 0}", "keys.json");
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_STREQ(e.what(), "keys.json: /k17: duplicate key");
    }
}

}  // namespace
