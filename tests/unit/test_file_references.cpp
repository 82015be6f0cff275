// The files a scene may make vkpath read (scene/file_references.h, docs/design.md "Files a scene
// may read"): a glTF buffer or image uri, a JSON scene's included glTF file or environment map must
// resolve inside the referring file's folder or an --allow-path folder, symbolic links followed.
// Every refusal is one line naming the file, the place and the uri as written.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "core/errors.h"
#include "scene/gltf.h"
#include "scene/scene.h"
#include "input_error.h"
#include "test_paths.h"

namespace {

namespace fs = std::filesystem;
using namespace vkp;

using test::inputErrorOf;

void write(const fs::path& p, const std::string& bytes) {
    fs::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << bytes;
}

/// One triangle whose POSITION is in the external buffer `uri` (36 bytes).
std::string triangleGltf(const std::string& uri) {
    return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0,0,0], "max": [1,1,0]}],
      "bufferViews": [{"buffer": 0, "byteLength": 36}],
      "buffers": [{"uri": ")" + uri + R"(", "byteLength": 36}]})";
}

std::string triangleBin() {
    const float p[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    return std::string(reinterpret_cast<const char*>(p), sizeof p);
}

struct FileReferences : ::testing::Test {
    // A folder per case: CTest may run the cases of this binary at the same time.
    fs::path root = test::scratchDir("file_references") / ::testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::path inner = root / "scene";   // the referring files' folder
    fs::path outer = root / "outside";  // a folder beside it
    void SetUp() override {
        fs::remove_all(inner);
        fs::remove_all(outer);
        write(inner / "tri.bin", triangleBin());
        write(outer / "tri.bin", triangleBin());
        write(inner / "sub" / "tri.bin", triangleBin());
    }
    fs::path gltf(const std::string& uri, const std::string& name = "t.gltf") {
        write(inner / name, triangleGltf(uri));
        return inner / name;
    }
};

TEST_F(FileReferences, GltfBuffersInsideTheFolderAreRead) {
    EXPECT_EQ(loadSceneGltf(gltf("tri.bin")).shapes.size(), 1u);
    EXPECT_EQ(loadSceneGltf(gltf("sub/tri.bin")).shapes.size(), 1u);
    EXPECT_EQ(loadSceneGltf(gltf("sub/../tri.bin")).shapes.size(), 1u);
    EXPECT_EQ(loadSceneGltf(gltf("t%72i.bin")).shapes.size(), 1u);  // %72 is "r"
}

TEST_F(FileReferences, GltfUrisOutsideTheFolderAreRefusedUnlessAllowed) {
    const std::string outside = ": resolves to ";
    for (const std::string uri : {"../outside/tri.bin", "../../../../../../../../etc/hostname", "/etc/hostname",
                                  "file:///etc/hostname", "sub/../../outside/tri.bin"}) {
        const fs::path file = gltf(uri);
        const std::string e = inputErrorOf([&] { loadSceneGltf(file); });
        EXPECT_EQ(e.rfind(file.string() + ": buffer 0: uri \"" + uri + "\"" + outside, 0), 0u) << e;
        EXPECT_NE(e.find("--allow-path"), std::string::npos) << e;
    }
    GltfOptions allow;
    allow.allowPaths = {outer};
    EXPECT_EQ(loadSceneGltf(gltf("../outside/tri.bin"), allow).shapes.size(), 1u);
    EXPECT_EQ(loadSceneGltf(gltf("file://" + (outer / "tri.bin").string()), allow).shapes.size(), 1u);
    // Allowing one folder does not allow its neighbours.
    const std::string e = inputErrorOf([&] { loadSceneGltf(gltf("../../../../../../../../etc/hostname"), allow); });
    EXPECT_NE(e.find(outside), std::string::npos) << e;
}

TEST_F(FileReferences, SymbolicLinksAreFollowedBeforeTheCheck) {
    fs::create_symlink(outer / "tri.bin", inner / "link-out.bin");
    fs::create_symlink(inner / "sub" / "tri.bin", inner / "link-in.bin");
    fs::create_symlink(outer, inner / "dir-out");
    EXPECT_EQ(loadSceneGltf(gltf("link-in.bin")).shapes.size(), 1u);
    for (const std::string uri : {"link-out.bin", "dir-out/tri.bin"}) {
        const std::string e = inputErrorOf([&] { loadSceneGltf(gltf(uri)); });
        EXPECT_NE(e.find("buffer 0: uri \"" + uri + "\": resolves to " + (fs::canonical(outer) / "tri.bin").string()), std::string::npos) << e;
    }
    GltfOptions allow;
    allow.allowPaths = {outer};
    EXPECT_EQ(loadSceneGltf(gltf("link-out.bin"), allow).shapes.size(), 1u);
}

TEST_F(FileReferences, UrisAreQuotedAsWrittenWithTheirPlace) {
    struct Case {
        std::string uri, message;
    };
    for (const Case& c : {Case{"modes%zz.bin", "invalid percent-encoding \"%zz\""}, Case{"x%4", "invalid percent-encoding \"%4\""},
                          Case{"a%00.bin", "contains %00"}, Case{"http://example.com/tri.bin", "a http: URI"},
                          Case{"file://host/tri.bin", "a file: URI must be file:///path"},
                          Case{"missing.bin", "cannot read"}}) {
        const fs::path file = gltf(c.uri);
        const std::string e = inputErrorOf([&] { loadSceneGltf(file); });
        EXPECT_EQ(e.rfind(file.string() + ": buffer 0: uri \"" + c.uri + "\": " + c.message, 0), 0u) << e;
    }
    // An image's place is its index.
    write(inner / "i.gltf", R"({"asset": {"version": "2.0"}, "images": [{"uri": "ok.png"}, {"uri": "/etc/passwd"}]})");
    write(inner / "ok.png", "");
    const std::string e = inputErrorOf([&] { loadSceneGltf(inner / "i.gltf"); });
    EXPECT_EQ(e.rfind((inner / "i.gltf").string() + ": image 1: uri \"/etc/passwd\": resolves to /etc/passwd", 0), 0u) << e;
}

TEST_F(FileReferences, JsonIncludesAndEnvironmentMapsFollowTheSameRule) {
    write(outer / "t.gltf", triangleGltf("tri.bin"));
    write(outer / "sky.pfm", "PF\n1 1\n-1\n" + std::string(12, '\0'));
    const std::string camera = R"("camera": {"lookfrom": [0,0,5], "lookat": [0,0,0], "vfov": 40, "width": 8, "height": 8})";
    write(inner / "inc.json", "{" + camera + R"(, "objects": [{"type": "gltf", "file": "../outside/t.gltf"}]})");
    write(inner / "env.json", "{" + camera + R"(, "objects": [], "environment": {"file": "../outside/sky.pfm"}})");
    const std::string i = inputErrorOf([&] { loadSceneJson(inner / "inc.json"); });
    EXPECT_EQ(i.rfind((inner / "inc.json").string() + ": /objects/0/file: resolves to " + (fs::canonical(outer) / "t.gltf").string(), 0), 0u) << i;
    const std::string e = inputErrorOf([&] { loadSceneJson(inner / "env.json"); });
    EXPECT_EQ(e.rfind((inner / "env.json").string() + ": /environment/file: resolves to ", 0), 0u) << e;
    SceneJsonOptions allow;
    allow.allowPaths = {outer};
    EXPECT_EQ(loadSceneJson(inner / "inc.json", allow).shapes.size(), 1u);
    EXPECT_EQ(loadSceneJson(inner / "env.json", allow).environment.image.width, 1u);
    // The included file's own buffer is beside it: its folder is the one that counts.
    write(inner / "up.json", "{" + camera + R"(, "objects": [{"type": "gltf", "file": "sub/t.gltf"}]})");
    write(inner / "sub" / "t.gltf", triangleGltf("../../outside/tri.bin"));
    const std::string u = inputErrorOf([&] { loadSceneJson(inner / "up.json"); });
    EXPECT_NE(u.find("/objects/0: "), std::string::npos) << u;
    EXPECT_NE(u.find("t.gltf: buffer 0: uri \"../../outside/tri.bin\": resolves to "), std::string::npos) << u;
}

}  // namespace
